// Tests for convex hulls, mass properties and rotation vectors.
#include "core/geometry/geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <span>
#include <string>
#include <vector>

namespace asgard::geometry {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kPi = std::numbers::pi;

// Corners of an axis-aligned box with edge lengths (a, b, c) centred at the origin.
std::vector<Vector3d> BoxCorners(double a, double b, double c) {
  std::vector<Vector3d> corners;
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back((i & 1 ? 0.5 : -0.5) * a, (i & 2 ? 0.5 : -0.5) * b,
                         (i & 4 ? 0.5 : -0.5) * c);
  }
  return corners;
}

Matrix3d BoxInertia(double mass, double a, double b, double c) {
  return Vector3d(mass / 12 * (b * b + c * c), mass / 12 * (a * a + c * c),
                  mass / 12 * (a * a + b * b))
      .asDiagonal();
}

Vector3d TriangleNormal(const ConvexHull& hull, const std::array<int, 3>& t) {
  const Vector3d& a = hull.vertices[t[0]];
  const Vector3d& b = hull.vertices[t[1]];
  const Vector3d& c = hull.vertices[t[2]];
  return (b - a).cross(c - a);
}

Vector3d VertexCentroid(const ConvexHull& hull) {
  Vector3d c = Vector3d::Zero();
  for (const auto& v : hull.vertices) c += v;
  return c / static_cast<double>(hull.vertices.size());
}

// Structural checks every hull must pass: outward triangles and faces,
// counter-clockwise face polygons on their planes, closed triangle mesh,
// every vertex used, and all `points` inside.
void ExpectWellFormedHull(const ConvexHull& hull, const std::vector<Vector3d>& points) {
  const Vector3d inside = VertexCentroid(hull);
  double scale = 0.0;
  for (const auto& v : hull.vertices) scale = std::max(scale, (v - inside).norm());
  const double eps = 1e-9 * scale;

  std::vector<int> used(hull.vertices.size(), 0);
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : hull.triangles) {
    const Vector3d n = TriangleNormal(hull, t);
    ASSERT_GT(n.norm(), 0.0) << "degenerate triangle";
    const Vector3d center = (hull.vertices[t[0]] + hull.vertices[t[1]] + hull.vertices[t[2]]) / 3;
    EXPECT_GT(n.dot(center - inside), 0.0) << "triangle faces inward";
    for (int k = 0; k < 3; ++k) {
      ++used[t[k]];
      ++edges[{t[k], t[(k + 1) % 3]}];
    }
  }
  // Closed, consistently oriented: each directed edge once, its reverse once.
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(edges.count({edge.second, edge.first}), 1u);
  }
  for (int u : used) EXPECT_GT(u, 0) << "vertex not on any triangle";

  for (const auto& face : hull.faces) {
    ASSERT_GE(face.vertices.size(), 3u);
    EXPECT_NEAR(face.normal.norm(), 1.0, 1e-12);
    EXPECT_LT(face.normal.dot(inside), face.offset) << "face normal points inward";
    const size_t n = face.vertices.size();
    for (size_t k = 0; k < n; ++k) {
      const Vector3d& p = hull.vertices[face.vertices[k]];
      EXPECT_NEAR(face.normal.dot(p), face.offset, eps);
      const Vector3d& q = hull.vertices[face.vertices[(k + 1) % n]];
      const Vector3d& r = hull.vertices[face.vertices[(k + 2) % n]];
      EXPECT_GT((q - p).cross(r - q).dot(face.normal), 0.0) << "face not counter-clockwise";
    }
  }
  for (const auto& p : points) {
    for (const auto& face : hull.faces) {
      EXPECT_LE(face.normal.dot(p), face.offset + eps) << "point outside the hull";
    }
  }
}

// The hull of `points`, checked to be well formed and to have the given
// numbers of vertices, faces and triangles.
ConvexHull CountedHull(const std::vector<Vector3d>& points, size_t vertices, size_t faces,
                       size_t triangles) {
  const ConvexHull hull = ComputeHull(points);
  EXPECT_EQ(hull.vertices.size(), vertices);
  EXPECT_EQ(hull.faces.size(), faces);
  EXPECT_EQ(hull.triangles.size(), triangles);
  ExpectWellFormedHull(hull, points);
  return hull;
}

