// Waveforms: the computed history of one component's state variables.
//
// A component's variables share one time scale (seed 5.1.3 keeps a time scale
// per variable; every variable belongs to exactly one component, so one scale
// per component is the same thing without the duplication).  Each sample
// holds the state x and its rate f = ẋ, so values between samples are the
// cubic Hermite interpolant of (x, f) at both ends.  For a trapezoidal step
// this cubic is exactly the quadratic the rule assumes (f linear over the
// step), so what is played back is what was integrated (seed 4.1.9).
//
//   x ▲        ●━━━━━●
//     │   ●━━━━┛     ┃ jump: two samples at one time (left and right limit)
//     │ ●━┛          ●━━━━●
//     └──────────────────────▶ t
//
// A step of a higher-order method (the explicit Dormand–Prince pair) adds a
// bubble term to the interval it ends: x(θ) = H(θ) + θ²(1−θ)² b, θ ∈ [0, 1],
// with H the cubic Hermite interpolant.  That is the method's own continuous
// extension (4th order), so playback, collision checks and the components
// that read this one between samples see what the method computed, to its
// order.  Intervals of trapezoidal and TR-BDF2 steps have b = 0.
//
// A sample also records what the integrator needs to continue from it
// exactly as it did the first time (next step size, whether the step history
// restarts there), so truncating to a sample and resuming reproduces the
// original computation bit for bit.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace asgard::solver {

enum class Side : uint8_t { kLeft, kRight };

// The weights of a step's cubic Hermite interpolant with its bubble, at the
// fraction s of a step of length h: value = h00·x0 + h10·f0 + h01·x1 +
// h11·f1 + hb·b (b the bubble θ²(1−θ)² coefficient), rate likewise with the
// d weights (already divided by h where needed).
struct HermiteWeights {
  double h00, h10, h01, h11, hb;
  double d00, d10, d01, d11, db;
};
HermiteWeights HermiteAt(double s, double h);
// The value weights alone (HermiteAt's h00, h10, h01, h11, without the
// divisions its rate weights need): for a cubic's value, in or beyond its
// step (the ESDIRK's stage predictors extrapolate with it).
struct CubicWeights {
  double x0, f0, x1, f1;
};
CubicWeights CubicAt(double s, double h);

// What the integrator needs to continue from a sample exactly as it did the
// first time.
struct SampleInfo {
  double h_next = 0.0;      // step size proposed for the step starting here
  bool restart = false;     // no usable step history before this sample
  bool implicit = false;    // the component was integrating implicitly (stiff) here
  uint8_t stiff_votes = 0;  // steps that argued for the other method
  uint8_t calm_votes = 0;   // explicit: consecutive steps that did not look stiff
  // Returns from implicit to explicit steps made because the explicit ones
  // were the cheaper (component.cc, kMaxReturns): each doubles the votes
  // the next switch to implicit steps needs.  Kept across restarts.
  uint8_t cheaper_returns = 0;
  double err_prev = 1e-4;   // last accepted error estimate (PI step control)
  long jumps_seen = 0;      // restart: the component's jump generation it applied
  // Implicit: the sample whose Jacobian the step from here reuses (−1: take
  // it here).  Kept with the sample so a resumed run reuses the same one.
  int jac_from = -1;
  // Implicit: the cost of a step (right-hand sides and factorizations,
  // rejected attempts included), averaged over the last steps; 0: none yet.
  float implicit_cost = 0.0f;
  // Implicit: Newton's factor ρ/(1−ρ) as the step into this sample left it,
  // the next step's start (component.cc, EtaDrift; 10: not known).
  double newton_eta = 10.0;
  // Implicit: the largest step Newton's failures allow from here
  // (component.cc, kNewtonCap).
  double h_newton = std::numeric_limits<double>::infinity();
};

class Waveform {
 public:
  explicit Waveform(int n = 0);
  Waveform(const Waveform& o);
  Waveform& operator=(const Waveform& o);
  Waveform(Waveform&&) = default;
  Waveform& operator=(Waveform&&) = default;

  int variable_count() const { return n_; }
  int size() const { return static_cast<int>(times_.size()); }
  bool empty() const { return times_.empty(); }
  double time(int k) const { return times_[k]; }
  double t_end() const { return times_.back(); }
  const double* x(int k) const { return Row(k); }
  const double* f(int k) const { return Row(k) + n_; }
  // Bubble coefficients of the interval ending at sample k (zero: none).
  const double* bubble(int k) const { return Row(k) + 2 * n_; }
  const SampleInfo& info(int k) const { return info_[k]; }
  SampleInfo& info(int k) { return info_[k]; }

  // `bubble` (may be null: zero) belongs to the interval from the previous
  // sample to this one.
  void Append(double t, const double* x, const double* f, SampleInfo info,
              const double* bubble = nullptr);
  // Keeps samples 0..k.
  void Resize(int k_plus_one);
  // Index of the sample that a truncation to time t keeps last: the last
  // sample with time < t, or the first sample at exactly t (its left limit).
  int KeepIndex(double t) const;

  // Value and rate of local variable i at time t, t within [time(0), t_end()].
  // At a jump, kLeft gives the limit from below and kRight from above.
  double Value(int i, double t, Side side) const;
  double Rate(int i, double t, Side side) const;
  // The values (rates) of local variables idx[0..n) at t, the segment
  // located and its weights computed once (each as Value or Rate gives it,
  // bit for bit).
  void Interpolate(const int* idx, int n, double t, Side side, bool rate, double* out) const;

 private:
  // Segment [k, k+1] containing t (k+1 < size), or the last sample (k+1 == size).
  int Locate(double t, Side side) const;
  double Interpolate(int i, double t, Side side, bool rate) const;

  // Segment b holds rows first_rows_·2^b, from sample first_rows_·(2^b − 1).
  const double* Row(int k) const {
    const size_t q = (static_cast<size_t>(k) >> first_shift_) + 1;
    const int b = 63 - __builtin_clzll(q);
    const size_t off = static_cast<size_t>(k) - (((size_t{1} << b) - 1) << first_shift_);
    return segments_[static_cast<size_t>(b)].get() + off * 3 * n_;
  }

  int n_;
  std::vector<double> times_;
  // Sample k's row x | f | bubble (3n values) lives in a segment that never
  // moves; each segment doubles the last (the first about 4 KiB), and is
  // left uninitialized, so appending copies only the new row and touches
  // only the memory the samples fill.  Contiguous vectors grown by doubling
  // had reallocated, copied and first-touched every sample again at each
  // doubling — 30% of the double pendulum's run in page faults.
  std::vector<std::unique_ptr<double[]>> segments_;
  int first_shift_ = 0;
  std::vector<SampleInfo> info_;
  // A search's starting guess, read and written by readers on any thread
  // (two components stepping at once may read one input): relaxed atomic,
  // since any value gives the same answer.
  class Hint {
   public:
    Hint() = default;
    Hint(const Hint& o) : v_(o.get()) {}
    Hint& operator=(const Hint& o) {
      set(o.get());
      return *this;
    }
    int get() const { return v_.load(std::memory_order_relaxed); }
    void set(int v) const { v_.store(v, std::memory_order_relaxed); }

   private:
    mutable std::atomic<int> v_{0};
  };
  // The segment the last lookup found: lookups come in runs close in time
  // (collision queries, readers' steps), so most need no binary search.
  Hint hint_;
  Hint keep_hint_;  // KeepIndex's last first-sample-at-or-after
};

}  // namespace asgard::solver
