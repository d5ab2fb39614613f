// Exact bounds on a waveform's interpolant pieces (hermite_range.h): the
// range against dense sampling, the halving search for the first span that
// leaves a box against a span-by-span scan, the rate bound against sampling.
#include "core/solver/hermite_range.h"

#include <gtest/gtest.h>

#include <random>

namespace asgard::solver {
namespace {

Cubic RandomCubic(std::mt19937_64& rng, bool bubble) {
  std::uniform_real_distribution<double> value(-2.0, 2.0), rate(-6.0, 6.0), h(0.01, 3.0);
  const double step = h(rng);
  return HermiteCubic(value(rng), rate(rng), value(rng), rate(rng), step,
                      bubble ? 0.5 * value(rng) : 0.0);
}

// The range holds every sampled value of the piece (bubble included), and
// with no bubble it is attained: its ends are values of the cubic.  Samples
// 1e-4 apart come within (1e-4)² |p''| / 8 of an interior extreme.
TEST(HermiteRange, ValueRangeHoldsTheSampledValuesAndIsAttainedWithoutBubble) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 400; ++trial) {
    const bool bubble = trial % 2 == 1;
    const Cubic p = RandomCubic(rng, bubble);
    double s0 = unit(rng), s1 = unit(rng);
    if (s0 > s1) std::swap(s0, s1);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    ValueRange(p, s0, s1, lo, hi);
    double smin = std::numeric_limits<double>::infinity(), smax = -smin;
    const int n = 10000;
    double second = 0;
    for (int k = 0; k <= n; ++k) {
      const double s = s0 + (s1 - s0) * k / n;
      const double v = p(s);
      smin = std::min(smin, v);
      smax = std::max(smax, v);
      second = std::max(second, std::abs(p.Second(s)));
    }
    const double round = 1e-13 * (1 + std::abs(lo) + std::abs(hi));
    ASSERT_LE(lo, smin + round) << trial;
    ASSERT_GE(hi, smax - round) << trial;
    if (!bubble) {
      const double gap = 1e-8 * second / 8 + round;
      ASSERT_GE(lo, smin - gap) << trial;
      ASSERT_LE(hi, smax + gap) << trial;
    }
  }
}

// The span-by-span answer FirstSpanLeaving must equal: the first span, of
// width ds from s0 (the last one ending at s1), whose range leaves [lo, hi].
double FirstSpanLeavingByScan(const Cubic& p, double s0, double s1, double ds, double lo,
                              double hi) {
  if (!(s1 > s0)) return -1;
  const double spans = std::max(1.0, std::ceil((s1 - s0) / ds));
  for (double k = 0; k < spans; ++k) {
    double l = std::numeric_limits<double>::infinity(), h = -l;
    ValueRange(p, s0 + k * ds, k + 1 >= spans ? s1 : std::min(s1, s0 + (k + 1) * ds), l, h);
    if (l < lo || h > hi) return s0 + k * ds;
  }
  return -1;
}

// Random pieces, spans from one to thousands, boxes that the piece stays in,
// leaves early, leaves late or leaves only in its last span.
TEST(HermiteRange, FirstSpanLeavingEqualsASpanBySpanScan) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int inside = 0, leaving = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Cubic p = RandomCubic(rng, trial % 3 == 0);
    double s0 = unit(rng), s1 = unit(rng);
    if (s0 > s1) std::swap(s0, s1);
    const double ds = (s1 - s0) * std::pow(10.0, -3 * unit(rng)) * (0.5 + unit(rng));
    // A box around the piece's value somewhere in [s0, s1], of a random size.
    const double at = p(s0 + (s1 - s0) * unit(rng));
    const double lo = at - 3 * unit(rng) * unit(rng), hi = at + 3 * unit(rng) * unit(rng);
    const double fast = FirstSpanLeaving(p, s0, s1, ds, lo, hi);
    ASSERT_EQ(fast, FirstSpanLeavingByScan(p, s0, s1, ds, lo, hi))
        << "trial " << trial << " s0 " << s0 << " s1 " << s1 << " ds " << ds;
    (fast < 0 ? inside : leaving) += 1;
  }
  // Both outcomes are exercised.
  EXPECT_GT(inside, 300);
  EXPECT_GT(leaving, 300);
}

TEST(HermiteRange, FirstSpanLeavingFindsALeaveInTheLastSpanOnly) {
  // x(s) = s on [0, 1]: rate 1 over an interval of length 1.
  const Cubic p = HermiteCubic(0, 1, 1, 1, 1, 0);
  // 1000 spans of 1e-3; the box ends inside the last one.
  EXPECT_EQ(FirstSpanLeaving(p, 0, 1, 1e-3, -1, 0.9995), 999 * 1e-3);
  EXPECT_EQ(FirstSpanLeaving(p, 0, 1, 1e-3, -1, 1.0), -1);
  EXPECT_EQ(FirstSpanLeaving(p, 0, 1, 1e-3, 0.0005, 2), 0);
  EXPECT_EQ(FirstSpanLeaving(p, 0.5, 0.5, 1e-3, 2, 3), -1);  // empty interval
}

TEST(HermiteRange, RateMaxBoundsTheSampledRate) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0), h(0.01, 3.0);
  for (int trial = 0; trial < 400; ++trial) {
    const Cubic p = RandomCubic(rng, trial % 2 == 1);
    double s0 = unit(rng), s1 = unit(rng);
    if (s0 > s1) std::swap(s0, s1);
    const double step = h(rng);
    const double bound = RateMax(p, s0, s1, step);
    for (int k = 0; k <= 1000; ++k) {
      const double s = s0 + (s1 - s0) * k / 1000;
      ASSERT_LE(std::abs(p.Derivative(s)) / step, bound * (1 + 1e-12)) << trial;
    }
  }
}

// The second derivative's bound holds the sampled values, and is reached on
// the whole interval for a pure bubble (its 2e at the ends, −e between).
TEST(HermiteRange, SecondBoundBoundsTheSampledSecondDerivative) {
  std::mt19937_64 rng(14);
  std::uniform_real_distribution<double> unit(0.0, 1.0), h(0.01, 3.0), ref(-5.0, 5.0);
  for (int trial = 0; trial < 400; ++trial) {
    const Cubic p = RandomCubic(rng, trial % 2 == 1);
    double s0 = unit(rng), s1 = unit(rng);
    if (s0 > s1) std::swap(s0, s1);
    const double step = h(rng), r = ref(rng);
    const double bound = SecondBound(p, s0, s1, step, r);
    for (int k = 0; k <= 1000; ++k) {
      const double s = s0 + (s1 - s0) * k / 1000;
      ASSERT_LE(std::abs(p.Second(s) / (step * step) - r), bound * (1 + 1e-12)) << trial;
    }
  }
  const Cubic bubble{0, 0, 0, 0, 1.0};  // e s²(1−s)², e = 1, on h = 1
  EXPECT_DOUBLE_EQ(bubble.Second(0.5), -1.0);
  EXPECT_LE(std::abs(bubble.Second(0.5) - 2.0), SecondBound(bubble, 0, 1, 1, 2.0));
  EXPECT_DOUBLE_EQ(SecondBound(bubble, 0, 1, 1, 2.0), 3.0);
}

}  // namespace
}  // namespace asgard::solver