void ExpectMatrixNear(const Matrix3d& actual, const Matrix3d& expected, double relative) {
  const double tolerance = relative * std::max(1.0, expected.norm());
  EXPECT_LE((actual - expected).norm(), tolerance) << "actual:\n"
                                                   << actual << "\nexpected:\n"
                                                   << expected;
}

template <typename F>
std::string ErrorMessage(F&& f) {
  try {
    f();
  } catch (const GeometryError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a GeometryError";
  return {};
}

// ---------------------------------------------------------------------------
// Hulls

TEST(ComputeHull, BoxWithInteriorAndDuplicatePointsHasEightVerticesAndSixQuads) {
  const double a = 2.0, b = 3.0, c = 5.0;
  std::vector<Vector3d> points = BoxCorners(a, b, c);
  points.push_back(points[0]);  // duplicates
  points.push_back(points[5]);
  points.push_back(points[5]);
  points.emplace_back(0.1, -0.2, 0.3);  // interior points
  points.emplace_back(0.0, 0.0, 0.0);
  points.emplace_back(-0.9, 1.4, -2.4);
  points.emplace_back(0.0, 0.0, 2.5);   // centre of the top face
  points.emplace_back(1.0, 0.0, -2.5);  // on a bottom edge
  const ConvexHull hull = CountedHull(points, 8u, 6u, 12u);
  for (const auto& face : hull.faces) EXPECT_EQ(face.vertices.size(), 4u);
  std::set<std::array<double, 3>> corners;
  for (const auto& v : hull.vertices) {
    EXPECT_DOUBLE_EQ(std::abs(v.x()), a / 2);
    EXPECT_DOUBLE_EQ(std::abs(v.y()), b / 2);
    EXPECT_DOUBLE_EQ(std::abs(v.z()), c / 2);
    corners.insert({v.x(), v.y(), v.z()});
  }
  EXPECT_EQ(corners.size(), 8u);
  for (const auto& face : hull.faces) {
    // Axis-aligned unit normals, offsets at the half extents.
    EXPECT_NEAR(face.normal.cwiseAbs().maxCoeff(), 1.0, 1e-15);
    int axis;
    face.normal.cwiseAbs().maxCoeff(&axis);
    EXPECT_NEAR(face.offset, Vector3d(a, b, c)[axis] / 2, 1e-14);
  }

  const double density = 1.5;
  const MassProperties mp = HullMassProperties(hull, density);
  const double volume = a * b * c;
  EXPECT_NEAR(mp.volume, volume, 1e-12 * volume);
  EXPECT_NEAR(mp.mass, density * volume, 1e-12 * volume);
  EXPECT_LE(mp.centroid.norm(), 1e-14);
  ExpectMatrixNear(mp.inertia, BoxInertia(density * volume, a, b, c), 1e-12);
}

TEST(ComputeHull, RegularTetrahedronHasFourTriangularFacesAndAnalyticMassProperties) {
  // Edge length 2√2; volume a³/(6√2) = 8/3, inertia m a²/20 about the centroid.
  const std::vector<Vector3d> points = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  const ConvexHull hull = CountedHull(points, 4u, 4u, 4u);

  const MassProperties mp = HullMassProperties(hull);
  const double edge = 2 * std::sqrt(2.0);
  EXPECT_NEAR(mp.volume, 8.0 / 3.0, 1e-14);
  EXPECT_LE(mp.centroid.norm(), 1e-15);
  ExpectMatrixNear(mp.inertia, Matrix3d::Identity() * mp.mass * edge * edge / 20, 1e-13);
}

TEST(ComputeHull, OctahedronHasSixVerticesAndEightFaces) {
  const double r = 1.5;
  std::vector<Vector3d> points = {{r, 0, 0},  {-r, 0, 0}, {0, r, 0},
                                  {0, -r, 0}, {0, 0, r},  {0, 0, -r}};
  points.emplace_back(0.1, 0.2, 0.3);
  const ConvexHull hull = CountedHull(points, 6u, 8u, 8u);
  for (const auto& face : hull.faces) {
    EXPECT_NEAR(face.offset, r / std::sqrt(3.0), 1e-14);
  }
  // Volume 4r³/3; inertia of the solid octahedron m r²/5 on each axis.
  const MassProperties mp = HullMassProperties(hull);
  EXPECT_NEAR(mp.volume, 4 * r * r * r / 3, 1e-13);
  ExpectMatrixNear(mp.inertia, Matrix3d::Identity() * mp.mass * r * r / 5, 1e-13);
}

TEST(ComputeHull, RandomPointCloudHullContainsEveryPoint) {
  std::mt19937 rng(12345);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<Vector3d> points;
    for (int i = 0; i < 500; ++i) {
      points.emplace_back(gauss(rng), 2 * gauss(rng), 0.5 * gauss(rng));
    }
    const ConvexHull hull = ComputeHull(points);
    EXPECT_GE(hull.vertices.size(), 4u);
    EXPECT_LT(hull.vertices.size(), points.size());
    ExpectWellFormedHull(hull, points);
    // Euler's formula for a triangulated sphere: F = 2V − 4.
    EXPECT_EQ(hull.triangles.size(), 2 * hull.vertices.size() - 4);
    // Every hull vertex is one of the input points.
    for (const auto& v : hull.vertices) {
      bool found = false;
      for (const auto& p : points) found = found || p == v;
      EXPECT_TRUE(found);
    }
    const MassProperties mp = HullMassProperties(hull);
    EXPECT_GT(mp.volume, 0.0);
    // The inertia tensor is symmetric positive definite and satisfies the
    // triangle inequality of principal moments.
    Eigen::SelfAdjointEigenSolver<Matrix3d> solver(mp.inertia);
    const Vector3d moments = solver.eigenvalues();
    EXPECT_GT(moments.minCoeff(), 0.0);
    EXPECT_LE(moments[2], moments[0] + moments[1] + 1e-12 * moments[2]);
  }
}

