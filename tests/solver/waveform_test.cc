// Waveform storage, truncation and Hermite interpolation.
#include "core/solver/waveform.h"

#include <gtest/gtest.h>

#include <cmath>

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
