// Waveform storage, truncation and Hermite interpolation.
#include "core/solver/waveform.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace asgard::solver {
namespace {

TEST(Waveform, HermiteInterpolationIsExactForCubics) {
  Waveform w(1);
  auto x = [](double t) { return 1 + 2 * t - 3 * t * t + 0.5 * t * t * t; };
  auto f = [](double t) { return 2 - 6 * t + 1.5 * t * t; };
  for (double t : {0.0, 0.5, 2.0}) {
    const double xv = x(t), fv = f(t);
    w.Append(t, &xv, &fv, {});
  }
  for (double t = 0; t <= 2; t += 0.01) {
    EXPECT_NEAR(w.Value(0, t, Side::kRight), x(t), 1e-13);
    EXPECT_NEAR(w.Rate(0, t, Side::kRight), f(t), 1e-12);
  }
}

TEST(Waveform, JumpsHaveDistinctLeftAndRightLimits) {
  Waveform w(1);
  const double zero = 0, one = 1, two = 2;
  w.Append(0, &zero, &zero, {});
  w.Append(1, &one, &zero, {});
  w.Append(1, &two, &zero, {0.1, true});
  w.Append(2, &two, &zero, {});
  EXPECT_EQ(w.Value(0, 1, Side::kLeft), 1);
  EXPECT_EQ(w.Value(0, 1, Side::kRight), 2);
  EXPECT_EQ(w.KeepIndex(1.0), 1);  // a truncation to t keeps the left limit
  EXPECT_EQ(w.KeepIndex(1.5), 2);
  EXPECT_EQ(w.KeepIndex(0.5), 0);
  w.Resize(w.KeepIndex(1.0) + 1);
  EXPECT_EQ(w.t_end(), 1);
  EXPECT_EQ(w.Value(0, 1, Side::kRight), 1);
}

// Reading several variables at once gives each one's Value and Rate bit for
// bit: inside pieces with bubbles, at samples, at a jump from either side.
TEST(Waveform, ManyVariablesAtOnceReadAsOneAtATime) {
  constexpr int n = 4;
  Waveform w(n);
  double x[n], f[n], b[n];
  auto fill = [&](double t, double shift) {
    for (int i = 0; i < n; ++i) {
      x[i] = std::sin(t * (i + 1)) + shift;
      f[i] = (i + 1) * std::cos(t * (i + 1));
      b[i] = 0.01 * (i - 1.5) * t;
    }
  };
  for (double t : {0.0, 0.3, 0.7, 0.7, 1.2}) {
    fill(t, t == 0.7 && w.size() > 2 ? 1.0 : 0.0);  // the second sample at 0.7 jumps
    w.Append(t, x, f, {}, b);
  }
  const int idx[3] = {3, 0, 2};
  for (double t : {0.0, 0.1, 0.3, 0.45, 0.7, 0.9, 1.2})
    for (Side side : {Side::kLeft, Side::kRight})
      for (bool rate : {false, true}) {
        double out[3];
        w.Interpolate(idx, 3, t, side, rate, out);
        for (int j = 0; j < 3; ++j)
          EXPECT_EQ(out[j], rate ? w.Rate(idx[j], t, side) : w.Value(idx[j], t, side))
              << t << " " << j << (rate ? " rate" : " value");
      }
}

}  // namespace
}  // namespace asgard::solver

namespace asgard::solver {
namespace {

TEST(Waveform, KeepIndexFromItsHintAnswersAsTheSearchDoes) {
  // Sample times with repeats (restarts, jumps), queries in runs, forward,
  // backward and at random, and the waveform cut back and grown again in
  // between: every answer is the definition's (the last sample before t, or
  // the first at t; sample 0 before the start).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Waveform w(1);
  std::vector<double> times;
  const double x = 0.0;
  auto grow = [&](int count) {
    double t = times.empty() ? 0.0 : times.back();
    for (int i = 0; i < count; ++i) {
      if (u(rng) > 0.2) t += u(rng) < 0.5 ? 0.25 : 0.1 * u(rng);  // else a repeat
      w.Append(t, &x, &x, SampleInfo{});
      times.push_back(t);
    }
  };
  auto expected = [&](double t) {
    const int k = static_cast<int>(std::lower_bound(times.begin(), times.end(), t) - times.begin());
    if (k < static_cast<int>(times.size()) && times[k] == t) return k;
    return std::max(0, k - 1);
  };
  grow(400);
  for (int round = 0; round < 200; ++round) {
    const double span = times.back() + 0.5;
    const double t0 = u(rng) * span - 0.25;
    for (int q = 0; q < 20; ++q) {
      // The same time again, a sample's own time, a nearby one, anywhere.
      const int pick = static_cast<int>(u(rng) * 4);
      double t = t0;
      if (pick == 1) t = times[static_cast<size_t>(u(rng) * times.size())];
      if (pick == 2) t = t0 + (u(rng) - 0.5) * 0.3;
      if (pick == 3) t = u(rng) * span - 0.25;
      ASSERT_EQ(w.KeepIndex(t), expected(t)) << "round " << round << " t " << t;
    }
    if (round % 10 == 9) {  // cut back and grow again: the hint may be past the end
      const int keep = 1 + static_cast<int>(u(rng) * (times.size() - 1));
      w.Resize(keep);
      times.resize(static_cast<size_t>(keep));
      grow(static_cast<int>(u(rng) * 100));
    }
  }
}

}  // namespace
}  // namespace asgard::solver