TEST(ComputeHull, RotatedAndTranslatedBoxInertiaTransformsAsRotationSandwich) {
  const double a = 1.0, b = 2.0, c = 0.5;
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Vector3d translation(10.0, -3.0, 7.5);
  std::vector<Vector3d> points;
  for (const auto& p : BoxCorners(a, b, c)) points.push_back(rotation * p + translation);
  points.push_back(translation);  // interior

  const ConvexHull hull = CountedHull(points, 8u, 6u, 12u);

  const MassProperties mp = HullMassProperties(hull, 2.0);
  const double mass = 2.0 * a * b * c;
  EXPECT_NEAR(mp.mass, mass, 1e-12 * mass);
  EXPECT_LE((mp.centroid - translation).norm(), 1e-12);
  ExpectMatrixNear(mp.inertia, rotation * BoxInertia(mass, a, b, c) * rotation.transpose(), 1e-12);
}

TEST(ComputeHull, PrismApproachesCylinderAsSideCountGrows) {
  const double radius = 0.8, height = 2.0;
  const double volume = kPi * radius * radius * height;
  const double mass = volume;
  const double axial = mass * radius * radius / 2;
  const double transverse = mass * (3 * radius * radius + height * height) / 12;
  double previous_error = 1.0;
  for (int sides : {8, 16, 32, 64, 128}) {
    std::vector<Vector3d> points;
    for (int k = 0; k < sides; ++k) {
      const double phi = 2 * kPi * k / sides;
      for (double z : {-height / 2, height / 2}) {
        points.emplace_back(radius * std::cos(phi), radius * std::sin(phi), z);
      }
    }
    const ConvexHull hull = CountedHull(points, 2u * sides, sides + 2u, 4u * sides - 4);

    // Exact prism volume: n/2 r² sin(2π/n) h.
    const MassProperties mp = HullMassProperties(hull);
    EXPECT_NEAR(mp.volume, sides / 2.0 * radius * radius * std::sin(2 * kPi / sides) * height,
                1e-12);
    const double error =
        std::max({std::abs(mp.volume - volume) / volume, std::abs(mp.inertia(2, 2) - axial) / axial,
                  std::abs(mp.inertia(0, 0) - transverse) / transverse,
                  std::abs(mp.inertia(1, 1) - transverse) / transverse});
    EXPECT_LT(error, previous_error);
    EXPECT_LT(error, 40.0 / (sides * sides));  // second-order convergence
    EXPECT_LT(std::abs(mp.inertia(0, 1)), 1e-12);
    previous_error = error;
  }
  EXPECT_LT(previous_error, 1e-3);
}

