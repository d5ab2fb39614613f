// Viewing state, camera and lights (seed 4.1.7, 4.1.8).
//
// The view is the seed's four quantities: a rotation (quaternion), a
// translation, a scale, and the centre of rotation and scaling.  They map a
// world point p to view space
//
//     v = k · (R · (p − c) + position),      k = scale / radius
//
// where `radius` is the framing radius (the scene's bounding sphere, so that
// scale 1 shows the whole scene).  The eye sits on the view-space +z axis at
// distance kEyeDistance, looks down −z with y up, and its field of view fits
// the unit sphere into the smaller image dimension with a small margin.  Every
// output — line drawings, shaded frames, POV-Ray, Rayshade, glTF — derives the
// same world-space perspective Camera from this, so they agree.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "core/render/color.h"

namespace asgard::render {

constexpr double kEyeDistance = 4.0;

struct ViewState {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // scene units, after rotation
  double scale = 1.0;                                  // zoom (1: the framing sphere fits)
  Eigen::Vector3d center = Eigen::Vector3d::Zero();    // of rotation and scaling
  double radius = 1.0;                                 // framing radius, scene units
};

// The default tilt of a framed scene: 14° about x (see a little of the top)
// then 20° about y (a little of the right side), so boxes read as solids.
Eigen::Quaterniond DefaultTilt();

// A perspective camera in world coordinates.
struct Camera {
  Eigen::Vector3d eye, target, up;  // up is a unit vector orthogonal to target − eye
  double fov_y = 0.5;               // vertical field of view, radians
  int width = 640, height = 480;    // image size in pixels
  double near = 0.1, far = 100.0;   // clip distances along the view direction

  double aspect() const { return static_cast<double>(width) / height; }
  double fov_x() const;
  // World → camera coordinates (camera looks down −z, y up), 4×4.
  Eigen::Matrix4d ViewMatrix() const;
  // OpenGL-style projection (camera → clip coordinates).
  Eigen::Matrix4d ProjectionMatrix() const;
  // World point → pixel coordinates (x right, y down, origin top-left) and
  // the distance in front of the eye (≤ 0: behind the eye).
  Eigen::Vector3d Project(const Eigen::Vector3d& world) const;
  Eigen::Vector3d ToCamera(const Eigen::Vector3d& world) const;
  // Camera coordinates (z < 0 in front) → pixel coordinates.
  Eigen::Vector2d CameraToPixel(const Eigen::Vector3d& cam) const;
  Eigen::Vector3d Forward() const { return (target - eye).normalized(); }
};

Camera MakeCamera(const ViewState& view, int width, int height);

struct Light {
  bool directional = true;
  Eigen::Vector3d position = Eigen::Vector3d(0, 0, 10);   // point lights, world
  Eigen::Vector3d direction = Eigen::Vector3d(0, 0, -1);  // directional, world, unit
  Rgb color{1, 1, 1};
  double intensity = 1.0;
};

// Without scene lights: one directional light pointing into the screen.
Light DefaultLight(const Camera& camera);

}  // namespace asgard::render
