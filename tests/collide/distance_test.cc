// Distance (GJK), support mapping and the MPR overlap oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "tests/collide/shapes.h"

namespace asgard::collide {
namespace {

using testing::Box;
using testing::MakePose;
using testing::PieceFromHull;
using testing::RandomHull;
using testing::RandomRotation;

const Eigen::Matrix3d kI = Eigen::Matrix3d::Identity();

Eigen::Matrix3d Rot(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

void ExpectVector(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected, double tol) {
  EXPECT_LE((actual - expected).norm(), tol)
      << "actual " << actual.transpose() << " expected " << expected.transpose();
}

TEST(Piece, SphereBoundRadiusIsCentreDistancePlusRadius) {
  const Piece s = Piece::Sphere({3, 4, 0}, 2);
  EXPECT_DOUBLE_EQ(s.bound_radius, 7.0);
  ExpectVector(s.Support({0, 0, 5}), {3, 4, 2}, 1e-15);
  ExpectVector(s.Support({0, 0, 0}), {3, 4, 0}, 0.0);
}

TEST(Piece, PolytopeHasOutwardNormalsAdjacencyAndBoundRadius) {
  const Piece box = Box({1, 2, 3});
  EXPECT_EQ(box.vertices.size(), 8u);
  EXPECT_EQ(box.faces.size(), 6u);
  EXPECT_NEAR(box.bound_radius, std::sqrt(14.0), 1e-15);
  for (size_t f = 0; f < box.faces.size(); ++f) {
    const Eigen::Vector3d& n = box.normals[f];
    EXPECT_NEAR(n.norm(), 1.0, 1e-15);
    for (int v : box.faces[f]) EXPECT_GT(n.dot(box.vertices[static_cast<size_t>(v)]), 0.0);
  }
  for (const auto& list : box.neighbors) EXPECT_EQ(list.size(), 3u);
  ExpectVector(box.Support({1, -1, 1}), {1, -2, 3}, 0.0);
}

TEST(Piece, HillClimbingSupportOnALargePolytopeFindsTheMaximum) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 400; ++i) {
    points.push_back(Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized());
  }
  const Piece piece = PieceFromHull(geometry::ComputeHull(points));
  ASSERT_GT(piece.vertices.size(), 100u);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(piece.vertices.size()) - 1);
  for (int trial = 0; trial < 1000; ++trial) {
    const Eigen::Vector3d d(normal(rng), normal(rng), normal(rng));
    double best = -1e300;
    for (const auto& v : piece.vertices) best = std::max(best, v.dot(d));
    const int index = piece.SupportIndex(d, pick(rng));
    EXPECT_NEAR(piece.vertices[static_cast<size_t>(index)].dot(d), best, 1e-12);
  }
}

TEST(Distance, SeparatedSpheresGiveTheExactGapNormalAndPoints) {
  const Piece a = Piece::Sphere({0, 0, 0}, 1.0);
  const Piece b = Piece::Sphere({1, 0, 0}, 0.5);
  // b's centre in the world: (2, 4, 0) + Rz(90°)(1, 0, 0) = (2, 5, 0).
  const DistanceResult r = Distance(a, MakePose({1, 1, 0}, kI), b,
                                    MakePose({2, 4, 0}, Rot(std::numbers::pi / 2, {0, 0, 1})));
  EXPECT_FALSE(r.overlapping);
  EXPECT_NEAR(r.distance, std::sqrt(17.0) - 1.5, 1e-14);
  ExpectVector(r.normal, Eigen::Vector3d(1, 4, 0) / std::sqrt(17.0), 1e-14);
  ExpectVector(r.point_a, Eigen::Vector3d(1, 1, 0) + r.normal, 1e-14);
  ExpectVector(r.point_b, Eigen::Vector3d(2, 5, 0) - 0.5 * r.normal, 1e-14);
}

