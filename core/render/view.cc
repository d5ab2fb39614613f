// Camera geometry from the seed's view state (see view.h for the model).
//
// Design: the view-space camera is fixed (eye at kEyeDistance on +z, looking
// at the origin), so the view state alone decides what is seen, exactly as in
// the seed's viewer where the mouse edits rotation, translation and scale of
// the scene rather than moving an eye.  Inverting the similarity transform
// gives a world-space eye, target and up vector, which is what POV-Ray,
// Rayshade and glTF cameras need.
#include "core/render/view.h"

#include <algorithm>
#include <cmath>

namespace asgard::render {

Eigen::Quaterniond DefaultTilt() {
  const double deg = M_PI / 180.0;
  return Eigen::Quaterniond(Eigen::AngleAxisd(14 * deg, Eigen::Vector3d::UnitX())) *
         Eigen::Quaterniond(Eigen::AngleAxisd(-20 * deg, Eigen::Vector3d::UnitY()));
}

Camera MakeCamera(const ViewState& view, int width, int height) {
  Camera cam;
  cam.width = std::max(1, width);
  cam.height = std::max(1, height);
  const double radius = view.radius > 0 ? view.radius : 1.0;
  const double k = (view.scale > 0 ? view.scale : 1.0) / radius;
  const Eigen::Matrix3d rt = view.rotation.normalized().toRotationMatrix().transpose();
  // p = Rᵀ (v / k − position) + c
  auto to_world = [&](const Eigen::Vector3d& v) -> Eigen::Vector3d {
    return rt * (v / k - view.position) + view.center;
  };
  cam.eye = to_world(Eigen::Vector3d(0, 0, kEyeDistance));
  cam.target = to_world(Eigen::Vector3d::Zero());
  cam.up = (rt * Eigen::Vector3d::UnitY()).normalized();
  // The unit sphere's silhouette seen from distance E has half-angle
  // asin(1/E); fit it (plus 6 %) into the smaller image dimension.
  const double fit = 1.06 * std::tan(std::asin(1.0 / kEyeDistance));
  const double aspect = cam.aspect();
  cam.fov_y = 2 * std::atan(aspect >= 1 ? fit : fit / aspect);
  cam.near = 0.05 * kEyeDistance / k;
  cam.far = (kEyeDistance + 40.0) / k;
  return cam;
}

double Camera::fov_x() const { return 2 * std::atan(std::tan(fov_y / 2) * aspect()); }

Eigen::Matrix4d Camera::ViewMatrix() const {
  const Eigen::Vector3d f = Forward();
  const Eigen::Vector3d s = f.cross(up).normalized();
  const Eigen::Vector3d u = s.cross(f);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Eigen::Matrix4d Camera::ProjectionMatrix() const {
  const double f = 1.0 / std::tan(fov_y / 2);
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = f / aspect();
  p(1, 1) = f;
  p(2, 2) = (far + near) / (near - far);
  p(2, 3) = 2 * far * near / (near - far);
  p(3, 2) = -1;
  return p;
}

Eigen::Vector3d Camera::ToCamera(const Eigen::Vector3d& world) const {
  const Eigen::Vector4d c = ViewMatrix() * world.homogeneous();
  return c.head<3>();
}

Eigen::Vector2d Camera::CameraToPixel(const Eigen::Vector3d& c) const {
  const double f = 1.0 / std::tan(fov_y / 2);
  const double w = c.z() < 0 ? -c.z() : 1e-12;
  const double xn = f / aspect() * c.x() / w;
  const double yn = f * c.y() / w;
  return {(xn + 1) * 0.5 * width, (1 - yn) * 0.5 * height};
}

Eigen::Vector3d Camera::Project(const Eigen::Vector3d& world) const {
  const Eigen::Vector3d c = ToCamera(world);
  const Eigen::Vector2d px = CameraToPixel(c);
  return {px.x(), px.y(), -c.z()};
}

Light DefaultLight(const Camera& camera) {
  Light l;
  l.directional = true;
  l.direction = camera.Forward();
  return l;
}

}  // namespace asgard::render
