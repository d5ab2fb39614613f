// Contact manifolds: the points where two convex pieces touch.
//
// Design
// ------
// Resting and stacking need every point of a contact, not one: a box on a
// floor is held at four corners, a box on its edge at two.  With the pair's
// normal n (from GJK's closest points, or from MPR's penetration when the
// pieces overlap), the reference face is the face of either piece whose
// outward normal is most parallel to the contact (a's face to n, b's face to
// −n), if it is within kFaceCos of it; the incident face is the other piece's
// face most opposed to the reference normal.  The incident polygon is
// clipped by the reference face's side planes (Sutherland–Hodgman in 3D);
// every clipped point no higher than `margin` above the reference plane
// (plus the pair's own separation) becomes a contact point, placed midway
// between the incident point and its projection on the reference plane,
// with the reference normal and its signed height as the gap.  A vertex
// landing on a face gives one point, an edge two, a face up to eight.
//
// Spheres, and edge–edge contacts (no face parallel to the normal), give the
// single closest-point pair.
//
// Rejected alternatives:
//   * Persistent manifolds built up from one point per query (Bullet's
//     default): needs several queries over time before a box rests on four
//     points, which an event-driven solver does not have.
//   * The patch centre alone (the seed's single impulse point): fine for one
//     impact, but a single resting point cannot hold a box against tipping.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/collide/collide.h"

namespace asgard::collide {
namespace {

constexpr double kFaceCos = 0.9986;  // cos 3°

struct FaceChoice {
  int face = -1;
  double dot = -std::numeric_limits<double>::infinity();
};

// The face of `piece` whose world normal is most aligned with `dir`.
FaceChoice MostAligned(const Piece& piece, const Pose& pose, const Eigen::Vector3d& dir) {
  FaceChoice best;
  const Eigen::Vector3d body = pose.R.transpose() * dir;
  for (size_t f = 0; f < piece.normals.size(); ++f) {
    const double d = piece.normals[f].dot(body);
    if (d > best.dot) {
      best.dot = d;
      best.face = static_cast<int>(f);
    }
  }
  return best;
}

std::vector<Eigen::Vector3d> FacePolygon(const Piece& piece, const Pose& pose, int face) {
  std::vector<Eigen::Vector3d> out;
  for (int v : piece.faces[static_cast<size_t>(face)])
    out.push_back(pose.p + pose.R * piece.vertices[static_cast<size_t>(v)]);
  return out;
}

std::vector<ContactPoint> Single(const DistanceResult& closest, double signed_distance) {
  ContactPoint c;
  c.point = 0.5 * (closest.point_a + closest.point_b);
  c.normal = closest.normal;
  c.gap = signed_distance;
  return {c};
}

}  // namespace

std::vector<ContactPoint> Manifold(const Piece& a, const Pose& pa, const Piece& b, const Pose& pb,
                                   const DistanceResult& closest, double signed_distance,
                                   double margin) {
  if (a.is_sphere || b.is_sphere || a.faces.empty() || b.faces.empty())
    return Single(closest, signed_distance);
  const Eigen::Vector3d n = closest.normal;
  const FaceChoice fa = MostAligned(a, pa, n);
  const FaceChoice fb = MostAligned(b, pb, -n);
  if (std::max(fa.dot, fb.dot) < kFaceCos) return Single(closest, signed_distance);
  const bool ref_is_a = fa.dot >= fb.dot;
  const Piece& ref = ref_is_a ? a : b;
  const Pose& ref_pose = ref_is_a ? pa : pb;
  const Piece& inc = ref_is_a ? b : a;
  const Pose& inc_pose = ref_is_a ? pb : pa;
  const int ref_face = ref_is_a ? fa.face : fb.face;
  const Eigen::Vector3d ref_normal = ref_pose.R * ref.normals[static_cast<size_t>(ref_face)];
  const FaceChoice fi = MostAligned(inc, inc_pose, -ref_normal);
  const std::vector<Eigen::Vector3d> ref_poly = FacePolygon(ref, ref_pose, ref_face);
  std::vector<Eigen::Vector3d> poly = FacePolygon(inc, inc_pose, fi.face);
  // Clip by the side planes of the reference face (inward normals
  // ref_normal × edge for a counter-clockwise face).
  const size_t m = ref_poly.size();
  double size = 0.0;
  for (const auto& p : ref_poly) size = std::max(size, (p - ref_poly[0]).norm());
  const double slack = 1e-12 * size;
  for (size_t i = 0; i < m && !poly.empty(); ++i) {
    const Eigen::Vector3d& p0 = ref_poly[i];
    const Eigen::Vector3d inward = ref_normal.cross(ref_poly[(i + 1) % m] - p0);
    const double length = inward.norm();
    if (!(length > 0.0)) continue;
    const Eigen::Vector3d side = inward / length;
    std::vector<Eigen::Vector3d> out;
    for (size_t j = 0; j < poly.size(); ++j) {
      const Eigen::Vector3d& p = poly[j];
      const Eigen::Vector3d& q = poly[(j + 1) % poly.size()];
      const double sp = (p - p0).dot(side) + slack, sq = (q - p0).dot(side) + slack;
      if (sp >= 0) out.push_back(p);
      if ((sp >= 0) != (sq >= 0)) out.push_back(p + (q - p) * (sp / (sp - sq)));
    }
    poly = std::move(out);
  }
  std::vector<ContactPoint> out;
  const double keep = std::max(signed_distance, 0.0) + margin;
  for (const auto& p : poly) {
    const double gap = (p - ref_poly[0]).dot(ref_normal);
    if (gap > keep) continue;
    ContactPoint c;
    c.point = p - 0.5 * gap * ref_normal;
    c.normal = ref_is_a ? ref_normal : Eigen::Vector3d(-ref_normal);
    c.gap = gap;
    out.push_back(c);
  }
  if (out.empty()) return Single(closest, signed_distance);
  return out;
}

}  // namespace asgard::collide
