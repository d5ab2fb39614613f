// A component: one strongly connected block of state equations, integrated
// with its own adaptive step (seed 5.2, 5.2.1).
//
// Method (chosen per component, re-chosen during the run):
//
//   non-stiff ──▶ Tsitouras 5(4) or Dormand–Prince 5(4) (SolverOptions::pair),
//                 explicit, FSAL; PI step control
//                 (h_new = h · 0.9 err^−0.17 err_prev^0.04); its 4th-order
//                 continuous extension goes into the waveform as a bubble
//   stiff ─────▶ ESDIRK 3(2) (esdirk.h): explicit first stage, three
//                implicit stages sharing the matrix I − γhJ, stiffly
//                accurate, L-stable, order 3 with an order-2 estimate
//   rows prescribed, not stiff ──▶ trapezoidal rule (TR)
//                                   y = x + h/2 (f(x) + f(y))   the seed's rule
//   --method tr | trbdf2: TR, and TR-BDF2 (γ = 2 − √2) where TR would be
//                stiff or has no history:
//                y_γ = x + γh/2 (f(x) + f(y_γ))
//                y = (y_γ − (1−γ)² x)/(γ(2−γ)) + d h f(y),  d = γ/2
//                (both stages use I − d h J)
//
//   Stiffness is judged from the spectral radius ρ of ∂f/∂x, never from a
//   matrix norm (the quaternion and angular-velocity rows make ‖J‖ orders
//   of magnitude larger than any eigenvalue): at the start, by power
//   iteration on the Jacobian (stiff above 500/s); while explicit, from the
//   last two stages (Hairer's estimate hρ ≈ h‖k₇−k₆‖/‖y₁−y₆‖; 15 steps above
//   3.25 switch to implicit); while implicit, by power iteration at each
//   Jacobian (15 steps whose next hρ < 1 switch back).  The votes travel with
//   the samples, so a truncated component resumes with the same decisions.
//   Rows that a trajectory or a resting contact prescribes always take the
//   implicit path.
//
//   Rejected: (1) one method everywhere — a 2nd-order method needs ~10× the
//   steps of a 5th-order one for 1e-6 on a pendulum, an explicit one cannot
//   cross a stiff link's transient; (2) Rosenbrock methods — they need an
//   exact Jacobian every step, which exact joints do not have symbolically;
//   (3) TR-BDF2 for stiff components: order 2, so at
//   tol 1e-6 a stiff link took ~10× the steps of CVODE's order-5 BDF on its
//   smooth forced motion; (4) Radau IIA 5: a 3n×3n (or complex n×n) system
//   per iteration, where the ESDIRK's stages reuse one real n×n LU.
//
//   TR is A-stable but its amplification tends to −1 for h|λ| → ∞: a stiff,
//   critically damped link then rings instead of settling.  The ESDIRK is
//   L-stable (amplification → 0).  A component that is implicit because it
//   is stiff takes ESDIRK steps; one that is implicit only because a
//   trajectory or a hold prescribes rows takes TR steps while it has a step
//   history and hρ ≤ 3 (one Newton solve a step), ESDIRK steps otherwise.
//
// Exact joints (physics/joints.h) are applied after the tape inside every
// evaluation of f; a component holding jointed bodies takes its Jacobian by
// difference quotients of the whole f.
//
// Newton: the iteration matrix M = I − a J is built from the Jacobian of a
// recent sample (symbolic, or differenced for small components; reused
// while Newton converges briskly) and factored once per step size (dense
// LU or KLU, see linear_solver.h); iterations stop when the remaining
// error, estimated from the contraction rate ρ as ‖Δ‖ρ/(1−ρ), is below 1e-4
// of the tolerance (kNewtonTol, component.cc, says why so far below).  An
// ESDIRK stage starts from a cubic: the first implicit stage from the last
// step's, carried on to its time; the later ones from the cubic through
// the sample and the first implicit stage.
//
// Error control: weights w = atol + rtol·max(|x|, |y|), max norm.
//   DP5:     the embedded 5th − 4th order difference.
//   TR:      LTE ≈ h³/6 · f[t₋₁, t₀, t₁]   (second divided difference of f)
//   TR-BDF2: LTE ≈ 2Ch (f₀/γ − f_γ/(γ(1−γ)) + f₁/(1−γ)), C = (−3γ²+4γ−2)/(12(2−γ)),
//            filtered through M⁻¹ (Hosea & Shampine 1996) so stiff modes
//            that have decayed do not hold the step down.
//   ESDIRK:  h Σ (b − b̂)_i k_i, filtered through M⁻¹ likewise; and the
//            step's interpolant (cubic Hermite) against the stage at
//            t + 0.6h, row j divided by 1 − γhJ_jj (DenseError): a stiff
//            link that holds a body to a moving point has exact step ends
//            at any h, and only this check keeps the path between them.
//   h_next = h · clamp(0.9 err^(−1/3), 0.2, 5)  (every implicit estimate is
//   of order 3 in h).
//
// Rest steps (seed 5.2.4: skip what a scene does not need): at a sample of
// an autonomous mode with no inputs, where the state would move over a span
// H by H·f and H²/2·J f, both below 1e-3 of the tolerance (J f by one
// difference of f along f), the state is kept over H with no integration —
// for ever (up to the next breakpoint) when every rate is zero, counting a
// rate within 64 ulps of the free rate a joint force cancels as zero.  A
// body hanging at rest, a velocity with no force on it, a sleeping body:
// one step per breakpoint, whatever the duration.  An unstable equilibrium
// a rounding away fails the second-order test and is integrated.  Rejected:
// velocity thresholds with a sleep timer (game engines) — they freeze slow
// motion and wake late; this test is against the tolerance.
//
// Breakpoints (trajectory interval ends, t compared with constants, knots,
// collisions): a step never crosses one; it lands on it exactly, and the
// component restarts there with a new sample holding the right-hand limits.
//
// Modes: while a trajectory prescribes a variable (seed 5.1.3) its row is
// x = g(t, ...) instead of ẋ = f; the set of active rows is the component's
// mode, constant between breakpoints.  Tapes and factorizations are cached
// per mode.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/expr/expr.h"
#include "core/solver/linear_solver.h"
#include "core/solver/waveform.h"

