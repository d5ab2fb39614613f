// Analysis queries: Variables, DependsOnTime, TimeBreakpoints.
#include <gtest/gtest.h>

#include <vector>

#include "core/expr/expr.h"
#include "tests/expr/test_util.h"

namespace asgard::expr {
namespace {

using testing::P;

TEST(Analysis, VariablesAreSortedAndUnique) {
  Pool pool;
  EXPECT_EQ(pool.Variables(P(pool, "tr1.dy*x + sin(x)*b1.x - x")), (std::vector<int>{0, 3, 5}));
  EXPECT_EQ(pool.Variables(P(pool, "t*ext0 + 2")), std::vector<int>{});
  EXPECT_EQ(pool.Variables(P(pool, "x - x + y")), std::vector<int>{1});
}

TEST(Analysis, DependsOnTimeSeesTimeAndExternals) {
  Pool pool;
  EXPECT_TRUE(pool.DependsOnTime(P(pool, "x + t")));
  EXPECT_TRUE(pool.DependsOnTime(P(pool, "ext1.d2*x")));
  EXPECT_FALSE(pool.DependsOnTime(P(pool, "x*y + 3")));
  EXPECT_FALSE(pool.DependsOnTime(P(pool, "t - t + x")));
  EXPECT_THROW(pool.DependsOnTime(99999), std::invalid_argument);
  EXPECT_THROW(pool.Variables(99999), std::invalid_argument);
}

struct BreakpointCase {
  const char* text;
  double t0, t1;
  std::vector<double> expected;
};

TEST(Analysis, TimeBreakpointsSolveForJumpAndKinkTimes) {
  const BreakpointCase cases[] = {
      {"t > 2", 0, 5, {2}},
      {"t > 7", 0, 5, {}},
      {"2 < t", 0, 5, {2}},
      {"2*t - 1 <= 0 ? x : y", 0, 5, {0.5}},
      {"x*(t > 1) + (t >= 3)*y", 0, 5, {1, 3}},
      {"t > 2 && t < 3", 0, 5, {2, 3}},
      {"(3 - t)/2 == 1", 0, 5, {1}},
      {"floor(t/0.5)", 0, 2, {0, 0.5, 1, 1.5, 2}},
      {"ceil(t - 0.25)", 0, 2, {0.25, 1.25}},
      {"abs(t - 1)*x", 0, 5, {1}},
      {"sign(3 - t)", 0, 5, {3}},
      {"fmod(t, 0.25)", 0, 1, {0, 0.25, 0.5, 0.75, 1}},
      {"t % 2", 0.5, 5, {2, 4}},
      {"min(t, 2) + max(t, 4)", 0, 5, {2, 4}},
      {"t > 1 ? (t > 2 ? 1 : 2) : floor(t)", 0, 3, {0, 1, 2, 3}},
      {"!(t - 1)", 0, 5, {1}},
      {"t > 2", 2, 2, {2}},
      {"t > 2", 3, 1, {}},
      {"t*t > 4", 0, 5, {}},   // not affine: not solved for
      {"ext0 > 1", 0, 5, {}},  // trajectory values are unknown
      {"x > t", 0, 5, {}},     // depends on the state
      {"sin(t)", 0, 5, {}},
  };
  for (const BreakpointCase& c : cases) {
    Pool pool;
    const std::vector<double> got = pool.TimeBreakpoints(P(pool, c.text), c.t0, c.t1);
    ASSERT_EQ(got.size(), c.expected.size()) << c.text;
    for (size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], c.expected[i], 1e-12) << c.text;
  }
}

TEST(Analysis, TimeBreakpointsAreCappedSortedAndUnique) {
  Pool pool;
  const std::vector<double> many = pool.TimeBreakpoints(P(pool, "floor(1000*t)"), 0, 100);
  EXPECT_EQ(many.size(), 10000u);
  EXPECT_TRUE(std::is_sorted(many.begin(), many.end()));
  const std::vector<double> merged =
      pool.TimeBreakpoints(P(pool, "floor(t) + ceil(t) + (t > 1) + fmod(t, 0.5)"), 0, 2);
  EXPECT_EQ(merged, (std::vector<double>{0, 0.5, 1, 1.5, 2}));
}

}  // namespace
}  // namespace asgard::expr