TEST(Distance, OverlappingSpheresAreFlaggedWithTheCentreLineNormal) {
  const Piece a = Piece::Sphere({0, 0, 0}, 1.0);
  const Piece b = Piece::Sphere({0, 0, 0}, 1.0);
  const DistanceResult r = Distance(a, MakePose({0, 0, 0}, kI), b, MakePose({0, 1.5, 0}, kI));
  EXPECT_TRUE(r.overlapping);
  EXPECT_EQ(r.distance, 0.0);
  ExpectVector(r.normal, {0, 1, 0}, 1e-15);
  const DistanceResult same = Distance(a, MakePose({0, 0, 0}, kI), b, MakePose({0, 0, 0}, kI));
  EXPECT_TRUE(same.overlapping);
  EXPECT_NEAR(same.normal.norm(), 1.0, 1e-15);
}

TEST(Distance, BoxesFaceToFaceGiveTheGapAlongTheFaceNormal) {
  const Piece box = Box({0.5, 0.5, 0.5});
  const DistanceResult r = Distance(box, MakePose({0, 0, 0}, kI), box, MakePose({3, 0.2, 0.1}, kI));
  EXPECT_FALSE(r.overlapping);
  EXPECT_NEAR(r.distance, 2.0, 1e-14);
  ExpectVector(r.normal, {1, 0, 0}, 1e-14);
  EXPECT_NEAR(r.point_a.x(), 0.5, 1e-14);
  EXPECT_NEAR(r.point_b.x(), 2.5, 1e-14);
  ExpectVector(r.point_b - r.point_a, 2.0 * r.normal, 1e-13);
  // Both points lie on the overlap of the two faces.
  EXPECT_GE(r.point_a.y(), -0.3 - 1e-14);
  EXPECT_LE(r.point_a.y(), 0.5 + 1e-14);
  EXPECT_GE(r.point_a.z(), -0.4 - 1e-14);
  EXPECT_LE(r.point_a.z(), 0.5 + 1e-14);
}

TEST(Distance, CrossedEdgesMeetAtTheirCommonPerpendicular) {
  const double h = 0.5;
  const Piece box = Box({h, h, h});
  const Pose pa = MakePose({0, 0, 0}, Rot(std::numbers::pi / 4, {1, 0, 0}));  // top edge along x
  const Pose pb = MakePose({0, 0, 3}, Rot(std::numbers::pi / 4, {0, 1, 0}));  // bottom edge along y
  const DistanceResult r = Distance(box, pa, box, pb);
  EXPECT_NEAR(r.distance, 3.0 - 2.0 * h * std::sqrt(2.0), 1e-14);
  ExpectVector(r.normal, {0, 0, 1}, 1e-14);
  ExpectVector(r.point_a, {0, 0, h * std::sqrt(2.0)}, 1e-14);
  ExpectVector(r.point_b, {0, 0, 3 - h * std::sqrt(2.0)}, 1e-14);
}

TEST(Distance, ParallelEdgesGiveFiniteResults) {
  const double h = 0.5;
  const Piece box = Box({h, h, h});
  const Eigen::Matrix3d R = Rot(std::numbers::pi / 4, {1, 0, 0});
  const DistanceResult r = Distance(box, MakePose({0, 0, 0}, R), box, MakePose({0.3, 0, 2}, R));
  EXPECT_NEAR(r.distance, 2.0 - 2.0 * h * std::sqrt(2.0), 1e-14);
  ExpectVector(r.normal, {0, 0, 1}, 1e-14);
  EXPECT_NEAR(r.point_a.z(), h * std::sqrt(2.0), 1e-14);
  EXPECT_GE(r.point_a.x(), -0.2 - 1e-14);
  EXPECT_LE(r.point_a.x(), 0.5 + 1e-14);
}