namespace asgard::physics {
struct EquationSystem;
class JointSolver;
}  // namespace asgard::physics

namespace asgard::solver {

struct ExplicitPair;  // explicit_pair.h

struct SolverOptions {
  double rtol = 1e-6;
  double atol = 1e-9;
  double initial_step = 0.0;  // 0: 1e-4 of the interval
  double max_step = 0.0;      // 0: the whole interval
  bool partition = true;      // false: one component for everything
  bool fuse_chains = true;    // fuse one-to-one chains of components (partition.h)
  // With fuse_chains: fuse a body's components where they form an island
  // (partition.h), unless a trajectory prescribes one of its variables.
  bool fuse_bodies = true;
  enum class Schedule : uint8_t { kEventDriven, kSequential };
  Schedule schedule = Schedule::kEventDriven;
  // kAuto: the explicit pair where the component is not stiff, the ESDIRK
  // where it is (decided from a spectral-radius estimate and
  // re-decided during the run).  kExplicit: always Dormand–Prince (rows a
  // trajectory or a hold prescribes still use the implicit path).
  // kEsdirk: always the implicit ESDIRK 3(2) (esdirk.h); kTrapezoidal: TR,
  // with TR-BDF2 where stiff or without history; kTrBdf2: always TR-BDF2.
  enum class Method : uint8_t { kAuto, kTrapezoidal, kTrBdf2, kExplicit, kEsdirk };
  Method method = Method::kAuto;
  // The explicit pair: Tsitouras 5(4) (smaller error constants at the same
  // 7 stages, FSAL, 4th-order dense output; 8–19% fewer evaluations than
  // Dormand–Prince at equal error on the pendulum scenes) or Dormand–Prince.
  enum class Pair : uint8_t { kDormandPrince, kTsitouras };
  Pair pair = Pair::kTsitouras;
  int dense_limit = 40;  // larger components use KLU
  // Threads that step components at once (1 to expr::Tape::kLanes; larger
  // asks are capped).  Results are bit-identical whatever the number
  // (simulation.h, "Threads").
  int threads = 1;
};

struct Counters {
  long steps = 0;
  long rejected_steps = 0;
  long trbdf2_steps = 0;
  long esdirk_steps = 0;     // steps of the ESDIRK 3(2) (esdirk.h)
  long explicit_steps = 0;   // steps of the explicit pair
  long method_switches = 0;  // explicit ⇄ implicit decisions
  long rhs_evaluations = 0;
  long jacobian_evaluations = 0;
  long factorizations = 0;
  long newton_iterations = 0;
  long newton_failures = 0;
  long truncated_steps = 0;
  long restarts = 0;
  long rest_steps = 0;       // steps that kept a state at rest (RestSpan)
  long ballistic_steps = 0;  // exact steps of motion under constant forces