TEST(ComputeHull, SurfaceGridFarFromTheOriginReducesToTheEightCorners) {
  std::vector<Vector3d> points;
  const Vector3d offset(1e6, -1e6, 1e6);
  for (int i = -4; i <= 4; ++i) {
    for (int j = -4; j <= 4; ++j) {
      for (int k = -4; k <= 4; ++k)
        points.push_back(offset + Vector3d(0.25 * i, 0.5 * j, 0.125 * k));
    }
  }
  const ConvexHull hull = CountedHull(points, 8u, 6u, 12u);
  const MassProperties mp = HullMassProperties(hull);
  EXPECT_NEAR(mp.volume, 2.0 * 4.0 * 1.0, 1e-8);
  EXPECT_LE((mp.centroid - offset).norm(), 1e-8);
  ExpectMatrixNear(mp.inertia, BoxInertia(8.0, 2, 4, 1), 1e-8);
}

TEST(ComputeHull, BumpBelowRoundoffIsTreatedAsOnTheFace) {
  std::vector<Vector3d> points = BoxCorners(1, 1, 1);
  points.emplace_back(0.1, 0.2, 0.5 + 1e-14);
  const ConvexHull hull = ComputeHull(points);
  EXPECT_EQ(hull.vertices.size(), 8u);
  EXPECT_EQ(hull.faces.size(), 6u);
  ExpectWellFormedHull(hull, points);
}

TEST(ComputeHull, ThinSlabStillHasAClosedOutwardHull) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<Vector3d> points;
  for (int i = 0; i < 60; ++i) points.emplace_back(uniform(rng), uniform(rng), 1e-7 * uniform(rng));
  const ConvexHull hull = ComputeHull(points);
  ExpectWellFormedHull(hull, points);
  EXPECT_GT(HullMassProperties(hull).volume, 0.0);
}

TEST(ComputeHull, BoundingSphereCoversEveryVertex) {
  const ConvexHull hull = ComputeHull(BoxCorners(2.0, 4.0, 4.0));
  const BoundingSphere bound = BoundHull(hull);
  EXPECT_LE(bound.center.norm(), 1e-15);
  EXPECT_NEAR(bound.radius, 3.0, 1e-15);
  EXPECT_EQ(BoundHull(ConvexHull{}).radius, 0.0);
}

// ---------------------------------------------------------------------------
// Errors

TEST(ComputeHullErrors, ThreePointsAreTooFew) {
  const std::vector<Vector3d> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::string message = ErrorMessage([&] { ComputeHull(points); });
  EXPECT_NE(message.find("at least 4 distinct points"), std::string::npos) << message;
  EXPECT_NE(message.find("got 3"), std::string::npos) << message;
}

TEST(ComputeHullErrors, FourCoplanarPointsHaveNoVolume) {
  const std::vector<Vector3d> points = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  const std::string message = ErrorMessage([&] { ComputeHull(points); });
  EXPECT_NE(message.find("points are coplanar: a convex piece needs volume"), std::string::npos)
      << message;
}

TEST(ComputeHullErrors, NearlyCoplanarTiltedPointsHaveNoVolume) {
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(1.1, Vector3d(1, -1, 2).normalized()).matrix();
  std::vector<Vector3d> points;
  for (int i = 0; i < 20; ++i) {
    points.push_back(rotation * Vector3d(std::cos(i), std::sin(3.0 * i), 1e-13 * (i % 3)));
  }
  const std::string message = ErrorMessage([&] { ComputeHull(points); });
  EXPECT_NE(message.find("coplanar"), std::string::npos) << message;
}

TEST(ComputeHullErrors, CollinearPointsHaveNoVolume) {
  std::vector<Vector3d> points;
  for (int i = 0; i < 6; ++i) points.push_back(Vector3d(1, 2, 3) * i + Vector3d(0.5, 0, 0));
  const std::string message = ErrorMessage([&] { ComputeHull(points); });
  EXPECT_NE(message.find("points are collinear"), std::string::npos) << message;
  EXPECT_NE(message.find("needs volume"), std::string::npos) << message;
}

