// Pieces of a waveform's playback interpolant (waveform.h) as cubics in the
// interval's own time s ∈ [0, 1], and exact bounds on them over a part of
// the interval: what the collision monitor boxes bodies and follows their
// loose boxes with (collisions.cc).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace asgard::solver {

// One interval of a waveform: the Hermite cubic plus the explicit method's
// bubble e s²(1−s)² (waveform.h), s ∈ [0, 1].
struct Cubic {
  double a, b, c, d;  // cubic part: a + b s + c s² + d s³
  double e = 0.0;     // bubble coefficient
  double Hermite(double s) const { return a + s * (b + s * (c + s * d)); }
  double HermiteDerivative(double s) const { return b + s * (2 * c + 3 * s * d); }
  double operator()(double s) const {
    const double u = s * (1 - s);
    return Hermite(s) + e * u * u;
  }
  double Derivative(double s) const {
    return HermiteDerivative(s) + e * 2 * s * (1 - s) * (1 - 2 * s);
  }
  double Second(double s) const { return 2 * c + 6 * d * s + e * (2 - 12 * s + 12 * s * s); }
};

// The piece of an interval of length h from value x0, rate f0 to x1, f1.
inline Cubic HermiteCubic(double x0, double f0, double x1, double f1, double h, double bubble) {
  const double m0 = f0 * h, m1 = f1 * h;
  return {x0, m0, -3 * x0 - 2 * m0 + 3 * x1 - m1, 2 * x0 + m0 - 2 * x1 + m1, bubble};
}

// Range over [s0, s1] ⊆ [0, 1] of the cubic, exactly (its values at s0, s1
// and at the critical points inside), widened by the bubble's range (its
// e s²(1−s)² lies between 0 and e/16); merged into [lo, hi].
inline void ValueRange(const Cubic& p, double s0, double s1, double& lo, double& hi) {
  struct Widen {
    const Cubic& p;
    double &lo, &hi;
    ~Widen() {
      if (p.e > 0)
        hi += p.e / 16;
      else
        lo += p.e / 16;
    }
  } widen{p, lo, hi};
  auto take = [&](double s) {
    if (s < s0 || s > s1) return;
    const double v = p.Hermite(s);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  };
  take(s0);
  take(s1);
  const double A = 3 * p.d, B = 2 * p.c, C = p.b;
  if (A == 0) {
    if (B != 0) take(-C / B);
    return;
  }
  const double disc = B * B - 4 * A * C;
  if (disc < 0) return;
  const double r = std::sqrt(disc);
  take((-B - r) / (2 * A));
  take((-B + r) / (2 * A));
}

// Of the spans [s0 + k ds, s0 + (k + 1) ds) ∩ [s0, s1), the start of the
// first over which p leaves [lo, hi], or −1 when it stays inside on all.
// Halving the spans where the range leaves: a piece inside throughout costs
// one range however many spans it has (a rest step over the whole run spans
// every window), one that leaves costs a range per halving.  Exact: a
// range's extremes are values at span ends and at the cubic's own critical
// points, so a range that leaves has a half that leaves.
inline double FirstSpanLeaving(const Cubic& p, double s0, double s1, double ds, double lo,
                               double hi) {
  if (!(s1 > s0)) return -1;
  const double spans = std::max(1.0, std::ceil((s1 - s0) / ds));
  auto leaves = [&](double k0, double k1) {
    double l = std::numeric_limits<double>::infinity(),
           h = -std::numeric_limits<double>::infinity();
    // The last span ends at s1 however s0 + spans · ds rounds.
    ValueRange(p, s0 + k0 * ds, k1 >= spans ? s1 : std::min(s1, s0 + k1 * ds), l, h);
    return l < lo || h > hi;
  };
  double k0 = 0, k1 = spans;
  if (!leaves(k0, k1)) return -1;
  while (k1 - k0 > 1) {
    const double mid = std::floor(0.5 * (k0 + k1));
    if (leaves(k0, mid))
      k1 = mid;
    else
      k0 = mid;
  }
  return s0 + k0 * ds;
}

// A bound on |p'| / h over [s0, s1]: the largest rate of the piece there.
inline double RateMax(const Cubic& p, double s0, double s1, double h) {
  double m = std::max(std::abs(p.HermiteDerivative(s0)), std::abs(p.HermiteDerivative(s1)));
  if (p.d != 0) {
    const double s = -p.c / (3 * p.d);
    if (s > s0 && s < s1) m = std::max(m, std::abs(p.HermiteDerivative(s)));
  }
  // |d/ds e s²(1−s)²| = |e| · 2s(1−s)|1−2s| ≤ |e| √3/9 < 0.2 |e| (at
  // s = 1/2 ± 1/√12).
  return (m + 0.2 * std::abs(p.e)) / h;
}

// A bound on |p''/h² − ref| over [s0, s1]: how far the piece's second
// derivative (per unit time²) strays from ref there.  The cubic's part is
// linear in s, so it lies between its values at the ends; the bubble's,
// e (2 − 12 s + 12 s²), lies in [−e, 2e] (or [2e, −e]) on [0, 1], so it
// differs from any convex combination of its end values by at most 3|e|.
inline double SecondBound(const Cubic& p, double s0, double s1, double h, double ref) {
  const double h2 = h * h;
  return std::max(std::abs(p.Second(s0) / h2 - ref), std::abs(p.Second(s1) / h2 - ref)) +
         3 * std::abs(p.e) / h2;
}

}  // namespace asgard::solver