  Counters& operator+=(const Counters& o);
};

// Every counter with its name: the one list that sums and reports read.
struct CounterField {
  const char* name;
  long Counters::*member;
};
// Each name is its member's, written once.  (A table: laid out by hand.)
// clang-format off
#define ASGARD_COUNTER(m) CounterField{#m, &Counters::m}
inline constexpr CounterField kCounterFields[] = {
    ASGARD_COUNTER(steps), ASGARD_COUNTER(rejected_steps), ASGARD_COUNTER(trbdf2_steps),
    ASGARD_COUNTER(esdirk_steps), ASGARD_COUNTER(explicit_steps), ASGARD_COUNTER(method_switches),
    ASGARD_COUNTER(rhs_evaluations), ASGARD_COUNTER(jacobian_evaluations),
    ASGARD_COUNTER(factorizations), ASGARD_COUNTER(newton_iterations),
    ASGARD_COUNTER(newton_failures), ASGARD_COUNTER(truncated_steps), ASGARD_COUNTER(restarts),
    ASGARD_COUNTER(rest_steps), ASGARD_COUNTER(ballistic_steps)};
#undef ASGARD_COUNTER
// clang-format on
static_assert(sizeof(kCounterFields) / sizeof(kCounterFields[0]) * sizeof(long) == sizeof(Counters),
              "every member of Counters is in kCounterFields");

class Simulation;

class Component {
 public:
  Component(Simulation& sim, int index, std::vector<int> vars);
  ~Component();
  Component(const Component&) = delete;
  Component& operator=(const Component&) = delete;

  int index() const { return index_; }
  const std::vector<int>& variables() const { return vars_; }
  const std::vector<int>& inputs() const { return inputs_; }
  const Waveform& waveform() const { return wave_; }
  const Counters& counters() const { return counters_; }
  double t_end() const { return wave_.t_end(); }
  bool finished() const;

  // Sets up inputs and breakpoints; requires every upstream component's
  // initial sample (call in dependency order).
  void Initialize();
  // Rebuilds the first sample from the (possibly changed) initial values of
  // the variables and the inputs' first samples; drops everything after it.
  void StartSample();
  // End time of the next step (after clipping to breakpoints and the end).
  double NextEnd() const;
  // Takes one accepted step (restarting first at a pending breakpoint).
  // Returns false on failure; error() says why.
  bool Step();
  const std::string& error() const { return error_; }
  // The lane (Simulation::values, expr::Tape::Evaluate) of the thread that
  // steps this component next; 0 outside a parallel run.
  void set_lane(int lane) { lane_ = lane; }
  // After a failure caused by a value that is not finite: that variable
  // (global index), else -1.
  int failed_variable() const { return failed_variable_; }