TEST(Distance, VertexAgainstFaceReachesTheFacePerpendicularly) {
  const double h = 0.5;
  const Piece box = Box({h, h, h});
  const Eigen::Matrix3d R =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(0, 0, -1))
          .toRotationMatrix();
  const DistanceResult r = Distance(box, MakePose({0, 0, 0}, kI), box, MakePose({0.1, -0.2, 3}, R));
  EXPECT_NEAR(r.distance, 3.0 - h * std::sqrt(3.0) - h, 1e-14);
  ExpectVector(r.normal, {0, 0, 1}, 1e-14);
  ExpectVector(r.point_a, {0.1, -0.2, h}, 1e-14);
  ExpectVector(r.point_b, {0.1, -0.2, 3 - h * std::sqrt(3.0)}, 1e-14);
}

TEST(Distance, SphereAgainstBoxFaceAndCorner) {
  const Piece box = Box({0.5, 0.5, 0.5});
  const Piece ball = Piece::Sphere({0, 0, 0}, 0.5);
  DistanceResult r = Distance(box, MakePose({0, 0, 0}, kI), ball, MakePose({2, 0.2, 0.3}, kI));
  EXPECT_NEAR(r.distance, 1.0, 1e-14);
  ExpectVector(r.normal, {1, 0, 0}, 1e-14);
  ExpectVector(r.point_a, {0.5, 0.2, 0.3}, 1e-14);
  ExpectVector(r.point_b, {1.5, 0.2, 0.3}, 1e-14);
  r = Distance(ball, MakePose({2, 2, 2}, kI), box, MakePose({0, 0, 0}, kI));
  EXPECT_NEAR(r.distance, 1.5 * std::sqrt(3.0) - 0.5, 1e-14);
  ExpectVector(r.normal, -Eigen::Vector3d(1, 1, 1).normalized(), 1e-14);
  ExpectVector(r.point_b, {0.5, 0.5, 0.5}, 1e-14);
  // An off-centre sphere in a rotated body.
  const Piece offset = Piece::Sphere({0, 1, 0}, 0.25);
  r = Distance(box, MakePose({0, 0, 0}, kI), offset,
               MakePose({0, 0, 2}, Rot(std::numbers::pi / 2, {1, 0, 0})));  // centre (0, 0, 3)
  EXPECT_NEAR(r.distance, 3.0 - 0.5 - 0.25, 1e-14);
}

TEST(Distance, SphereCentreInsideABoxOverlapsWithTheNearestFaceNormal) {
  const Piece box = Box({1, 1, 1});
  const Piece ball = Piece::Sphere({0, 0, 0}, 0.1);
  const DistanceResult r =
      Distance(box, MakePose({0, 0, 0}, kI), ball, MakePose({0.2, 0.9, 0.1}, kI));
  EXPECT_TRUE(r.overlapping);
  EXPECT_EQ(r.distance, 0.0);
  ExpectVector(r.normal, {0, 1, 0}, 1e-14);
}

TEST(Distance, CoincidentAndTouchingBoxesGiveFiniteResults) {
  const Piece box = Box({0.5, 0.5, 0.5});
  DistanceResult r = Distance(box, MakePose({0, 0, 0}, kI), box, MakePose({0, 0, 0}, kI));
  EXPECT_TRUE(r.overlapping);
  EXPECT_TRUE(r.normal.allFinite());
  EXPECT_NEAR(r.normal.norm(), 1.0, 1e-15);
  EXPECT_TRUE(r.point_a.allFinite() && r.point_b.allFinite());
  r = Distance(box, MakePose({0, 0, 0}, kI), box, MakePose({1, 0.25, 0}, kI));
  EXPECT_EQ(r.distance, 0.0);
  EXPECT_TRUE(r.overlapping);
  ExpectVector(r.normal, {1, 0, 0}, 1e-12);
  EXPECT_TRUE(r.point_a.allFinite() && r.point_b.allFinite());
  // Deep face-to-face overlap: the least-penetration normal.
  r = Distance(box, MakePose({0, 0, 0}, kI), box, MakePose({0, 0, -0.7}, kI));
  EXPECT_TRUE(r.overlapping);
  ExpectVector(r.normal, {0, 0, -1}, 1e-12);
  // A degenerate sphere (radius 0) exactly at a box corner.
  const Piece point = Piece::Sphere({0, 0, 0}, 0.0);
  r = Distance(point, MakePose({0.5, 0.5, 0.5}, kI), box, MakePose({0, 0, 0}, kI));
  EXPECT_EQ(r.distance, 0.0);
  EXPECT_TRUE(r.normal.allFinite());
}

