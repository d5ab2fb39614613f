// Time of impact by conservative advancement.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <ostream>
#include <string>
#include <vector>

#include "tests/collide/shapes.h"

namespace asgard::collide {
namespace {

using testing::Box;
using testing::MakePose;

const Eigen::Matrix3d kI = Eigen::Matrix3d::Identity();

Motion Linear(const Eigen::Vector3d& p0, const Eigen::Vector3d& v) {
  Motion m;
  m.pose = [p0, v](double t) { return MakePose(p0 + t * v, Eigen::Matrix3d::Identity()); };
  m.max_linear_speed = v.norm();
  return m;
}

Motion Static(const Eigen::Vector3d& p) { return Linear(p, Eigen::Vector3d::Zero()); }

// Translating at v while spinning about z at omega.
Motion Spinning(const Eigen::Vector3d& p0, const Eigen::Vector3d& v, double omega) {
  Motion m;
  m.pose = [p0, v, omega](double t) {
    return MakePose(p0 + t * v,
                    Eigen::AngleAxisd(omega * t, Eigen::Vector3d::UnitZ()).toRotationMatrix());
  };
  m.max_linear_speed = v.norm();
  m.max_angular_speed = std::abs(omega);
  return m;
}

// First time the pieces touch: fine sampling, then bisection on overlap.
double ReferenceContact(const Piece& a, const Motion& ma, const Piece& b, const Motion& mb,
                        double t0, double t1, double h) {
  auto touching = [&](double t) {
    const DistanceResult r = Distance(a, ma.pose(t), b, mb.pose(t));
    return r.overlapping;
  };
  double previous = t0;
  for (double t = t0 + h; t <= t1; t += h) {
    if (touching(t)) {
      double lo = previous, hi = t;
      for (int k = 0; k < 200 && hi - lo > 1e-15; ++k) {
        const double mid = 0.5 * (lo + hi);
        (touching(mid) ? hi : lo) = mid;
      }
      return hi;
    }
    previous = t;
  }
  return std::nan("");
}

void ExpectLanding(const ImpactResult& impact, double separation) {
  EXPECT_FALSE(impact.contact.overlapping);
  EXPECT_GT(impact.contact.distance, 0.0);
  EXPECT_LE(impact.contact.distance, separation);
}

TEST(TimeOfImpact, ApproachingSpheresMeetAtTwoSeconds) {
  const Piece ball = Piece::Sphere({0, 0, 0}, 1.0);
  const double separation = 1e-6;
  const auto impact = TimeOfImpact(ball, Linear({0, 0, 0}, {1, 0, 0}), ball,
                                   Linear({6, 0, 0}, {-1, 0, 0}), 0.0, 10.0, separation);
  ASSERT_TRUE(impact.has_value());
  ExpectLanding(*impact, separation);
  EXPECT_LE(impact->time, 2.0);
  EXPECT_GE(impact->time, 2.0 - separation / 2.0 - 1e-12);
  EXPECT_LT(impact->iterations, 60);
}

// A box moving along x at unit speed while spinning about z at `omega`,
// towards a static wall at x = `wall_x`: the impact must land just before the
// first contact that a fine reference search (step `reference_step`) finds in
// [0, t1].
struct SpinningBoxCase {
  const char* name;
  Eigen::Vector3d box_half_extents;
  double omega;
  double wall_x;
  double t1;
  double reference_step;
  int more_queries_than;  // the search must take more distance queries (-1: not checked)
};

class SpinningBoxAgainstAWall : public ::testing::TestWithParam<SpinningBoxCase> {};

void PrintTo(const SpinningBoxCase& c, std::ostream* os) { *os << c.name; }

TEST_P(SpinningBoxAgainstAWall, LandsJustBeforeTheReferenceContact) {
  const SpinningBoxCase& c = GetParam();
  const Piece box = Box(c.box_half_extents);
  const Piece wall = Box({0.05, 2, 2});
  const Motion mbox = Spinning({0, 0, 0}, {1, 0, 0}, c.omega);
  const Motion mwall = Static({c.wall_x, 0, 0});
  const double separation = 1e-9;
  const auto impact = TimeOfImpact(box, mbox, wall, mwall, 0.0, c.t1, separation);
  ASSERT_TRUE(impact.has_value());
  ExpectLanding(*impact, separation);
  if (c.more_queries_than >= 0) {
    EXPECT_GT(impact->iterations, c.more_queries_than);
  }
  const double reference = ReferenceContact(box, mbox, wall, mwall, 0.0, c.t1, c.reference_step);
  ASSERT_TRUE(std::isfinite(reference));
  EXPECT_NEAR(impact->time, reference, 1e-6);
  EXPECT_LE(impact->time, reference);
  std::printf("impact at %.12f (reference %.12f) after %d distance queries\n", impact->time,
              reference, impact->iterations);
}

std::vector<SpinningBoxCase> SpinningBoxCases() {
  return {
      {"SpinningBoxReachesAWallWhenAFineReferenceSearchSaysSo", Eigen::Vector3d(0.5, 0.5, 0.5), 5.0,
       3.0, 5.0, 1e-4, -1},
      // Spinning fast, the box leaves the advancement to the fallback.
      {"FastSpinLeavesAdvancementToTheFallbackAndStillLandsBeforeContact",
       Eigen::Vector3d(0.5, 0.3, 0.5), 80.0, 2.0, 3.0, 1e-5, 200},
  };
}

INSTANTIATE_TEST_SUITE_P(TimeOfImpact, SpinningBoxAgainstAWall,
                         ::testing::ValuesIn(SpinningBoxCases()),
                         [](const ::testing::TestParamInfo<SpinningBoxCase>& info) {
                           return std::string(info.param.name);
                         });

TEST(TimeOfImpact, ABallSpinningAboutItsCentreDoesNotSlowTheSearch) {
  const Piece ball = Piece::Sphere({0, 0, 0}, 0.5);
  const Piece box = Box({0.5, 0.5, 0.5});
  Motion spinning = Spinning({3, 0, 0}, {-0.01, 0, 0}, 1000.0);
  const double separation = 1e-6;
  const auto impact = TimeOfImpact(box, Static({0, 0, 0}), ball, spinning, 0.0, 1000.0, separation);
  ASSERT_TRUE(impact.has_value());
  ExpectLanding(*impact, separation);
  EXPECT_NEAR(impact->time, 200.0, separation / 0.01);
  EXPECT_LT(impact->iterations, 10);
}

// A spinning box closing slowly on a wall with a landing gap of a few ulps:
// with a graze tolerance g every step closes at least g at the bound's
// speed, and nothing before the landing overlaps by more than g.
TEST(TimeOfImpact, AGrazeToleranceBoundsTheStepsAndTheMissedOverlap) {
  const Piece wall = Box({0.5, 5, 5});
  const Piece box = Box({0.5, 0.5, 0.5});
  const Motion spinning = Spinning({1.3, 0, 0}, {-0.1, 0, 0}, 20.0);
  const double separation = 1e-12, graze = 1e-3, t1 = 2.0;
  const auto exact = TimeOfImpact(wall, Static({0, 0, 0}), box, spinning, 0.0, t1, separation);
  const auto fast =
      TimeOfImpact(wall, Static({0, 0, 0}), box, spinning, 0.0, t1, separation, nullptr, graze);
  ASSERT_TRUE(exact.has_value());
  ASSERT_TRUE(fast.has_value());
  EXPECT_FALSE(fast->contact.overlapping);
  // It may pass a first graze the exact search lands at, never land earlier.
  EXPECT_GE(fast->time, exact->time);
  // B = v + ω r; every advancement step covers g/B, plus one bisection.
  const double bound = 0.1 + 20.0 * std::sqrt(0.75);
  EXPECT_LE(fast->iterations, bound * fast->time / graze + 1 + 200);
  // Up to the landing, sampled finely: never deeper than the graze.
  for (double t = 0.0; t < fast->time; t += 1e-5) {
    const Pose pw = Static({0, 0, 0}).pose(t), pb = spinning.pose(t);
    if (!Distance(wall, pw, box, pb).overlapping) continue;
    const auto pen = PenetrationMpr(wall, pw, box, pb);
    ASSERT_TRUE(pen.has_value());
    EXPECT_LE(pen->depth, graze) << "t=" << t;
  }
}

// A box sliding along a wall face to face, 1e-6 away, with the landing gap
// below that: the gap never closes, but plain advancement can only step
// (gap − s/2)/B and stops at its query cap; with a graze tolerance the
// window takes B T / g steps and finds nothing.
TEST(TimeOfImpact, SlidingInContactTakesBoundedStepsWithAGrazeTolerance) {
  const Piece wall = Box({0.5, 5, 5});
  const Piece box = Box({0.5, 0.5, 0.5});
  int queries = 0;
  Motion sliding;
  sliding.pose = [&queries](double t) {
    ++queries;
    return MakePose({1.0 + 1e-6, t, 0.0},
                    Eigen::AngleAxisd(0.5 * t, Eigen::Vector3d::UnitX()).toRotationMatrix());
  };
  sliding.max_linear_speed = 1.0;
  sliding.max_angular_speed = 0.5;
  const double separation = 5e-7, graze = 1e-3, t1 = 1.0;
  const auto exact = TimeOfImpact(wall, Static({0, 0, 0}), box, sliding, 0.0, t1, separation);
  ASSERT_TRUE(exact.has_value());  // the cap: a possible contact, not a skipped one
  EXPECT_LT(exact->time, 0.5 * t1);
  EXPECT_GE(queries, 100000);
  queries = 0;
  const auto fast =
      TimeOfImpact(wall, Static({0, 0, 0}), box, sliding, 0.0, t1, separation, nullptr, graze);
  EXPECT_FALSE(fast.has_value());
  const double bound = 1.0 + 0.5 * std::sqrt(0.75);
  EXPECT_LE(queries, bound * t1 / graze + 2);
}

TEST(TimeOfImpact, FastSphereDoesNotTunnelThroughAThinPlate) {
  const Piece plate = Box({2, 2, 0.005});
  const Piece ball = Piece::Sphere({0, 0, 0}, 0.1);
  const double separation = 1e-6;
  const auto impact = TimeOfImpact(plate, Static({0, 0, 0}), ball,
                                   Linear({0.3, -0.2, 5}, {0, 0, -1000}), 0.0, 1.0, separation);
  ASSERT_TRUE(impact.has_value());
  ExpectLanding(*impact, separation);
  const double expected = (5.0 - 0.105) / 1000.0;
  EXPECT_LE(impact->time, expected);
  EXPECT_GE(impact->time, expected - separation / 1000.0);
  EXPECT_NEAR(impact->contact.normal.z(), 1.0, 1e-12);
}

TEST(TimeOfImpact, RandomTumblingPolytopesNeverLandAfterTheFirstSampledContact) {
  std::mt19937_64 rng(31);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double separation = 1e-8;
  int contacts = 0;
  for (int trial = 0; trial < 80; ++trial) {
    const geometry::ConvexHull ha = testing::RandomHull(rng, 10, 1.0);
    const geometry::ConvexHull hb = testing::RandomHull(rng, 10, 0.8);
    const Piece a = testing::PieceFromHull(ha), b = testing::PieceFromHull(hb);
    const Eigen::Vector3d pb0 =
        4.0 * Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    const Eigen::Vector3d vb =
        -pb0 / 2.0 + 0.1 * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    const Eigen::Vector3d wa(normal(rng), normal(rng), normal(rng));
    const Eigen::Vector3d wb = 3.0 * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    const Eigen::Matrix3d ra = testing::RandomRotation(rng), rb = testing::RandomRotation(rng);
    Motion ma, mb;
    ma.pose = [=](double t) {
      return MakePose(Eigen::Vector3d::Zero(),
                      Eigen::AngleAxisd(wa.norm() * t, wa.normalized()) * ra);
    };
    ma.max_angular_speed = wa.norm();
    mb.pose = [=](double t) {
      return MakePose(pb0 + t * vb, Eigen::AngleAxisd(wb.norm() * t, wb.normalized()) * rb);
    };
    mb.max_linear_speed = vb.norm();
    mb.max_angular_speed = wb.norm();
    const auto impact = TimeOfImpact(a, ma, b, mb, 0.0, 4.0, separation);
    const double reference = ReferenceContact(a, ma, b, mb, 0.0, 4.0, 1e-3);
    if (std::isfinite(reference)) {
      ASSERT_TRUE(impact.has_value()) << "trial " << trial;
      EXPECT_LE(impact->time, reference) << "trial " << trial;
    }
    if (impact) {
      ++contacts;
      ExpectLanding(*impact, separation);
    }
  }
  EXPECT_GT(contacts, 40);
}

TEST(TimeOfImpact, NoContactInTheIntervalGivesNothing) {
  const Piece ball = Piece::Sphere({0, 0, 0}, 1.0);
  const Piece box = Box({0.5, 0.5, 0.5});
  // Moving apart.
  EXPECT_FALSE(TimeOfImpact(ball, Linear({0, 0, 0}, {-1, 0, 0}), ball, Linear({3, 0, 0}, {1, 0, 0}),
                            0.0, 10.0, 1e-6)
                   .has_value());
  // Passing by at a distance of 0.5.
  EXPECT_FALSE(
      TimeOfImpact(box, Static({0, 0, 0}), ball, Linear({-5, 2, 0}, {1, 0, 0}), 0.0, 10.0, 1e-6)
          .has_value());
  // Approaching, but the interval ends first (contact at t = 2).
  EXPECT_FALSE(
      TimeOfImpact(ball, Static({0, 0, 0}), ball, Linear({4, 0, 0}, {-1, 0, 0}), 0.0, 1.9, 1e-6)
          .has_value());
  // Nothing moves.
  EXPECT_FALSE(
      TimeOfImpact(ball, Static({0, 0, 0}), ball, Static({4, 0, 0}), 0.0, 1.0, 1e-6).has_value());
}

TEST(TimeOfImpact, StartingOverlappedReportsTheStartTime) {
  const Piece box = Box({0.5, 0.5, 0.5});
  const auto impact =
      TimeOfImpact(box, Static({0, 0, 0}), box, Linear({0.5, 0, 0}, {1, 0, 0}), 0.25, 1.0, 1e-6);
  ASSERT_TRUE(impact.has_value());
  EXPECT_EQ(impact->time, 0.25);
  EXPECT_TRUE(impact->contact.overlapping);
}

TEST(TimeOfImpact, SharedCacheKeepsQueriesCheapAndResultsDeterministic) {
  const Piece box = Box({0.5, 0.5, 0.5});
  const Piece wall = Box({0.05, 2, 2});
  const Motion mbox = Spinning({0, 0, 0}, {1, 0, 0}, 5.0);
  DistanceCache cache;
  const auto first = TimeOfImpact(box, mbox, wall, Static({3, 0, 0}), 0.0, 5.0, 1e-9, &cache);
  const auto second = TimeOfImpact(box, mbox, wall, Static({3, 0, 0}), 0.0, 5.0, 1e-9);
  ASSERT_TRUE(first && second);
  EXPECT_NEAR(first->time, second->time, 1e-12);
  const auto again = TimeOfImpact(box, mbox, wall, Static({3, 0, 0}), 0.0, 5.0, 1e-9);
  EXPECT_EQ(again->time, second->time);
  EXPECT_EQ(again->iterations, second->iterations);
}

}  // namespace
}  // namespace asgard::collide