  // Keeps samples up to `t` (see Waveform::KeepIndex), or with `strict` only
  // those before t; returns the time of the last sample kept.
  double Truncate(double t, bool strict = false);
  // Events added while simulating (collisions).  A jump sets local variable
  // `local` to `value` at t (right limit).  The component owns its events;
  // its dynamic breakpoints are their times plus those of every component
  // upstream (SetDynamicBreakpoints), since an upstream jump makes its
  // rates jump.
  void AddJump(double t, int local, double value);
  // Holds local variable `local` at `value` (rate 0) from t on — a dynamic
  // override of its equation, used for resting contact — until released.
  void AddHold(double t, int local, double value);
  void ReleaseHold(double t, int local);
  bool Held(int local, double t) const;
  // Takes over another component's results (samples and events) — the same
  // variables with the same equations, from an earlier form of the scene.
  void CopyResults(const Component& from);
  // Drops the events after t (with `strict`, at or after t): jumps, holds
  // starting then, and releases then.
  void ForgetAfter(double t, bool strict);
  // The dynamic breakpoints are the times of this component's own events
  // (kept up to date as they come and go) and `upstream`'s (the breakpoints
  // of the components upstream, BreakpointsInto each; sorted runs).
  void SetDynamicBreakpoints(const std::vector<double>& upstream);
  // Appends the dynamic breakpoints (own, then inherited: two sorted runs,
  // possibly with repeats) to `out`.
  void BreakpointsInto(std::vector<double>& out) const;

 private:
  struct Mode;
  // The mode's prescribed rows for the joint solver, or null when it has
  // none (it then skips every row test).
  static const char* Prescribed(const Mode& m);
  struct Attempt;

  Mode& ModeAt(double t);
  std::string ModeKey(double t) const;
  std::unique_ptr<Mode> BuildMode(const std::string& key, double t);
  // Rows of a mode in free flight under constant forces: per row, -1 where
  // the rate is a constant (or a constant prescribes the value, or the row is
  // still), else the local row whose variable the rate is; `still`: rows
  // whose rates must be zero at a sample for the mode to move so; `spins`:
  // bodies whose angular velocity is constant (its rates are exactly zero:
  // no torque, isotropic inertia), so that their orientation turns at a
  // constant rate, exactly (BallisticStep), while they fly.
  struct Spin {
    std::array<int, 4> q;  // local rows of the orientation (qw qx qy qz)
    std::array<int, 3> w;  // local rows of the angular velocity (body axes)
  };
  struct Ballistic {
    std::vector<int> rows;
    std::vector<int> still;
    std::vector<Spin> spins;
  };
  Ballistic BallisticRows(const std::vector<expr::NodeId>& outputs,
                          const std::vector<char>& prescribed) const;
  // Span over which the last sample's mode moves ballistically, or 0.
  double BallisticSpan(const Mode& m, double h);
  void BallisticStep(const Mode& m, double t, double h_max);
  // Fills the global value array with y and with the inputs at t.
  void Load(double t, const double* y, Side side);
  void EvalF(const Mode& m, double t, const double* y, double* out, Side side, bool landing);
  void PrepareJacobian(Mode& m);
  void EvalJacobian(Mode& m, double t, const double* y);
  bool FactorMatrix(Mode& m, double a);
  bool Newton(Mode& m, double t_new, double a, const double* c, double* y, double* fy,
              bool landing);
  void Rates(const Mode& m, double t, const double* y, const double* fy, const double* y0, double h,
             double* rate, Side side);
  bool TryStep(double h, bool landing, bool fresh_jacobian, Attempt& out);
  double DenseError(const Mode& m, double h);
  bool EsdirkStep(Mode& m, double h, bool landing);
  bool TryExplicitStep(const Mode& m, double h, bool landing, Attempt& out);
  template <const ExplicitPair& P>
  bool TryExplicitStepWith(const Mode& m, double h, bool landing, Attempt& out);
  bool UseImplicit(const Mode& m, const SampleInfo& info) const;
  // Spectral radius of ∂f/∂x (ODE rows) by power iteration on the Jacobian
  // last evaluated, or on difference quotients of f at the last sample.
  template <typename Apply>
  double PowerIteration(const Mode& m, Apply apply);
  double SpectralRadius(const Mode& m);
  double SpectralRadiusMatrixFree(const Mode& m, double t);
  bool InitialImplicit(double t);
  // `rows`: test only these rows (the still rows of a ballistic mode).
  double RestSpan(const Mode& m, double h, const std::vector<int>* rows = nullptr);
  void Restart();
  SampleInfo RestartSample(double t, const double* x, bool implicit);
  bool PendingRestart() const;
  double NextBreakpoint(double t) const;
  bool IsBreakpoint(double t) const;
  double WeightedNorm(const double* v, const double* x, const double* y) const;
  std::string Describe() const;

