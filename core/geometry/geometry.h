// Geometry: convex hulls, mass properties and rotations.
//
// Shapes are unions of convex pieces (hulls of point sets, and spheres).  The
// simulator needs each piece's hull (faces outward), and each body's mass,
// centre of mass and inertia tensor at unit density.
//
//   points ──ComputeHull (qhull)──▶ ConvexHull ──HullMassProperties──▶ MassProperties
//   sphere ─────────────────────────────────────SphereMassProperties─▶ MassProperties
//   pieces ──────────────────────────────────────CombineMassProperties▶ MassProperties
//
// Errors (too few points, all points coplanar or collinear, non-finite input)
// throw GeometryError with a message a user can act on.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace asgard::geometry {

class GeometryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A convex polyhedron.
//   vertices   hull vertices only (interior and duplicate input points removed)
//   triangles  counter-clockwise seen from outside (right-hand normal points out)
//   faces      polygons after merging coplanar triangles, vertex indices in
//              counter-clockwise order seen from outside, with the outward
//              unit normal and plane offset (n·x = d for points on the face)
struct HullFace {
  std::vector<int> vertices;
  Eigen::Vector3d normal;
  double offset = 0.0;
};
struct ConvexHull {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<HullFace> faces;
};

// Computes the convex hull of `points`.  Throws GeometryError when fewer than
// 4 distinct points are given, when the points are (nearly) coplanar, or when
// any coordinate is not finite.
ConvexHull ComputeHull(std::span<const Eigen::Vector3d> points);

// Mass properties at density `density`.
//   inertia is about the centroid, in the input coordinate axes.
struct MassProperties {
  double mass = 0.0;
  double volume = 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

MassProperties HullMassProperties(const ConvexHull& hull, double density = 1.0);
MassProperties SphereMassProperties(const Eigen::Vector3d& center, double radius,
                                    double density = 1.0);
// Sum of pieces (overlaps counted twice), inertia moved to the combined
// centroid with the parallel-axis theorem.
MassProperties CombineMassProperties(std::span<const MassProperties> parts);

// Rotations.  Quaternions are (w, x, y, z), Hamilton convention, rotating body
// vectors into the world: v_W = q ⊗ v_B ⊗ q*.
Eigen::Quaterniond QuaternionFromRotationVector(const Eigen::Vector3d& r);
Eigen::Vector3d RotationVectorFromQuaternion(const Eigen::Quaterniond& q);

// Smallest sphere-ish bound: centre = centroid of vertices, radius = max
// distance to a vertex (used by the broad phase).
struct BoundingSphere {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0.0;
};
BoundingSphere BoundHull(const ConvexHull& hull);

}  // namespace asgard::geometry
