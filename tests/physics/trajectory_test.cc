// Bézier trajectories: interpolation, derivatives, extrapolation.
#include <gtest/gtest.h>

#include "core/physics/trajectory.h"

namespace asgard::physics {
namespace {

std::vector<scene::TrajectoryKnot> Knots(std::vector<scene::TrajectoryKnot> k) { return k; }

TEST(TrajectoryCurve, PassesThroughItsKnotsAndIsC1) {
  TrajectoryCurve c(Knots({{0, {0, 0, 0}}, {1, {1, 2, 0}}, {3, {2, 0, 1}}, {4, {0, 0, 0}}}));
  for (size_t i = 0; i < c.times.size(); ++i)
    EXPECT_LT((c.Value(c.times[i]) - c.points[i]).norm(), 1e-14);
  for (double knot : {1.0, 3.0}) {
    const double e = 1e-9;
    EXPECT_LT((c.Value(knot - e, 1) - c.Value(knot + e, 1)).norm(), 1e-7);
  }
}

TEST(TrajectoryCurve, DerivativesMatchDifferenceQuotients) {
  TrajectoryCurve c(Knots({{0, {0, 0, 0}}, {1, {1, 2, 0}}, {3, {2, 0, 1}}}));
  for (double t : {0.2, 0.7, 1.5, 2.9}) {
    const double h = 1e-6;
    for (int order = 0; order < 3; ++order) {
      const Eigen::Vector3d fd = (c.Value(t + h, order) - c.Value(t - h, order)) / (2 * h);
      EXPECT_LT((fd - c.Value(t, order + 1)).norm(), 1e-6 * (1 + fd.norm())) << t << " " << order;
    }
  }
}

TEST(TrajectoryCurve, ExtrapolatesLinearlyOutsideItsKnots) {
  TrajectoryCurve c(Knots({{1, {0, 0, 0}}, {2, {1, 0, 0}}}));
  EXPECT_NEAR(c.Value(3).x(), 2.0, 1e-14);
  EXPECT_NEAR(c.Value(0).x(), -1.0, 1e-14);
  EXPECT_EQ(c.Value(5, 2).norm(), 0.0);
  TrajectoryCurve single(Knots({{1, {4, 5, 6}}}));
  EXPECT_EQ(single.Value(7).y(), 5.0);
}

}  // namespace
}  // namespace asgard::physics