  // Jacobian by difference quotients of the whole right-hand side (the
  // joints' forces have no symbolic form).
  void EvalJacobianNumerically(Mode& m, double t, const double* y);

  Simulation& sim_;
  const physics::EquationSystem& sys_;
  std::unique_ptr<physics::JointSolver> joints_;  // exact links among our bodies
  bool points_autonomous_ = true;                 // no joint holds a body on a moving point
  std::vector<char> joint_rows_;                  // per local row: a joint force acts on it
  int index_;
  int lane_ = 0;
  std::vector<int> vars_;
  int first_var_ = -1;  // vars_[0] when vars_ is a run of consecutive variables
  std::vector<int> inputs_;
  std::vector<double> static_breakpoints_;
  std::vector<double> own_times_;  // own event times, sorted, with repeats
  std::vector<double> inherited_;  // upstream components' breakpoints, sorted, unique
  struct Jump {
    double t;
    int local;
    double value;
    long generation;  // jump_generation_ when it was added or last changed
  };
  std::vector<Jump> jumps_;  // in time order, ties in the order added
  // The jumps at time t: [first, last).
  std::pair<std::vector<Jump>::const_iterator, std::vector<Jump>::const_iterator> JumpsAt(
      double t) const;
  void AddTime(double t);     // into own_times_
  void RemoveTime(double t);  // one occurrence
  long jump_generation_ = 0;
  struct Hold {
    double from;
    double to;
    int local;
    double value;
  };
  std::vector<Hold> holds_;
  Waveform wave_;
  std::map<std::string, std::unique_ptr<Mode>> modes_;
  Mode* last_mode_ = nullptr;
  double mode_lo_ = 1, mode_hi_ = 0;  // interval where last_mode_ is valid
  // Jacobian cache: valid for (sample index, mode).
  int jac_sample_ = -1;
  Mode* jac_mode_ = nullptr;
  double factored_a_ = -1;
  double rho_ = 0.0;  // spectral radius estimate at the Jacobian's sample
  // Newton's ρ/(1−ρ) from the last solve that measured a contraction rate ρ
  // (component.cc: EtaDrift), from the sample a step starts at.
  double newton_eta_ = SampleInfo().newton_eta;
  Counters counters_;
  std::string error_;
  int failed_variable_ = -1;
  // Fails the step when the last sample holds a value or rate that is not
  // finite (an overflowing initial value, a force that divides by zero):
  // shrinking the step cannot help, and the message names the variable.
  bool CheckFinite();
  // Scratch vectors of n values, all in one allocation (a component is set
  // up for every idle body of a scene, so its set-up is kept small).
  struct Scratch {
    double* p = nullptr;
    size_t n = 0;
    double& operator[](size_t i) const { return p[i]; }
    double* data() const { return p; }
    double* begin() const { return p; }
    double* end() const { return p + n; }
  };
  std::unique_ptr<double[]> scratch_;
  Scratch x_, y_, fy_, yg_, fg_, c_, r_, est_, rate_, pv_, pw_, bubble_;
  Scratch k_[7];  // the explicit pair's stages
  std::vector<double> gdot_;
  std::vector<char> rest_rows_;  // RestSpan's rows
  size_t rest_veto_ = 0;         // RestSpan's last row ruling rest out (tested first)
  SampleInfo next_info_;         // method state to store with the sample a step appends
};

}  // namespace asgard::solver