TEST(ComputeHullErrors, NanCoordinateIsRejected) {
  std::vector<Vector3d> points = BoxCorners(1, 1, 1);
  points[3].y() = std::numeric_limits<double>::quiet_NaN();
  const std::string message = ErrorMessage([&] { ComputeHull(points); });
  EXPECT_NE(message.find("point 3 has a non-finite coordinate"), std::string::npos) << message;
}

TEST(ComputeHullErrors, InfiniteCoordinateIsRejected) {
  std::vector<Vector3d> points = BoxCorners(1, 1, 1);
  points[0].z() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(ComputeHull(points), GeometryError);
}

TEST(ComputeHullErrors, AllDuplicatePointsAreOneDistinctPoint) {
  const std::vector<Vector3d> points(10, Vector3d(1, 2, 3));
  const std::string message = ErrorMessage([&] { ComputeHull(points); });
  EXPECT_NE(message.find("at least 4 distinct points, got 1 (of 10 given)"), std::string::npos)
      << message;
}

TEST(ComputeHullErrors, EmptyInputIsRejected) {
  EXPECT_THROW(ComputeHull(std::span<const Vector3d>()), GeometryError);
}

// ---------------------------------------------------------------------------
// Mass properties

TEST(MassProperties, SphereHasTwoFifthsMassRadiusSquared) {
  const double r = 0.3, density = 7.8;
  const MassProperties mp = SphereMassProperties(Vector3d(1, 2, 3), r, density);
  const double volume = 4.0 / 3.0 * kPi * r * r * r;
  EXPECT_NEAR(mp.volume, volume, 1e-15);
  EXPECT_NEAR(mp.mass, density * volume, 1e-14);
  EXPECT_EQ(mp.centroid, Vector3d(1, 2, 3));
  ExpectMatrixNear(mp.inertia, Matrix3d::Identity() * 0.4 * mp.mass * r * r, 1e-15);
  EXPECT_THROW(SphereMassProperties(Vector3d::Zero(), -1.0), GeometryError);
  EXPECT_THROW(SphereMassProperties(Vector3d::Zero(), 1.0, -2.0), GeometryError);
}

TEST(MassProperties, TwoSpheresCombineWithTheParallelAxisTheorem) {
  const MassProperties a = SphereMassProperties(Vector3d(-1, 0, 0), 0.5);
  const MassProperties b = SphereMassProperties(Vector3d(2, 0, 0), 0.25, 8.0);  // same mass
  const std::vector<MassProperties> parts = {a, b};
  const MassProperties sum = CombineMassProperties(parts);
  EXPECT_NEAR(sum.mass, a.mass + b.mass, 1e-14);
  EXPECT_NEAR(sum.volume, a.volume + b.volume, 1e-14);
  EXPECT_LE((sum.centroid - Vector3d(0.5, 0, 0)).norm(), 1e-15);
  // Each sphere sits 1.5 from the combined centroid along x.
  const double own = 0.4 * a.mass * 0.25 + 0.4 * b.mass * 0.0625;
  const double shift = (a.mass + b.mass) * 1.5 * 1.5;
  ExpectMatrixNear(sum.inertia, Vector3d(own, own + shift, own + shift).asDiagonal(), 1e-14);
}

TEST(MassProperties, TwoUnitCubesCombineIntoTheTwoByOneByOneBox) {
  std::vector<Vector3d> left, right;
  for (const auto& p : BoxCorners(1, 1, 1)) {
    left.push_back(p + Vector3d(-0.5, 0, 0));
    right.push_back(p + Vector3d(0.5, 0, 0));
  }
  const std::vector<MassProperties> parts = {HullMassProperties(ComputeHull(left), 3.0),
                                             HullMassProperties(ComputeHull(right), 3.0)};
  const MassProperties sum = CombineMassProperties(parts);
  const MassProperties box = HullMassProperties(ComputeHull(BoxCorners(2, 1, 1)), 3.0);
  EXPECT_NEAR(sum.mass, box.mass, 1e-13);
  EXPECT_NEAR(sum.volume, 2.0, 1e-13);
  EXPECT_LE((sum.centroid - box.centroid).norm(), 1e-14);
  ExpectMatrixNear(sum.inertia, box.inertia, 1e-13);
  ExpectMatrixNear(sum.inertia, BoxInertia(6.0, 2, 1, 1), 1e-13);
}