TEST(Distance, DegenerateSegmentAndPointPolytopesGiveFiniteExactDistances) {
  const Piece box = Box({0.5, 0.5, 0.5});
  const Piece segment = Piece::Polytope({{-3, 0, 0}, {3, 0, 0}}, {});
  const Piece point = Piece::Polytope({{0, 0, 0}}, {});
  DistanceResult r = Distance(box, MakePose({0, 0, 0}, kI), segment, MakePose({0, 0, 2}, kI));
  EXPECT_NEAR(r.distance, 1.5, 1e-14);
  ExpectVector(r.normal, {0, 0, 1}, 1e-14);
  // A segment parallel to another (a second segment piece).
  r = Distance(segment, MakePose({0, 0, 0}, kI), segment, MakePose({1, 2, 0}, kI));
  EXPECT_NEAR(r.distance, 2.0, 1e-14);
  EXPECT_TRUE(r.point_a.allFinite());
  r = Distance(point, MakePose({0, 0, 0}, kI), point, MakePose({0, 0, 0}, kI));
  EXPECT_TRUE(r.overlapping);
  EXPECT_TRUE(r.normal.allFinite());
  r = Distance(point, MakePose({0.2, 0.1, 0.7}, kI), box, MakePose({0, 0, 0}, kI));
  EXPECT_NEAR(r.distance, 0.2, 1e-14);
  ExpectVector(r.normal, {0, 0, -1}, 1e-14);
}

// A pair of random polytopes: a (5 to max_vertices points, size 1) at a
// random pose, b (size b_size) turned at random with its centre min_gap + 2u
// away from a's in a random direction, u uniform in [0, 1).
struct RandomPair {
  geometry::ConvexHull ha, hb;
  Piece a, b;
  Pose pa, pb;
};

class RandomPairs {
 public:
  explicit RandomPairs(uint64_t seed) : rng_(seed) {}

  RandomPair Next(int max_vertices, double b_size, double min_gap) {
    std::uniform_int_distribution<int> count(5, max_vertices);
    const geometry::ConvexHull ha = RandomHull(rng_, count(rng_), 1.0);
    const geometry::ConvexHull hb = RandomHull(rng_, count(rng_), b_size);
    const Piece a = PieceFromHull(ha);
    const Piece b = PieceFromHull(hb);
    const Pose pa = MakePose({normal_(rng_), normal_(rng_), normal_(rng_)}, RandomRotation(rng_));
    const Eigen::Vector3d dir =
        Eigen::Vector3d(normal_(rng_), normal_(rng_), normal_(rng_)).normalized();
    const Pose pb = MakePose(pa.p + (min_gap + 2.0 * uniform_(rng_)) * dir, RandomRotation(rng_));
    return {ha, hb, a, b, pa, pb};
  }

 private:
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
  std::normal_distribution<double> normal_{0.0, 1.0};
};

TEST(Distance, RandomPolytopesMatchABruteForceOverFeaturePairs) {
  RandomPairs pairs(42);
  int compared = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const auto [ha, hb, a, b, pa, pb] = pairs.Next(40, 0.7, 1.2);
    const double reference = testing::BruteForceDistance(ha, pa, hb, pb);
    const DistanceResult r = Distance(a, pa, b, pb);
    if (reference < 1e-6) continue;
    ++compared;
    EXPECT_FALSE(r.overlapping);
    EXPECT_NEAR(r.distance, reference, 1e-9) << "trial " << trial;
    EXPECT_NEAR((r.point_b - r.point_a).norm(), r.distance, 1e-9);
    ExpectVector(r.point_b - r.point_a, r.distance * r.normal, 1e-9);
    EXPECT_LE(r.iterations, 64);
  }
  EXPECT_GT(compared, 200);
}

