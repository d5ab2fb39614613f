// Waveform storage and Hermite interpolation (design note in waveform.h).
#include "core/solver/waveform.h"

#include <algorithm>

namespace asgard::solver {

namespace {
constexpr size_t kFirstSegmentBytes = 4 * 1024;
}

Waveform::Waveform(int n) : n_(n) {
  const size_t row_bytes = 3 * sizeof(double) * static_cast<size_t>(std::max(n, 1));
  while ((row_bytes << (first_shift_ + 1)) <= kFirstSegmentBytes) ++first_shift_;
}

Waveform::Waveform(const Waveform& o) : Waveform(o.n_) {
  for (int k = 0; k < o.size(); ++k) Append(o.time(k), o.x(k), o.f(k), o.info(k), o.bubble(k));
  hint_ = o.hint_;
  keep_hint_ = o.keep_hint_;
}

Waveform& Waveform::operator=(const Waveform& o) {
  if (this != &o) *this = Waveform(o);
  return *this;
}

void Waveform::Append(double t, const double* x, const double* f, SampleInfo info,
                      const double* bubble) {
  const size_t k = times_.size();
  const size_t q = (k >> first_shift_) + 1;
  const size_t b = static_cast<size_t>(63 - __builtin_clzll(q));
  if (b == segments_.size())
    segments_.emplace_back(new double[(size_t{1} << (b + first_shift_)) * 3 * n_]);
  double* row = const_cast<double*>(Row(static_cast<int>(k)));
  std::copy(x, x + n_, row);
  std::copy(f, f + n_, row + n_);
  if (bubble)
    std::copy(bubble, bubble + n_, row + 2 * n_);
  else
    std::fill(row + 2 * n_, row + 3 * n_, 0.0);
  times_.push_back(t);
  info_.push_back(info);
}

void Waveform::Resize(int k) {
  times_.resize(k);
  info_.resize(k);
  // Keep the segments that hold samples 0 .. k−1 (and the next, to be
  // refilled at once by a resumed run).
  size_t keep = 0;
  if (k > 0)
    keep =
        static_cast<size_t>(64 - __builtin_clzll((static_cast<size_t>(k - 1) >> first_shift_) + 1));
  if (segments_.size() > keep + 1) segments_.resize(keep + 1);
}

int Waveform::KeepIndex(double t) const {
  // First sample with time >= t: the last answer or the next one when it
  // is still right (a window's bodies and variables ask for the same t in
  // runs), else a binary search.
  const int n = size();
  auto first_at_or_after = [&](int k) {
    return (k == 0 || times_[static_cast<size_t>(k) - 1] < t) &&
           (k == n || times_[static_cast<size_t>(k)] >= t);
  };
  int k = std::min(keep_hint_.get(), n);
  if (!first_at_or_after(k) && !(k < n && first_at_or_after(++k)))
    k = static_cast<int>(std::lower_bound(times_.begin(), times_.end(), t) - times_.begin());
  keep_hint_.set(k);
  if (k < n && times_[static_cast<size_t>(k)] == t) return k;
  return std::max(0, k - 1);
}

int Waveform::Locate(double t, Side side) const {
  const int n = size();
  if (n == 1) return 0;
  // The hinted segment or the next: the same answers as the searches below.
  for (int h = std::min(hint_.get(), n - 2), tries = 0; tries < 2 && h + 1 < n; ++h, ++tries) {
    const double a = times_[static_cast<size_t>(h)], b = times_[static_cast<size_t>(h) + 1];
    if (side == Side::kLeft ? (a < t && t <= b) : (a <= t && t < b)) {
      hint_.set(h);
      return h;
    }
  }
  int k;
  if (side == Side::kLeft) {
    // segment with time(k) < t <= time(k+1)
    k = static_cast<int>(std::lower_bound(times_.begin(), times_.end(), t) - times_.begin()) - 1;
  } else {
    // segment with time(k) <= t < time(k+1)
    k = static_cast<int>(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin()) - 1;
  }
  k = std::clamp(k, 0, n - 1);
  hint_.set(k);
  return k;
}

CubicWeights CubicAt(double s, double h) {
  const double s2 = s * s, s3 = s2 * s;
  return {2 * s3 - 3 * s2 + 1, (s3 - 2 * s2 + s) * h, -2 * s3 + 3 * s2, (s3 - s2) * h};
}

HermiteWeights HermiteAt(double s, double h) {
  const double s2 = s * s;
  const double u = s * (1 - s);
  const CubicWeights c = CubicAt(s, h);
  return {c.x0,
          c.f0,
          c.x1,
          c.f1,
          u * u,
          (6 * s2 - 6 * s) / h,
          3 * s2 - 4 * s + 1,
          (-6 * s2 + 6 * s) / h,
          3 * s2 - 2 * s,
          2 * u * (1 - 2 * s) / h};
}

double Waveform::Interpolate(int i, double t, Side side, bool rate) const {
  double out;
  Interpolate(&i, 1, t, side, rate, &out);
  return out;
}

double Waveform::Value(int i, double t, Side side) const { return Interpolate(i, t, side, false); }

void Waveform::Interpolate(const int* idx, int n, double t, Side side, bool rate,
                           double* out) const {
  const int k = Locate(t, side);
  // At a sample, its values.
  const double* at = nullptr;
  if (k + 1 >= size() || times_[k + 1] == times_[k] || t == times_[k])
    at = rate ? f(k) : x(k);
  else if (t == times_[k + 1])
    at = rate ? f(k + 1) : x(k + 1);
  if (at) {
    for (int j = 0; j < n; ++j) out[j] = at[idx[j]];
    return;
  }
  const double h = times_[k + 1] - times_[k];
  const HermiteWeights w = HermiteAt((t - times_[k]) / h, h);
  const double *x0 = x(k), *f0 = f(k), *x1 = x(k + 1), *f1 = f(k + 1), *b1 = bubble(k + 1);
  for (int j = 0; j < n; ++j) {
    const int i = idx[j];
    out[j] = rate ? w.d00 * x0[i] + w.d10 * f0[i] + w.d01 * x1[i] + w.d11 * f1[i] + w.db * b1[i]
                  : w.h00 * x0[i] + w.h10 * f0[i] + w.h01 * x1[i] + w.h11 * f1[i] + w.hb * b1[i];
  }
}

double Waveform::Rate(int i, double t, Side side) const { return Interpolate(i, t, side, true); }

}  // namespace asgard::solver