TEST(MassProperties, CombiningNothingGivesZero) {
  const MassProperties none = CombineMassProperties({});
  EXPECT_EQ(none.mass, 0.0);
  EXPECT_EQ(none.inertia, Matrix3d::Zero());
}

// ---------------------------------------------------------------------------
// Rotation vectors

void ExpectSameRotation(const Eigen::Quaterniond& p, const Eigen::Quaterniond& q, double tol) {
  // q and −q are the same rotation.
  EXPECT_NEAR(std::abs(p.coeffs().dot(q.coeffs())), 1.0, tol);
}

TEST(RotationVector, RoundTripsForGeneralAngles) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    Vector3d axis(uniform(rng), uniform(rng), uniform(rng));
    axis.normalize();
    const double angle = kPi * (0.5 * uniform(rng) + 0.5);  // in [0, π)
    const Vector3d r = angle * axis;
    const Eigen::Quaterniond q = QuaternionFromRotationVector(r);
    EXPECT_NEAR(q.norm(), 1.0, 1e-15);
    ExpectSameRotation(q, Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis)), 1e-15);
    EXPECT_LE((RotationVectorFromQuaternion(q) - r).norm(), 1e-14);
    // Applying the rotation to a vector matches the matrix form.
    const Vector3d v(0.3, -1.2, 2.0);
    EXPECT_LE((q * v - Eigen::AngleAxisd(angle, axis) * v).norm(), 1e-14);
  }
}

TEST(RotationVector, TinyAnglesRoundTripToFullRelativePrecision) {
  for (double angle : {1e-12, 3e-9, 1e-6, 9.9e-5, 1.01e-4}) {
    const Vector3d r = angle * Vector3d(0.2, -0.6, 0.5).normalized();
    const Eigen::Quaterniond q = QuaternionFromRotationVector(r);
    EXPECT_NEAR(q.norm(), 1.0, 1e-15);
    // sin(θ/2)/θ = 1/2 − θ²/48 + O(θ⁴).
    EXPECT_LE((q.vec() - (0.5 - angle * angle / 48) * r).norm(), 1e-15 * angle);
    EXPECT_NEAR(q.w(), std::cos(angle / 2), 1e-16);
    const Vector3d back = RotationVectorFromQuaternion(q);
    EXPECT_LE((back - r).norm(), 4e-16 * angle) << "angle " << angle;
  }
  EXPECT_EQ(RotationVectorFromQuaternion(Eigen::Quaterniond::Identity()), Vector3d::Zero());
  EXPECT_EQ(QuaternionFromRotationVector(Vector3d::Zero()).w(), 1.0);
}

TEST(RotationVector, AnglesNearPiRoundTrip) {
  const Vector3d axis = Vector3d(1, 2, -2).normalized();
  for (double delta : {1e-3, 1e-8, 1e-12, 0.0}) {
    const Vector3d r = (kPi - delta) * axis;
    const Vector3d back = RotationVectorFromQuaternion(QuaternionFromRotationVector(r));
    EXPECT_LE((back - r).norm(), 1e-14) << "delta " << delta;
  }
  // Slightly beyond π comes back as the equivalent rotation about −axis.
  const Vector3d beyond = (kPi + 1e-6) * axis;
  const Vector3d back = RotationVectorFromQuaternion(QuaternionFromRotationVector(beyond));
  EXPECT_LE(back.norm(), kPi);
  EXPECT_LE((back + (kPi - 1e-6) * axis).norm(), 1e-14);
}

TEST(RotationVector, AngleIsInZeroToPiAndQuaternionSignIsIrrelevant) {
  const Vector3d r(0.3, -2.0, 1.1);
  const Eigen::Quaterniond q = QuaternionFromRotationVector(r);
  const Eigen::Quaterniond minus(-q.w(), -q.x(), -q.y(), -q.z());
  EXPECT_LE((RotationVectorFromQuaternion(minus) - r).norm(), 1e-14);
  // Non-unit quaternions are normalised first.
  const Eigen::Quaterniond scaled(3 * q.w(), 3 * q.x(), 3 * q.y(), 3 * q.z());
  EXPECT_LE((RotationVectorFromQuaternion(scaled) - r).norm(), 1e-14);
  EXPECT_THROW(RotationVectorFromQuaternion(Eigen::Quaterniond(0, 0, 0, 0)), GeometryError);
}

}  // namespace
}  // namespace asgard::geometry