TEST(Distance, LargePolytopesUsingHillClimbingMatchTheBruteForce) {
  std::mt19937_64 rng(77);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto surface_hull = [&](double sx, double sy, double sz) {
    std::vector<Eigen::Vector3d> p;
    for (int i = 0; i < 120; ++i) {
      const Eigen::Vector3d x = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
      p.push_back(Eigen::Vector3d(sx * x.x(), sy * x.y(), sz * x.z()));
    }
    return geometry::ComputeHull(p);
  };
  for (int trial = 0; trial < 12; ++trial) {
    const geometry::ConvexHull ha = surface_hull(1.0, 0.6, 0.8);
    const geometry::ConvexHull hb = surface_hull(0.5, 0.9, 0.4);
    ASSERT_GT(ha.vertices.size(), 32u);
    const Piece a = PieceFromHull(ha), b = PieceFromHull(hb);
    const Pose pa = MakePose({0, 0, 0}, RandomRotation(rng));
    const Eigen::Vector3d dir = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    const Pose pb = MakePose(2.2 * dir, RandomRotation(rng));
    DistanceCache cache;
    const DistanceResult r = Distance(a, pa, b, pb, &cache);
    EXPECT_NEAR(r.distance, testing::BruteForceDistance(ha, pa, hb, pb), 1e-9);
    const DistanceResult again = Distance(a, pa, b, pb, &cache);
    EXPECT_NEAR(again.distance, r.distance, 1e-12);
    EXPECT_EQ(again.iterations, 1);
  }
}

TEST(Distance, NearlyTouchingPolytopesMatchTheBruteForce) {
  std::mt19937_64 rng(2024);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> exponent(-10.0, -4.0);
  for (int trial = 0; trial < 100; ++trial) {
    const geometry::ConvexHull ha = RandomHull(rng, 12, 1.0);
    const geometry::ConvexHull hb = RandomHull(rng, 12, 1.0);
    const Piece a = PieceFromHull(ha), b = PieceFromHull(hb);
    const Pose pa = MakePose({0, 0, 0}, RandomRotation(rng));
    const Eigen::Vector3d dir = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    Pose pb = MakePose(3.0 * dir, RandomRotation(rng));
    // Slide b towards a until the gap is tiny.
    const DistanceResult far = Distance(a, pa, b, pb);
    const double gap = std::pow(10.0, exponent(rng));
    pb.p -= (far.distance - gap) * far.normal;
    const DistanceResult r = Distance(a, pa, b, pb);
    const double reference = testing::BruteForceDistance(ha, pa, hb, pb);
    EXPECT_NEAR(r.distance, reference, 1e-12 + 1e-9 * reference) << "trial " << trial;
    EXPECT_TRUE(r.normal.allFinite());
  }
}

TEST(Distance, OverlapAgreesWithMprAndSeparatingAxesOnRandomPairs) {
  RandomPairs pairs(1234);
  int overlapping = 0, separated = 0, near = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const auto [ha, hb, a, b, pa, pb] = pairs.Next(30, 0.8, 0.0);
    const DistanceResult r = Distance(a, pa, b, pb);
    const std::optional<bool> mpr = OverlapMpr(a, pa, b, pb);
    const double sat = testing::SatPenetration(ha, pa, hb, pb);
    ASSERT_TRUE(mpr.has_value());
    EXPECT_TRUE(r.normal.allFinite());
    if (std::abs(sat) <= 1e-8 || (!r.overlapping && r.distance <= 1e-8)) {
      ++near;
      continue;
    }
    EXPECT_EQ(r.overlapping, sat > 0.0) << "trial " << trial << " sat " << sat;
    EXPECT_EQ(*mpr, r.overlapping) << "trial " << trial << " sat " << sat;
    (r.overlapping ? overlapping : separated)++;
  }
  EXPECT_GT(overlapping, 200);
  EXPECT_GT(separated, 200);
  EXPECT_LT(near, 10);
}

TEST(Distance, MprSeesSpheresWithTheirRadius) {
  const Piece box = Box({0.5, 0.5, 0.5});
  const Piece ball = Piece::Sphere({0, 0, 0}, 0.5);
  EXPECT_EQ(OverlapMpr(box, MakePose({0, 0, 0}, kI), ball, MakePose({0.9, 0, 0}, kI)), true);
  EXPECT_EQ(OverlapMpr(box, MakePose({0, 0, 0}, kI), ball, MakePose({1.1, 0, 0}, kI)), false);
  EXPECT_EQ(OverlapMpr(ball, MakePose({0, 0, 0}, kI), ball, MakePose({0, 0.99, 0}, kI)), true);
  Pose bad = MakePose({0, 0, 0}, kI);
  bad.p.x() = std::nan("");
  EXPECT_EQ(OverlapMpr(box, bad, ball, MakePose({0, 0, 0}, kI)), std::nullopt);
}

TEST(Distance, WarmStartCostsAboutOneIterationAndMatchesColdQueries) {
  const Piece a = Box({0.5, 0.3, 0.4});
  const Piece b = Box({0.4, 0.4, 0.2});
  const Pose pa = MakePose({0, 0, 0}, Rot(0.3, {1, 2, 3}));
  DistanceCache cache;
  int warm_iterations = 0, cold_iterations = 0;
  const int steps = 1000;
  for (int k = 0; k <= steps; ++k) {
    const double s = static_cast<double>(k) / steps;
    const double angle = 2.0 * std::numbers::pi * s;
    const Pose pb =
        MakePose({2.0 * std::cos(angle), 2.0 * std::sin(angle), 0.5 * std::sin(2 * angle)},
                 Rot(3.0 * s, {0.3, -1, 0.5}) * Rot(0.2, {1, 0, 0}));
    const DistanceResult warm = Distance(a, pa, b, pb, &cache);
    const DistanceResult cold = Distance(a, pa, b, pb);
    if (k > 0) warm_iterations += warm.iterations;
    cold_iterations += cold.iterations;
    ASSERT_FALSE(cold.overlapping);
    EXPECT_NEAR(warm.distance, cold.distance, 1e-12) << "step " << k;
    ExpectVector(warm.normal, cold.normal, 1e-9);
    ExpectVector(warm.point_b - warm.point_a, cold.point_b - cold.point_a, 1e-12);
  }
  const double warm_average = static_cast<double>(warm_iterations) / steps;
  const double cold_average = static_cast<double>(cold_iterations) / (steps + 1);
  RecordProperty("warm_average_iterations", std::to_string(warm_average));
  RecordProperty("cold_average_iterations", std::to_string(cold_average));
  std::printf("GJK iterations per query: warm %.3f, cold %.3f\n", warm_average, cold_average);
  EXPECT_LE(warm_average, 2.0);
  EXPECT_LT(warm_average, cold_average);
}

TEST(Distance, IsDeterministic) {
  std::mt19937_64 rng(5);
  const geometry::ConvexHull ha = RandomHull(rng, 20, 1.0);
  const geometry::ConvexHull hb = RandomHull(rng, 20, 1.0);
  const Piece a = PieceFromHull(ha), b = PieceFromHull(hb);
  const Pose pa = MakePose({0, 0, 0}, RandomRotation(rng));
  const Pose pb = MakePose({1.5, 0.3, -0.2}, RandomRotation(rng));
  const DistanceResult r1 = Distance(a, pa, b, pb);
  const DistanceResult r2 = Distance(a, pa, b, pb);
  EXPECT_EQ(r1.distance, r2.distance);
  EXPECT_EQ(r1.point_a, r2.point_a);
  EXPECT_EQ(r1.point_b, r2.point_b);
  EXPECT_EQ(r1.iterations, r2.iterations);
}

}  // namespace
}  // namespace asgard::collide
