// Component integration: modes, Newton, TR and TR-BDF2 steps, restarts
// (design note in component.h).
#include "core/solver/component.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>
#include <type_traits>
#include <utility>

#include "core/physics/equations.h"
#include "core/physics/joints.h"
#include "core/solver/esdirk.h"
#include "core/solver/explicit_pair.h"
#include "core/solver/simulation.h"

namespace asgard::solver {
namespace {

const double kGamma = 2.0 - std::sqrt(2.0);
const double kD = 1.0 - 1.0 / std::sqrt(2.0);  // = γ/2 = (1−γ)/(2−γ)
const double kBdfY = 1.0 / (kGamma * (2.0 - kGamma));
const double kBdfX = (1.0 - kGamma) * (1.0 - kGamma) / (kGamma * (2.0 - kGamma));
const double kErrC = (-3 * kGamma * kGamma + 4 * kGamma - 2) / (12 * (2 - kGamma));
// Newton stops when the estimated remaining error, ‖Δ‖ ρ/(1−ρ) with ρ the
// observed contraction rate, is below this fraction of the tolerance.  Far
// below the error test's 1: the remaining error is not random from step to
// step.  A Jacobian that lags the motion (a stiff spring's direction turning
// with its body) leaves it with one sign, so it adds up over the run's
// thousands of steps where truncation errors partly cancel.  A pendulum on a
// critically damped spring of ω0 = 1000 (ESDIRK, 20 s), its error against
// the explicit pair at rtol 1e-10, at rtol 1e-2 … 1e-7: with 0.02, 2.0 (the
// energy 8 times its start), 1.5, 7.5e-2, 7.6e-3, 1.5e-3, 2.1e-4, the energy
// rising at every tolerance; with 1e-4, 4.5e-2, 3.8e-3, 9.1e-5, 3.2e-5,
// 4.0e-6, 3.4e-7 (within 5× the tolerance and falling with it, the energy
// falling by the spring's own damping), for 9–22% more right-hand sides
// and, on a linear stiff link (ω0 = 100, rtol 1e-6), 16% more instructions
// (6.0 M → 7.0 M, the same steps).
constexpr double kNewtonTol = 1e-4;
constexpr int kNewtonMaxIter = 10;
// Before a second iterate gives a rate, the first update is weighed with
// the factor η = ρ/(1−ρ) of the last solve that measured one, raised to the
// power 3/4 at each solve that does not (EtaDrift: a stale η grows back
// towards 1, and a second iterate is taken again within a few solves); an
// unknown η is kEtaUnknown, which asks the first update to be below
// kNewtonTol/kEtaUnknown^(3/4) (1.8e-5) of the tolerance.
constexpr double kEtaUnknown = SampleInfo().newton_eta;
// η^(3/4) by two square roots (a power per Newton solve was 6% of a stiff
// link's run).
double EtaDrift(double eta) {
  const double e = std::max(eta, 1e-16);
  return std::sqrt(e * std::sqrt(e));
}
// TR-BDF2 instead of TR when h·ρ(J) exceeds this: TR's amplification tends to
// −1 for stiff modes, so a mode with hλ beyond ~3 rings instead of decaying.
constexpr double kTrStiffness = 3.0;
// Dormand–Prince is stable along the negative real axis up to hλ ≈ 3.3; a
// step whose estimated hρ exceeds this is held down by stability, not accuracy.
constexpr double kExplicitStability = 3.25;
// An implicit step with hρ below this could have been taken explicitly.
constexpr double kExplicitComfort = 1.0;
// Implicit step control: h_new = h · clamp(safety · err^(−1/3), min, max)
// (TR and TR-BDF2 are 2nd order); after a Newton failure the step is cut
// by kNewtonFailureCut.
constexpr double kImplicitSafety = 0.9, kImplicitMinFactor = 0.2, kImplicitMaxFactor = 5.0;
constexpr double kNewtonFailureCut = 0.25;
// The steps after a Newton failure at h stay below kNewtonCap·h, a bound
// that relaxes by kNewtonCapGrowth at each accepted step: a simplified
// Newton whose Jacobian lags the motion fails above some step size, and
// growing back to it at once (×kImplicitMaxFactor) failed again every few
// steps: a pendulum on a stiff spring (esdirk_test), 20 s at rtol 1e-4, made
// 6 039 failures in 7 801 steps; with the bound, 1 400 in 4 601 and 28%
// fewer right-hand sides.
constexpr double kNewtonCap = 0.8, kNewtonCapGrowth = 1.02;
// Jacobian reuse: a step whose Newton solves averaged at most this many
// iterations hands its Jacobian on, for at most kMaxJacobianAge samples;
// a proposed growth of the step below kKeepStepFactor is dropped so the LU
// is kept as well.
constexpr int kReuseIterations = 3;
constexpr int kMaxJacobianAge = 20;
// Components of at most this many variables difference their Jacobian
// (PrepareJacobian).
constexpr int kNumericJacobianMax = 32;
constexpr double kKeepStepFactor = 1.2;
// Steps that must argue for the other method before it changes (one noisy
// estimate must not flip it back and forth); an explicit step size hovering
// at the stability limit alternates between looking stiff and not, so only
// kCalmVotes consecutive calm steps clear the stiff votes (as in Hairer's
// DOPRI5 detector).
constexpr int kSwitchVotes = 15;
constexpr int kCalmVotes = 6;
// A non-stiff component held to the explicit stability limit (a pendulum's
// exact joint at loose tolerance: ρ ≈ 22) switched to the ESDIRK, whose
// steps there were no longer and cost three times as much: the pendulum at
// rtol 0.1 took 2 328 right-hand sides for 10 s where at 0.01 it takes 704.
// So an implicit step also votes for explicit steps when those, at
// hρ = kExplicitStability, would have covered it for less; kCalmVotes such
// votes switch, and each such return doubles the votes the next switch to
// implicit steps needs (at most 2^kMaxReturns times), so that the two
// methods do not alternate at the limit (the pendulum at 0.1: 783).  An
// implicit step's cost is its right-hand sides plus factorizations, rejected
// attempts included (for a component small enough to difference its
// Jacobian an LU costs about a right-hand side), averaged with memory
// kCostMemory; an explicit step's is kExplicitStepCost right-hand sides
// (seven stages, the first the last step's).
constexpr double kCostMemory = 0.75;
constexpr double kExplicitStepCost = 6.0;
constexpr int kMaxReturns = 4;
// Spectral radius (1/s) above which a component starts implicitly, and
// below which alone it may switch back to explicit steps.  At ρ = 100 an
// explicit step is bounded by stability to 35 ms (Tsitouras: hλ ≥ −3.5),
// and Tsitouras' controller, once the motion is smooth, settles near hρ ≈ 3
// — just under the hρ > 3.25 that votes for the switch, so such a component
// never left explicit steps: a critically damped link of ω0 = 100 took
// 665 explicit steps for 10 s at 1e-4 where the ESDIRK takes 42.  A
// stiff component's implicit step is held small by a transient as long as
// the transient lasts (hρ < 1 for tens of steps), which is not stiffness
// gone.  Exact joints' stabilization and rigid-body rotation stay far below
// it (ρ ≈ 22–24 on every articulated benchmark scene, chains and trees
// included).
constexpr double kStartStiffRho = 100.0;
// Rest steps: a component whose state would move by at most this fraction of
// the tolerance over a span (to second order) keeps its state over it.
constexpr double kRestFraction = 1e-3;
// A rest step is taken only when it spans this many of the steps the
// integrator would take instead (else the probe costs more than it saves).
constexpr double kRestMinGain = 4.0;
// A rate this many ulps (relative) of the free rate a joint force cancels is
// that cancellation's rounding, not motion.
constexpr double kRestRounding = 64 * std::numeric_limits<double>::epsilon();
// A turning body's exact step (BallisticStep): the playback interpolant's
// error over a step of phase φ = |ω|h/2 is at most this times φ⁵ (per unit
// of the orientation's size), which bounds the step.
constexpr double kSpinInterpolation = 8e-5;

namespace dp {
// PI step control (Gustafsson): h_new = h · safety · err^−α · err_prev^β.
constexpr double kBeta = 0.04, kAlpha = 0.2 - 0.75 * kBeta, kSafety = 0.9;
constexpr double kMinFactor = 0.2, kMaxFactor = 10.0;
}  // namespace dp

}  // namespace

Counters& Counters::operator+=(const Counters& o) {
  for (const CounterField& f : kCounterFields) this->*f.member += o.*f.member;
  return *this;
}

namespace {
struct Plan {
  double t_end;
  bool landing;
};
}  // namespace

static Plan PlanStep(double t, double h, double bp, double t1) {
  const double lim = std::min(bp, t1);
  // Do not leave a sliver before the limit: stretch up to 1% to reach it.
  if (t + 1.01 * h >= lim) return {lim, lim == bp};
  return {t + h, false};
}

struct Component::Mode {
  std::vector<char> prescribed;  // per local variable
  // n outputs: ẋ (ODE rows) or g (prescribed rows); evaluated on the value
  // array offset by its shift (TapeCache: shared with identical components).
  TapeCache::Shared f_tape;
  std::vector<expr::NodeId> outputs;  // per row: ẋ's or g's expression
  // Built on first use (PrepareJacobian): everything below but `out` of f.
  expr::Tape fj_tape;           // the same followed by the Jacobian entries
  std::vector<int> jrow, jcol;  // local (row, col) of each Jacobian entry
  std::vector<int> jdiag;       // the entries on the diagonal (DenseError)
  // Differenced instead (EvalJacobianNumerically): the entries of column c
  // are by_col[col_begin[c] .. col_begin[c+1]).
  bool numeric_jacobian = false;
  std::vector<int> by_col, col_begin;
  TapeCache::Shared gdot_tape;  // ∂g/∂t for prescribed rows whose g depends on t only
  std::vector<int> gdot_rows;
  std::vector<int> mrow, mcol;  // matrix pattern: n diagonal entries, then jrow/jcol
  std::vector<double> jvals, mvals, out;
  std::unique_ptr<LinearSolver> solver;
  bool any_prescribed = false;
  // No row depends on t (nor on a moving joint point): with constant inputs
  // a state where the rates vanish stays (rest steps).
  bool autonomous = false;
  // Motion under constant forces (BallisticRows); its rows are empty when
  // the mode is not of that form.
  Ballistic ballistic;
};

const char* Component::Prescribed(const Mode& m) {
  return m.any_prescribed ? m.prescribed.data() : nullptr;
}

struct Component::Attempt {
  bool trbdf2 = false;
  bool esdirk = false;
  bool explicit_step = false;
  double err = 0.0;
  double h_rho = 0.0;   // explicit: stiffness estimate h·ρ from the last stages
  int jac_sample = -1;  // implicit: the sample the Jacobian was taken at
  long newton_iterations = 0;
  int solves = 0;  // implicit: Newton solves (stages) of the step
};

Component::Component(Simulation& sim, int index, std::vector<int> vars)
    : sim_(sim),
      sys_(sim.system()),
      index_(index),
      vars_(std::move(vars)),
      wave_(static_cast<int>(vars_.size())) {
  const size_t n = vars_.size();
  Scratch* const all[] = {&x_,    &y_,    &fy_,   &yg_,   &fg_,     &c_,    &r_,
                          &est_,  &rate_, &pv_,   &pw_,   &bubble_, &k_[0], &k_[1],
                          &k_[2], &k_[3], &k_[4], &k_[5], &k_[6]};
  scratch_ = std::make_unique<double[]>(std::size(all) * n);
  for (size_t i = 0; i < std::size(all); ++i) *all[i] = {scratch_.get() + i * n, n};
  bool run = n > 0;
  for (size_t j = 1; j < n && run; ++j) run = vars_[j] == vars_[j - 1] + 1;
  if (run) first_var_ = vars_[0];
}

Component::~Component() = default;

bool Component::finished() const {
  return !wave_.empty() && wave_.t_end() >= sys_.t1 && !PendingRestart();
}

// ---- setup -----------------------------------------------------------------

void Component::Initialize() {
  std::vector<int> reads;
  for (int v : vars_) {
    const auto& sv = sys_.variables[v];
    for (int r : sim_.reads(v))
      if (sim_.component_of(r) != index_) reads.push_back(r);
    static_breakpoints_.insert(static_breakpoints_.end(), sv.breakpoints.begin(),
                               sv.breakpoints.end());
  }
  std::sort(reads.begin(), reads.end());
  reads.erase(std::unique(reads.begin(), reads.end()), reads.end());
  inputs_ = std::move(reads);
  // An upstream jump makes our rates jump: land on upstream breakpoints too.
  for (int u : sim_.partition().upstream[index_]) {
    const auto& ub = sim_.component(u).static_breakpoints_;
    static_breakpoints_.insert(static_breakpoints_.end(), ub.begin(), ub.end());
  }
  std::sort(static_breakpoints_.begin(), static_breakpoints_.end());
  static_breakpoints_.erase(std::unique(static_breakpoints_.begin(), static_breakpoints_.end()),
                            static_breakpoints_.end());
  // Exact joints whose bodies are ours (a jointed group is always whole).
  const std::vector<int>& joints = sim_.joints_of(index_);
  if (!joints.empty()) {
    auto local_first = [&](int b) {
      const int v = sys_.bodies[b].first_var;
      return v >= 0 && sim_.component_of(v) == index_ ? sim_.local_index(v) : -1;
    };
    for (int j : joints)
      if (sys_.joints[j].body_b < 0)
        for (expr::NodeId e : sys_.joints[j].p)
          if (sys_.pool.DependsOnTime(e)) points_autonomous_ = false;
    // Rows a joint force acts on: the accelerations of its bodies.
    joint_rows_.assign(vars_.size(), 0);
    for (int j : joints)
      for (int b : {sys_.joints[j].body_a, sys_.joints[j].body_b}) {
        if (b < 0 || local_first(b) < 0) continue;
        for (int slot :
             {physics::kDx, physics::kDy, physics::kDz, physics::kW1, physics::kW2, physics::kW3})
          joint_rows_[local_first(b) + slot] = 1;
      }
    joints_ = std::make_unique<physics::JointSolver>(sys_, joints, local_first);
  }

  StartSample();
}

// The first sample: the variables' initial values (or what a trajectory
// prescribes at t0) with right-hand-limit rates, as a restart.
void Component::StartSample() {
  const size_t n = vars_.size();
  for (size_t j = 0; j < n; ++j) x_[j] = sys_.variables[vars_[j]].initial;
  wave_.Resize(0);
  const SampleInfo info = RestartSample(sys_.t0, x_.data(), false);
  wave_.Append(sys_.t0, y_.data(), rate_.data(), info);
  // A state at rest (rates zero, see RestSpan) needs no method until something moves
  // it; the stiffness test then waits for the votes of the steps.
  // RestSpan is infinite exactly when the rates vanish, whatever the step
  // it is weighed against: against an infinite one it says so without the
  // second-order probe.  A ballistic mode's span is positive against a zero
  // step (its first- and second-order spans are).
  const Mode& m = ModeAt(sys_.t0);
  const bool still = m.autonomous && inputs_.empty() &&
                     std::isinf(RestSpan(m, std::numeric_limits<double>::infinity()));
  const bool ballistic = !m.ballistic.rows.empty();
  wave_.info(0).implicit = !still && !ballistic && InitialImplicit(sys_.t0);
  jac_sample_ = -1;
}

// ---- modes -----------------------------------------------------------------

// One byte per variable (0: its equation; i+1: override i), then for each
// active hold the variable and the held value's bits.
std::string Component::ModeKey(double t) const {
  std::string key(vars_.size(), '\0');
  for (size_t j = 0; j < vars_.size(); ++j) {
    const auto& ov = sys_.variables[vars_[j]].overrides;
    for (size_t i = 0; i < ov.size(); ++i)
      if (ov[i].from <= t && t < ov[i].to) key[j] = static_cast<char>(i + 1);
  }
  for (const Hold& h : holds_) {
    if (!(h.from <= t && t < h.to)) continue;
    key.append(reinterpret_cast<const char*>(&h.local), sizeof h.local);
    key.append(reinterpret_cast<const char*>(&h.value), sizeof h.value);
  }
  return key;
}

Component::Mode& Component::ModeAt(double t) {
  if (last_mode_ && mode_lo_ <= t && t < mode_hi_) return *last_mode_;
  std::string key = ModeKey(t);
  // The interval around t where the same overrides are active.
  mode_lo_ = -std::numeric_limits<double>::infinity();
  mode_hi_ = std::numeric_limits<double>::infinity();
  auto bound = [&](double b) {
    if (b <= t)
      mode_lo_ = std::max(mode_lo_, b);
    else
      mode_hi_ = std::min(mode_hi_, b);
  };
  for (int v : vars_)
    for (const auto& o : sys_.variables[v].overrides) {
      bound(o.from);
      bound(o.to);
    }
  for (const Hold& h : holds_) {
    bound(h.from);
    bound(h.to);
  }
  auto it = modes_.find(key);
  if (it == modes_.end()) it = modes_.emplace(key, BuildMode(key, t)).first;
  last_mode_ = it->second.get();
  return *last_mode_;
}

std::unique_ptr<Component::Mode> Component::BuildMode(const std::string& key, double t) {
  const std::lock_guard<std::mutex> lock(sim_.build_mutex());  // the pool and the tape cache
  auto m = std::make_unique<Mode>();
  auto& pool = const_cast<expr::Pool&>(sys_.pool);  // derivatives extend the pool
  const int n = static_cast<int>(vars_.size());
  m->prescribed.assign(n, 0);
  std::vector<expr::NodeId> outputs(n);
  std::vector<expr::NodeId> gdots;
  for (int j = 0; j < n; ++j) {
    const auto& sv = sys_.variables[vars_[j]];
    outputs[j] = sv.rhs;
    if (key[j] != 0) {
      const physics::Override& o = sv.overrides[key[j] - 1];
      outputs[j] = o.expr;
      if (o.kind == physics::Override::Kind::kValue) {
        m->prescribed[j] = 1;
        if (pool.Variables(o.expr).empty()) {
          m->gdot_rows.push_back(j);
          gdots.push_back(pool.TimeDerivative(o.expr));
        }
      }
    }
  }
  for (const Hold& h : holds_) {
    if (!(h.from <= t && t < h.to)) continue;
    outputs[h.local] = pool.Const(h.value);
    if (!m->prescribed[h.local]) {
      m->prescribed[h.local] = 1;
      m->gdot_rows.push_back(h.local);
      gdots.push_back(pool.Const(0.0));
    }
  }
  m->f_tape = sim_.tapes().Get(pool, outputs);
  m->autonomous = points_autonomous_ && !m->f_tape.reads_time;
  if (!gdots.empty()) m->gdot_tape = sim_.tapes().Get(pool, gdots);  // else never evaluated
  m->any_prescribed =
      std::any_of(m->prescribed.begin(), m->prescribed.end(), [](char p) { return p != 0; });
  if (m->autonomous && !m->any_prescribed && !joints_ && inputs_.empty())
    m->ballistic = BallisticRows(outputs, m->prescribed);
  m->outputs = std::move(outputs);
  gdot_.resize(std::max(gdot_.size(), m->gdot_rows.size()));
  return m;
}

// A mode whose every rate is a constant a, or a variable v of ours whose own
// rate is a constant (ẋ = v, v̇ = a: free flight under constant forces) moves
// along the quadratic x + H v + H²/2 a exactly, over any span.  Two more
// kinds of row keep their value: one a constant prescribes (a hold), and a
// row of any other form whose rate is zero in a sample where every such row
// and every constant-rate row they read have rate zero (`still`): such rows
// read only each other and constants, so they are an autonomous subsystem
// at an exact equilibrium — a ball's rotation at rest (q̇ = ½ q⊗ω with
// ω = 0, ω̇ = 0) while it flies.
Component::Ballistic Component::BallisticRows(const std::vector<expr::NodeId>& outputs,
                                              const std::vector<char>& prescribed) const {
  const auto& pool = sys_.pool;
  const int n = static_cast<int>(vars_.size());
  auto local = [&](int v) {
    auto it = std::lower_bound(vars_.begin(), vars_.end(), v);
    return it == vars_.end() || *it != v ? -1 : static_cast<int>(it - vars_.begin());
  };
  auto constant = [&](int k) { return pool.IsConst(outputs[k]); };
  Ballistic b;
  b.rows.assign(n, -1);
  std::vector<char> other(n, 0);
  for (int j = 0; j < n; ++j) {
    if (constant(j)) continue;
    if (prescribed[j]) return {};
    const expr::Node& node = pool.node(outputs[j]);
    const int k = node.op == expr::Op::kVar ? local(node.index) : -1;
    if (k >= 0 && constant(k))
      b.rows[j] = k;
    else
      other[j] = 1;
  }
  // The variables the other rows read, in one walk of their shared nodes (a
  // walk per row went over a rigid body's common subexpressions 7 times).
  std::vector<expr::NodeId> roots;
  for (int j = 0; j < n; ++j)
    if (other[j]) {
      b.still.push_back(j);
      roots.push_back(outputs[j]);
    }
  for (int v : pool.Variables(roots)) {
    const int k = local(v);
    if (k < 0 || !(other[k] || constant(k))) return {};
    if (!other[k] && !prescribed[k]) b.still.push_back(k);
  }
  std::sort(b.still.begin(), b.still.end());
  b.still.erase(std::unique(b.still.begin(), b.still.end()), b.still.end());
  // Bodies whose angular velocity is constant: its three rows' rates are
  // exactly zero (no torque on isotropic inertia: the gyroscopic terms
  // cancel, physics::EquationSystem).  The orientation's rate is ½ q⊗ω, the
  // only one a free body's orientation is given, so each of its four rows is
  // then a harmonic oscillator of frequency |ω|/2: it turns exactly, and its
  // rows leave `still`.
  std::vector<char> spinning(n, 0);
  for (int j : b.still) {
    const int v = vars_[j];
    const int body = sys_.variables[v].body;
    if (body < 0 || v != sys_.bodies[body].first_var + physics::kQw) continue;
    Spin spin;
    bool ok = true;
    for (int i = 0; i < 4 && ok; ++i) {
      spin.q[i] = local(v + i);
      ok = spin.q[i] >= 0 && other[spin.q[i]];
    }
    for (int i = 0; i < 3 && ok; ++i) {
      spin.w[i] = local(v - physics::kQw + physics::kW1 + i);
      ok = spin.w[i] >= 0 && !prescribed[spin.w[i]] && pool.ConstValue(outputs[spin.w[i]]) == 0.0;
    }
    if (!ok) continue;
    b.spins.push_back(spin);
    for (int k : spin.q) spinning[k] = 1;
  }
  std::erase_if(b.still, [&](int j) { return spinning[j] != 0; });
  return b;
}

// How long the last sample's mode may move ballistically (BallisticRows):
// for ever when its still rows' rates are zero and nothing turns, else as
// long as the still rows would move less than RestSpan allows (they are
// kept) and the playback follows each turn (below), else 0.
double Component::BallisticSpan(const Mode& m, double h) {
  if (m.ballistic.rows.empty()) return 0.0;
  const double* x = wave_.x(wave_.size() - 1);
  const double* f = wave_.f(wave_.size() - 1);
  // A turning body: as long as the playback interpolant (a cubic and its
  // bubble through the exact middle, waveform.h) follows the turn to the
  // tolerance.  For a unit harmonic of phase φ over the step its error is
  // at most kSpinInterpolation φ⁵ (measured: 7.45e-5 φ⁵ for φ ≤ 0.1,
  // falling slowly as φ grows).
  const SolverOptions& o = sim_.options();
  double span = std::numeric_limits<double>::infinity();
  for (const Spin& s : m.ballistic.spins) {
    const double omega = 0.5 * std::hypot(x[s.w[0]], x[s.w[1]], x[s.w[2]]);
    if (omega == 0.0) continue;
    // Each row is a harmonic of amplitude at most |q|: the orientation is
    // followed to the tolerance relative to its size.
    double size2 = 0.0;
    for (int j : s.q) size2 += x[j] * x[j];
    const double tol = o.atol + o.rtol * std::sqrt(size2);
    span = std::min(span, std::pow(tol / kSpinInterpolation, 0.2) / omega);
  }
  const auto& still = m.ballistic.still;
  if (std::all_of(still.begin(), still.end(), [f](int j) { return f[j] == 0.0; })) return span;
  return std::min(span, RestSpan(m, h, &still));
}

// One exact step of a ballistic mode to the next breakpoint (or the step
// limit): positions on their quadratics, velocities on their lines,
// turning bodies' orientations on their turns.
void Component::BallisticStep(const Mode& m, double t, double h_max) {
  const int k = wave_.size() - 1;
  const size_t n = vars_.size();
  const double* x = wave_.x(k);
  const double* f = wave_.f(k);
  const Plan plan = PlanStep(t, h_max, NextBreakpoint(t), sys_.t1);
  const double h = plan.t_end - t;
  for (size_t j = 0; j < n; ++j)
    if (m.ballistic.rows[j] < 0) {
      x_[j] = x[j] + h * f[j];
      rate_[j] = f[j];
    }
  for (int j : m.ballistic.still) x_[j] = x[j];  // at rest (to the tolerance)
  for (size_t j = 0; j < n; ++j)
    if (const int v = m.ballistic.rows[j]; v >= 0) {
      x_[j] = x[j] + h * f[j] + 0.5 * h * h * f[v];
      rate_[j] = x_[v];
    }
  // A turning body's orientation: q̈ = −Ω² q with Ω = |ω|/2, so
  // q(h) = cos(Ωh) q + sin(Ωh)/Ω q̇; the bubble makes the interpolant pass
  // through the middle of the turn (waveform.h: x(½) = H(½) + b/16).
  const bool turning = !m.ballistic.spins.empty();
  if (turning) std::fill(bubble_.begin(), bubble_.end(), 0.0);
  for (const Spin& s : m.ballistic.spins) {
    const double omega = 0.5 * std::hypot(x[s.w[0]], x[s.w[1]], x[s.w[2]]);
    if (omega == 0.0) {
      for (int j : s.q) x_[j] = x[j];
      continue;
    }
    const double c = std::cos(omega * h), sn = std::sin(omega * h);
    const double c_mid = std::cos(0.5 * omega * h), s_mid = std::sin(0.5 * omega * h);
    for (int j : s.q) {
      x_[j] = c * x[j] + (sn / omega) * f[j];
      rate_[j] = c * f[j] - (omega * sn) * x[j];
      const double mid = c_mid * x[j] + (s_mid / omega) * f[j];
      const double cubic_mid = 0.5 * (x[j] + x_[j]) + 0.125 * h * (f[j] - rate_[j]);
      bubble_[j] = 16.0 * (mid - cubic_mid);
    }
  }
  SampleInfo next = wave_.info(k);
  next.restart = false;
  wave_.Append(plan.t_end, x_.data(), rate_.data(), next, turning ? bubble_.data() : nullptr);
  ++counters_.steps;
  ++counters_.ballistic_steps;
  jac_sample_ = -1;
  if (plan.landing) Restart();
}

// ---- evaluation --------------------------------------------------------------

void Component::Load(double t, const double* y, Side side) {
  double* xg = sim_.values(lane_);
  if (first_var_ >= 0)
    std::copy(y, y + vars_.size(), xg + first_var_);
  else
    for (size_t j = 0; j < vars_.size(); ++j) xg[vars_[j]] = y[j];
  for (int i : inputs_) xg[i] = sim_.InputValue(i, t, side);
}

void Component::EvalF(const Mode& m, double t, const double* y, double* out, Side side,
                      bool landing) {
  double te = t;
  if (landing) te = std::nextafter(t, -std::numeric_limits<double>::infinity());
  if (side == Side::kRight) te = std::nextafter(t, std::numeric_limits<double>::infinity());
  const expr::ExternFn& ext = sim_.externs();
  ++counters_.rhs_evaluations;
  // A component that reads only its own variables, numbered in a run, and
  // nothing else from the simulation's values (prescribed rates) has its
  // tape and its joints read y itself: tape variable i is ours at i + shift
  // − first_var_ (a joint's point is a function of t only).  Else y goes to
  // the values first, with the inputs.
  if (first_var_ >= 0 && inputs_.empty() && m.gdot_rows.empty()) {
    m.f_tape.tape->Evaluate(te, y, out, &ext, first_var_ - m.f_tape.shift, lane_);
    if (joints_) joints_->Apply(te, y, out, Prescribed(m), &ext, nullptr, 1, first_var_);
    return;
  }
  Load(t, y, side);
  m.f_tape.tape->Evaluate(te, sim_.values(lane_) + m.f_tape.shift, out, &ext, 0, lane_);
  if (joints_) joints_->Apply(te, sim_.values(lane_), out, Prescribed(m), &ext);
}

// The Jacobian's pattern, tape and linear solver, built when a mode first
// needs them (a component at rest never does).  A jointed component
// differences the whole f (the joint solve has no symbolic form); so does a
// small one: its n + 1 right-hand sides per Jacobian cost less than
// differentiating and compiling its equations once, now that a Jacobian
// serves many steps (Step) — on the stiff-link benchmark the symbolic
// Jacobian was 41% of a run at rtol 1e-2.
void Component::PrepareJacobian(Mode& m) {
  if (m.solver) return;
  const std::lock_guard<std::mutex> lock(sim_.build_mutex());  // the pool
  auto& pool = const_cast<expr::Pool&>(sys_.pool);  // derivatives extend the pool
  const int n = static_cast<int>(vars_.size());
  std::vector<expr::NodeId> all = m.outputs;
  m.numeric_jacobian = joints_ || n <= kNumericJacobianMax;
  for (int j = 0; j < n && joints_; ++j)
    for (int c = 0; c < n; ++c) {
      m.jrow.push_back(j);
      m.jcol.push_back(c);
    }
  for (int j = 0; j < n && !joints_; ++j) {
    for (int v : pool.Variables(m.outputs[j])) {
      auto it = std::lower_bound(vars_.begin(), vars_.end(), v);
      if (it == vars_.end() || *it != v) continue;
      if (!m.numeric_jacobian) {
        const expr::NodeId d = pool.Derivative(m.outputs[j], v);
        if (pool.IsConst(d) && *pool.ConstValue(d) == 0.0) continue;
        all.push_back(d);
      }
      m.jrow.push_back(j);
      m.jcol.push_back(static_cast<int>(it - vars_.begin()));
    }
  }
  if (m.numeric_jacobian) {
    m.col_begin.assign(n + 1, 0);
    for (int c : m.jcol) ++m.col_begin[c + 1];
    for (int c = 0; c < n; ++c) m.col_begin[c + 1] += m.col_begin[c];
    m.by_col.assign(m.jcol.size(), 0);
    std::vector<int> fill(m.col_begin.begin(), m.col_begin.end() - 1);
    for (size_t e = 0; e < m.jcol.size(); ++e) m.by_col[fill[m.jcol[e]]++] = static_cast<int>(e);
  } else {
    m.fj_tape = expr::Tape::Compile(pool, all);
  }
  for (int j = 0; j < n; ++j) {
    m.mrow.push_back(j);
    m.mcol.push_back(j);
  }
  m.mrow.insert(m.mrow.end(), m.jrow.begin(), m.jrow.end());
  m.mcol.insert(m.mcol.end(), m.jcol.begin(), m.jcol.end());
  for (size_t e = 0; e < m.jrow.size(); ++e)
    if (m.jrow[e] == m.jcol[e]) m.jdiag.push_back(static_cast<int>(e));
  m.jvals.assign(m.jrow.size(), 0.0);
  m.mvals.assign(m.mrow.size(), 0.0);
  m.out.assign(all.size(), 0.0);
  m.solver = LinearSolver::Create(n, m.mrow, m.mcol, sim_.options().dense_limit);
}

void Component::EvalJacobian(Mode& m, double t, const double* y) {
  PrepareJacobian(m);
  if (m.numeric_jacobian) return EvalJacobianNumerically(m, t, y);
  Load(t, y, Side::kRight);
  const expr::ExternFn& ext = sim_.externs();
  m.fj_tape.Evaluate(t, sim_.values(lane_), m.out.data(), &ext);
  ++counters_.jacobian_evaluations;
  const size_t n = vars_.size();
  for (size_t k = 0; k < m.jrow.size(); ++k) m.jvals[k] = m.out[n + k];
  factored_a_ = -1;
}

void Component::EvalJacobianNumerically(Mode& m, double t, const double* y) {
  const size_t n = vars_.size();
  std::copy(y, y + n, pv_.begin());
  EvalF(m, t, pv_.data(), c_.data(), Side::kRight, false);
  const double root_eps = std::sqrt(std::numeric_limits<double>::epsilon());
  for (size_t col = 0; col < n; ++col) {
    const int begin = m.col_begin[col], end = m.col_begin[col + 1];
    if (begin == end) continue;  // no equation reads this variable
    const double saved = pv_[col];
    const double d = root_eps * std::max(std::abs(saved), 1e-3);
    pv_[col] = saved + d;
    EvalF(m, t, pv_.data(), pw_.data(), Side::kRight, false);
    pv_[col] = saved;
    const double step = (saved + d) - saved;
    for (int i = begin; i < end; ++i) {
      const int e = m.by_col[i];
      m.jvals[e] = (pw_[m.jrow[e]] - c_[m.jrow[e]]) / step;
    }
  }
  ++counters_.jacobian_evaluations;
  factored_a_ = -1;
}

// Power iteration on J restricted to the ODE rows, from a fixed start vector
// (deterministic).  A complex pair makes the iterates rotate rather than
// converge, but the growth ratio still measures |λ|, which is what the
// stability limits depend on.  `apply` sets pw_ = J·pv_ / ‖pv_‖∞.
template <typename Apply>
double Component::PowerIteration(const Mode& m, Apply apply) {
  const size_t n = vars_.size();
  for (size_t j = 0; j < n; ++j) pv_[j] = m.prescribed[j] ? 0.0 : 1.0 + 0.37 * double(j % 7);
  double rho = 0.0;
  for (int it = 0; it < 12; ++it) {
    double norm_v = 0.0;
    for (size_t j = 0; j < n; ++j) norm_v = std::max(norm_v, std::abs(pv_[j]));
    if (norm_v == 0.0) return 0.0;
    apply(norm_v);
    for (size_t j = 0; j < n; ++j)
      if (m.prescribed[j]) pw_[j] = 0.0;
    double norm_w = 0.0;
    for (size_t j = 0; j < n; ++j) norm_w = std::max(norm_w, std::abs(pw_[j]));
    if (it >= 8) rho = std::max(rho, norm_w);  // last iterations: rotation-safe
    std::swap(pv_, pw_);
  }
  return std::isfinite(rho) ? rho : std::numeric_limits<double>::infinity();
}

double Component::SpectralRadius(const Mode& m) {
  return PowerIteration(m, [&](double norm_v) {
    std::fill(pw_.begin(), pw_.end(), 0.0);
    for (size_t k = 0; k < m.jrow.size(); ++k)
      if (!m.prescribed[m.jcol[k]]) pw_[m.jrow[k]] += m.jvals[k] * pv_[m.jcol[k]] / norm_v;
  });
}

// The same iteration with J·v taken as a difference quotient of f along v,
// one right-hand side per iteration: no Jacobian is formed, so a component
// that never turns out stiff never compiles a Jacobian tape.
double Component::SpectralRadiusMatrixFree(const Mode& m, double t) {
  const int k = wave_.size() - 1;
  const size_t n = vars_.size();
  const double* x = wave_.x(k);
  double scale = 1.0;
  for (size_t j = 0; j < n; ++j) scale = std::max(scale, std::abs(x[j]));
  const double delta = std::sqrt(std::numeric_limits<double>::epsilon()) * scale;
  EvalF(m, t, x, c_.data(), Side::kRight, false);
  return PowerIteration(m, [&](double norm_v) {
    for (size_t j = 0; j < n; ++j) y_[j] = x[j] + delta * (pv_[j] / norm_v);
    EvalF(m, t, y_.data(), pw_.data(), Side::kRight, false);
    for (size_t j = 0; j < n; ++j) pw_[j] = (pw_[j] - c_[j]) / delta;
  });
}

bool Component::FactorMatrix(Mode& m, double a) {
  PrepareJacobian(m);
  if (factored_a_ == a) return true;
  const size_t n = vars_.size();
  for (size_t j = 0; j < n; ++j) m.mvals[j] = 1.0;
  for (size_t k = 0; k < m.jrow.size(); ++k) {
    const double scale = m.prescribed[m.jrow[k]] ? 1.0 : a;
    m.mvals[n + k] = -scale * m.jvals[k];
  }
  ++counters_.factorizations;
  if (!m.solver->Factor(m.mvals.data())) {
    factored_a_ = -1;
    return false;
  }
  factored_a_ = a;
  return true;
}

double Component::WeightedNorm(const double* v, const double* x, const double* y) const {
  const SolverOptions& o = sim_.options();
  double norm = 0.0;
  for (size_t j = 0; j < vars_.size(); ++j) {
    const double w = o.atol + o.rtol * std::max(std::abs(x[j]), std::abs(y[j]));
    norm = std::max(norm, std::abs(v[j]) / w);
  }
  return std::isnan(norm) ? std::numeric_limits<double>::infinity() : norm;
}

// Solves y − c − a f(t, y) = 0 (ODE rows) and y − g(t, y) = 0 (prescribed
// rows) by Newton's method with the factored matrix.  On success fy holds
// the rates the equation implies, (y − c)/a, and the prescribed values y:
// no evaluation of f at the last iterate.  They differ from f(t, y) by the
// iteration's remaining error over a, which on a stiff row (|a J| ≫ 1) is
// less than f's own error J·δ; the values rows read from these rates (the
// stages' sums, the sample's rate) are as accurate as the iteration.
bool Component::Newton(Mode& m, double t_new, double a, const double* c, double* y, double* fy,
                       bool landing) {
  const size_t n = vars_.size();
  const double* x = wave_.x(wave_.size() - 1);
  double prev = std::numeric_limits<double>::infinity();
  // A linear equation with a current Jacobian converges in one update; the
  // rates seen by earlier solves say when that is so (EtaDrift).
  newton_eta_ = EtaDrift(newton_eta_);
  for (int it = 0; it < kNewtonMaxIter; ++it) {
    EvalF(m, t_new, y, fy, Side::kLeft, landing);
    ++counters_.newton_iterations;
    for (size_t j = 0; j < n; ++j) r_[j] = m.prescribed[j] ? fy[j] - y[j] : c[j] + a * fy[j] - y[j];
    m.solver->Solve(r_.data());
    for (size_t j = 0; j < n; ++j) y[j] += r_[j];
    const double norm = WeightedNorm(r_.data(), x, y);
    if (!std::isfinite(norm)) break;
    const double rate = it == 0 ? 0.0 : norm / prev;
    if (it >= 1 && rate > 0.9) break;
    if (it >= 1) newton_eta_ = rate / (1.0 - rate);
    prev = norm;
    const bool converged = norm * newton_eta_ <= kNewtonTol;
    if (converged || norm == 0.0) {
      for (size_t j = 0; j < n; ++j) fy[j] = m.prescribed[j] ? y[j] : (y[j] - c[j]) / a;
      return std::all_of(fy, fy + n, [](double v) { return std::isfinite(v); });
    }
  }
  ++counters_.newton_failures;
  newton_eta_ = kEtaUnknown;
  return false;
}

// Rates stored with a sample: ẋ for ODE rows, dg/dt for prescribed rows
// (exact when g depends on t only, else the secant over the step).
void Component::Rates(const Mode& m, double t, const double* y, const double* fy, const double* y0,
                      double h, double* rate, Side side) {
  const size_t n = vars_.size();
  for (size_t j = 0; j < n; ++j) {
    if (!m.prescribed[j])
      rate[j] = fy[j];
    else
      rate[j] = h > 0 ? (y[j] - y0[j]) / h : 0.0;
  }
  if (m.gdot_rows.empty()) return;
  double* g = gdot_.data();
  double te = side == Side::kRight ? std::nextafter(t, std::numeric_limits<double>::infinity()) : t;
  const expr::ExternFn& ext = sim_.externs();
  m.gdot_tape.tape->Evaluate(te, sim_.values(lane_) + m.gdot_tape.shift, g, &ext, 0, lane_);
  for (size_t i = 0; i < m.gdot_rows.size(); ++i) rate[m.gdot_rows[i]] = g[i];
}

// ---- stepping ----------------------------------------------------------------

// The ESDIRK stage whose value checks the step's interpolant (DenseError).
constexpr int kDenseCheckStage = 2;

// One step of kEsdirk32 (esdirk.h) from the last sample: three Newton
// solves with the one matrix I − γhJ.  Leaves the solution in y_, its tape
// outputs in fy_ and the filtered error estimate in est_.
bool Component::EsdirkStep(Mode& m, double h, bool landing) {
  const Esdirk& E = kEsdirk32;
  const int k = wave_.size() - 1;
  const size_t n = vars_.size();
  const double t = wave_.time(k);
  const double* x = wave_.x(k);
  const double* f = wave_.f(k);
  const double a = E.gamma * h;
  if (!FactorMatrix(m, a)) return false;
  // Stage rates: the sample's, then two kept, then the last in fy_; the
  // first implicit stage's value is kept in k_[4] (the explicit pair's
  // scratch), the dense check's in k_[3].
  const double* ks[4] = {f, k_[1].data(), k_[2].data(), fy_.data()};
  // Predictors.  The first implicit stage's: the last step's cubic carried
  // on to the stage's time (where the last step was not a restart; else
  // the sample's rate held over the stage).  The later stages': the cubic
  // through the sample and the first implicit stage, values and rates, at
  // the stage's time.  A prescribed row extrapolates its value along its
  // rate.  (From the rate held over each stage, a pendulum on a stiff
  // spring (ω0 = 100, 20 s, rtol 1e-6) took 60 256 Newton iterations and
  // 3 167 Jacobians for its 5 918 ESDIRK steps; from these, 50 875 and 587.)
  const double hp = k >= 1 && !wave_.info(k).restart ? t - wave_.time(k - 1) : 0.0;
  const bool history = hp > 0.0;
  for (int i = 1; i < 4; ++i) {
    for (size_t j = 0; j < n; ++j) {
      double sum = 0.0;
      for (int l = 0; l < i; ++l) sum += E.a[i][l] * ks[l][j];
      c_[j] = x[j] + h * sum;
    }
    if (i == 1 && history) {
      const CubicWeights w = CubicAt(1.0 + E.c[1] * h / hp, hp);
      const double* xp = wave_.x(k - 1);
      const double* fp = wave_.f(k - 1);
      for (size_t j = 0; j < n; ++j)
        y_[j] = w.x0 * xp[j] + w.f0 * fp[j] + w.x1 * x[j] + w.f1 * f[j];
    } else if (i == 1) {
      for (size_t j = 0; j < n; ++j) y_[j] = c_[j] + a * f[j];
    } else {
      const CubicWeights w = CubicAt(E.c[i] / E.c[1], E.c[1] * h);
      const double* z1 = k_[4].data();
      for (size_t j = 0; j < n; ++j)
        y_[j] = w.x0 * x[j] + w.f0 * f[j] + w.x1 * z1[j] + w.f1 * ks[1][j];
    }
    for (size_t j = 0; j < n; ++j)
      if (m.prescribed[j]) y_[j] = x[j] + E.c[i] * h * f[j];
    double* rates = i < 3 ? k_[i].data() : fy_.data();
    const bool last = i == 3;
    if (!Newton(m, last ? t + h : t + E.c[i] * h, a, c_.data(), y_.data(), rates, last && landing))
      return false;
    if (i == 1) std::copy(y_.begin(), y_.end(), k_[4].begin());
    if (i == kDenseCheckStage) std::copy(y_.begin(), y_.end(), k_[3].begin());
  }
  for (size_t j = 0; j < n; ++j) {
    double sum = 0.0;
    for (int l = 0; l < 4; ++l) sum += E.e[l] * ks[l][j];
    est_[j] = m.prescribed[j] ? 0.0 : h * sum;
  }
  m.solver->Solve(est_.data());
  for (size_t j = 0; j < n; ++j)
    if (m.prescribed[j]) est_[j] = 0.0;
  return true;
}

bool Component::TryStep(double h, bool landing, bool fresh_jacobian, Attempt& out) {
  const int k = wave_.size() - 1;
  const size_t n = vars_.size();
  const double t = wave_.time(k);
  const double* x = wave_.x(k);
  const double* f = wave_.f(k);
  Mode& m = ModeAt(t);
  // The Jacobian of an earlier sample of this mode while Newton converges
  // with it (Step decides, the sample records it); this sample's otherwise.
  const int from = wave_.info(k).jac_from;
  const int s = !fresh_jacobian && from >= 0 && from < k ? from : k;
  if (jac_sample_ != s || jac_mode_ != &m) {
    EvalJacobian(m, wave_.time(s), wave_.x(s));
    rho_ = SpectralRadius(m);
    jac_sample_ = s;
    jac_mode_ = &m;
  }
  out.jac_sample = s;
  const long iterations_before = counters_.newton_iterations;
  const bool history = k >= 1 && !wave_.info(k).restart;
  const SolverOptions::Method method = sim_.options().method;
  const bool stiff_step = !history || h * rho_ > kTrStiffness;
  switch (method) {
    case SolverOptions::Method::kTrapezoidal:
      out.trbdf2 = stiff_step;
      break;
    case SolverOptions::Method::kTrBdf2:
      out.trbdf2 = true;
      break;
    case SolverOptions::Method::kEsdirk:
      out.esdirk = true;
      break;
    case SolverOptions::Method::kAuto:
      // A component integrated implicitly because it is stiff takes the
      // L-stable method throughout; one that is implicit only because rows
      // are prescribed keeps TR while it is not stiff (one solve per step).
      out.esdirk = stiff_step || wave_.info(k).implicit;
      break;
    case SolverOptions::Method::kExplicit:
      out.esdirk = stiff_step;
      break;
  }
  out.h_rho = h * rho_;
  if (out.esdirk) {
    if (!EsdirkStep(m, h, landing)) return false;
  } else if (!out.trbdf2) {
    const double a = 0.5 * h;
    if (!FactorMatrix(m, a)) return false;
    const double* fp = wave_.f(k - 1);
    const double hp = t - wave_.time(k - 1);
    for (size_t j = 0; j < n; ++j) {
      c_[j] = x[j] + a * f[j];
      y_[j] = x[j] + h * f[j] + 0.5 * h * h * (f[j] - fp[j]) / hp;
    }
    if (!Newton(m, t + h, a, c_.data(), y_.data(), fy_.data(), landing)) return false;
    for (size_t j = 0; j < n; ++j) {
      if (m.prescribed[j]) {
        est_[j] = 0.0;
        continue;
      }
      const double dd1 = (fy_[j] - f[j]) / h;
      const double dd0 = (f[j] - fp[j]) / hp;
      est_[j] = h * h * h / 6.0 * (dd1 - dd0) / (h + hp);
    }
  } else {
    const double a = kD * h;
    if (!FactorMatrix(m, a)) return false;
    for (size_t j = 0; j < n; ++j) {
      c_[j] = x[j] + a * f[j];
      yg_[j] = x[j] + kGamma * h * f[j];
    }
    if (!Newton(m, t + kGamma * h, a, c_.data(), yg_.data(), fg_.data(), false)) return false;
    for (size_t j = 0; j < n; ++j) {
      c_[j] = kBdfY * yg_[j] - kBdfX * x[j];
      y_[j] = m.prescribed[j] ? fg_[j] : yg_[j] + (1 - kGamma) * h * fg_[j];
    }
    if (!Newton(m, t + h, a, c_.data(), y_.data(), fy_.data(), landing)) return false;
    for (size_t j = 0; j < n; ++j) {
      est_[j] =
          m.prescribed[j]
              ? 0.0
              : 2 * kErrC * h *
                    (f[j] / kGamma - fg_[j] / (kGamma * (1 - kGamma)) + fy_[j] / (1 - kGamma));
    }
    m.solver->Solve(est_.data());
    for (size_t j = 0; j < n; ++j)
      if (m.prescribed[j]) est_[j] = 0.0;
  }
  out.newton_iterations = counters_.newton_iterations - iterations_before;
  out.solves = out.esdirk ? 3 : out.trbdf2 ? 2 : 1;
  out.err = WeightedNorm(est_.data(), x, y_.data());
  Rates(m, t + h, y_.data(), fy_.data(), x, h, rate_.data(), Side::kLeft);
  if (out.esdirk) out.err = std::max(out.err, DenseError(m, h));
  return true;
}

// The step is played back, searched for events and collided through the
// waveform's cubic Hermite interpolant, not the stages, so its error is
// checked too: against the ESDIRK stage kept in k_[3] (time c·h, stage
// order 2).  Where a stiff link holds a body to a moving target the step's
// ends are exact whatever h (the method is stiffly accurate) and the
// embedded estimate sees nothing, while the interpolant between two ends a
// second apart misses the path by h⁴|x⁗|/384; the stage is on the path.
// A row whose own rate is stiff (J_jj ≪ 0: a damped link's velocity) has
// end rates that carry its end error times J_jj, so its interpolant is only
// as good as those rates whatever h; its mismatch is divided by
// 1 − γhJ_jj, the diagonal of the filter the embedded estimate gets,
// which leaves rows with slow rates (positions, rotations) as they are.
double Component::DenseError(const Mode& m, double h) {
  const int k = wave_.size() - 1;
  const size_t n = vars_.size();
  const double* x = wave_.x(k);
  const double* f = wave_.f(k);
  const HermiteWeights w = HermiteAt(kEsdirk32.c[kDenseCheckStage], h);
  for (size_t j = 0; j < n; ++j) {
    const double hermite = w.h00 * x[j] + w.h10 * f[j] + w.h01 * y_[j] + w.h11 * rate_[j];
    pv_[j] = m.prescribed[j] ? 0.0 : hermite - k_[3][j];
  }
  const double a = kEsdirk32.gamma * h;
  for (const int e : m.jdiag)
    if (m.jvals[e] < 0.0) pv_[m.jrow[e]] /= 1.0 - a * m.jvals[e];
  return WeightedNorm(pv_.data(), x, y_.data());
}

namespace {

// Row R of P's weight table: the stage weights a[R] for R < 7, then the
// error weights e (kErrRow) and the continuous extension's bubble d
// (kBubbleRow).  Weights are read from P inside the template (not passed as
// floating-point template arguments) so that every C++20 compiler we build
// with, clang-14 included, accepts it.
constexpr int kErrRow = 7;
constexpr int kBubbleRow = 8;

template <const ExplicitPair& P, int Row>
constexpr double Weight(size_t r) {
  if constexpr (Row == kErrRow)
    return P.e[r];
  else if constexpr (Row == kBubbleRow)
    return P.d[r];
  else
    return P.a[Row][r];
}

// w·v, or −0.0 (which adding leaves any sum as it is, so the compiler drops
// it) where the weight w is zero.
template <const ExplicitPair& P, int Row, size_t R>
inline double Term(double v) {
  constexpr double w = Weight<P, Row>(R);
  if constexpr (w == 0.0)
    return -0.0;
  else
    return w * v;
}

// The loop that follows has no dependence between iterations: the stage
// sums write row j of one array from row j of others, so the compiler may
// compute several rows at once (it could not prove the arrays apart, and
// left the sums scalar: a quarter of a rigid body's explicit step).  Each
// row's arithmetic is the same, so the results are the same bits.
// (Clang's own vectorizer checks the arrays apart at run time; its
// assume_safety hint warns, an error here, where a build with sanitizers
// cannot vectorize.)
#if defined(__GNUC__) && !defined(__clang__)
#define ASGARD_INDEPENDENT_ITERATIONS _Pragma("GCC ivdep")
#else
#define ASGARD_INDEPENDENT_ITERATIONS
#endif

// Σ_r w_r k_r[j] over the stages, left to right, with the weights known at
// compile time (zero weights cost nothing).
template <const ExplicitPair& P, int Row, size_t... R>
inline double Combine(const double* const* k, size_t j, std::index_sequence<R...>) {
  return (... + Term<P, Row, R>(k[R][j]));
}

}  // namespace

bool Component::TryExplicitStep(const Mode& m, double t_end, bool landing, Attempt& out) {
  return sim_.options().pair == SolverOptions::Pair::kTsitouras
             ? TryExplicitStepWith<kTsitouras>(m, t_end, landing, out)
             : TryExplicitStepWith<kDormandPrince>(m, t_end, landing, out);
}

// One step of the explicit pair P from the last sample to t_end.  Stages
// reuse the sample's rate (FSAL); the last stage's rate becomes the new
// sample's.
template <const ExplicitPair& P>
bool Component::TryExplicitStepWith(const Mode& m, double t_end, bool landing, Attempt& out) {
  const int k = wave_.size() - 1;
  const size_t n = vars_.size();
  const double t = wave_.time(k);
  const double h = t_end - t;
  const double* x = wave_.x(k);
  std::copy(wave_.f(k), wave_.f(k) + n, k_[0].begin());
  const double* const ks[7] = {k_[0].data(), k_[1].data(), k_[2].data(), k_[3].data(),
                               k_[4].data(), k_[5].data(), k_[6].data()};
  // Stage S's state: in y_ (the 6th's, at c = 1, in yg_ for the stiffness
  // estimate); the 7th's is the 5th-order solution.
  auto stage = [&]<int S>(std::integral_constant<int, S>) {
    double* ys = S == 5 ? yg_.data() : y_.data();
    ASGARD_INDEPENDENT_ITERATIONS
    for (size_t j = 0; j < n; ++j)
      ys[j] = x[j] + h * Combine<P, S>(ks, j, std::make_index_sequence<S>());
    constexpr bool at_end = P.c[S] == 1.0;
    EvalF(m, at_end ? t_end : t + P.c[S] * h, ys, k_[S].data(), Side::kLeft, at_end && landing);
  };
  stage(std::integral_constant<int, 1>());
  stage(std::integral_constant<int, 2>());
  stage(std::integral_constant<int, 3>());
  stage(std::integral_constant<int, 4>());
  stage(std::integral_constant<int, 5>());
  stage(std::integral_constant<int, 6>());
  const double *k6 = ks[5], *k7 = ks[6];
  ASGARD_INDEPENDENT_ITERATIONS
  for (size_t j = 0; j < n; ++j) {
    est_[j] = h * Combine<P, kErrRow>(ks, j, std::make_index_sequence<7>());
    bubble_[j] = h * Combine<P, kBubbleRow>(ks, j, std::make_index_sequence<7>());
  }
  double num = 0.0, den = 0.0;
  for (size_t j = 0; j < n; ++j) {
    num += (k7[j] - k6[j]) * (k7[j] - k6[j]);
    den += (y_[j] - yg_[j]) * (y_[j] - yg_[j]);
    rate_[j] = k7[j];
  }
  out.explicit_step = true;
  out.h_rho = den > 0 ? h * std::sqrt(num / den) : 0.0;
  out.err = WeightedNorm(est_.data(), x, y_.data());
  if (!std::all_of(k7, k7 + n, [](double v) { return std::isfinite(v); }))
    out.err = std::numeric_limits<double>::infinity();
  return std::isfinite(out.err);
}

#undef ASGARD_INDEPENDENT_ITERATIONS

bool Component::UseImplicit(const Mode& m, const SampleInfo& info) const {
  switch (sim_.options().method) {
    case SolverOptions::Method::kTrapezoidal:
    case SolverOptions::Method::kTrBdf2:
    case SolverOptions::Method::kEsdirk:
      return true;
    case SolverOptions::Method::kExplicit:
      return m.any_prescribed;
    case SolverOptions::Method::kAuto:
      break;
  }
  return m.any_prescribed || info.implicit;
}

// The method a component starts with (kAuto): implicit when the spectral
// radius of its Jacobian at t0 makes explicit steps stability-bound.
bool Component::InitialImplicit(double t) {
  if (sim_.options().method != SolverOptions::Method::kAuto) return false;
  return SpectralRadiusMatrixFree(ModeAt(t), t) > kStartStiffRho;
}

double Component::NextEnd() const {
  const double t = wave_.t_end();
  const double h = PendingRestart() ? sim_.restart_step() : wave_.info(wave_.size() - 1).h_next;
  return PlanStep(t, h, NextBreakpoint(t), sys_.t1).t_end;
}

bool Component::CheckFinite() {
  const int k = wave_.size() - 1;
  const double* x = wave_.x(k);
  const double* f = wave_.f(k);
  // v·0 is 0 for every finite v and NaN for ±∞ and NaN: one sum over the
  // values and rates (no test per value; this runs at every step).
  double probe = 0.0;
  for (size_t j = 0; j < vars_.size(); ++j) probe += x[j] * 0.0 + f[j] * 0.0;
  if (probe == 0.0) return true;
  for (size_t j = 0; j < vars_.size(); ++j) {
    if (std::isfinite(x[j]) && std::isfinite(f[j])) continue;
    failed_variable_ = vars_[j];
    std::ostringstream msg;
    msg << "at t=" << wave_.time(k) << " " << sys_.variables[vars_[j]].name << " = " << x[j]
        << " with rate " << f[j] << " (component " << index_ << "): values must stay finite";
    error_ = msg.str();
    return false;
  }
  return true;
}

// How long the last sample's state may be kept as it is: the span H over
// which the solution's first two Taylor terms, H f and H²/2 J f, both stay
// below kRestFraction of the tolerance (J f by a difference along f of one
// tolerance unit).  Rates that are all exactly zero keep the state for ever
// (it is an equilibrium).  0 when that is not worth a rest step against the
// step `h` the integrator would try.  Only for autonomous modes without
// inputs, where the rates at an unchanged state are unchanged.
double Component::RestSpan(const Mode& m, double h, const std::vector<int>* rows) {
  const int k = wave_.size() - 1;
  const size_t n = vars_.size();
  const double* x = wave_.x(k);
  const double* f = wave_.f(k);
  const SolverOptions& o = sim_.options();
  // The rows tested: `rows`, else every row a constant does not prescribe
  // (rest_rows_ marks `rows` once the first scan below has passed).
  auto tested = [&](size_t j) { return !m.prescribed[j] && (!rows || rest_rows_[j]); };
  // Rows no joint force acts on first: a moving body fails here, before the
  // free rates are evaluated (this runs at every step of such a component).
  const double t = wave_.time(k);
  auto weighted = [&](size_t j) { return std::abs(f[j]) / (o.atol + o.rtol * std::abs(x[j])); };
  // A row whose rate alone rules the rest step out ends the test there (the
  // test on the largest rate is the same test: kRestFraction / fn falls as
  // fn grows); a moving body's first row does.
  auto too_fast = [&](double w) { return w > 0.0 && !(kRestFraction / w >= kRestMinGain * h); };
  double fn = 0.0;
  auto scan = [&](size_t j) {  // false: row j rules the rest step out
    if (m.prescribed[j] || (joints_ && joint_rows_[j])) return true;
    const double w = weighted(j);
    fn = std::max(fn, w);
    return !too_fast(w);
  };
  if (rows) {
    for (int j : *rows)
      if (!scan(static_cast<size_t>(j))) return 0.0;
    rest_rows_.assign(n, 0);
    for (int j : *rows) rest_rows_[j] = 1;
  } else {
    // The row that ruled the last test out first: a moving body's spin
    // rows come after its resting position rows, scanned at every step.
    if (rest_veto_ < n && !scan(rest_veto_)) return 0.0;
    for (size_t j = 0; j < n; ++j)
      if (!scan(j)) {
        rest_veto_ = j;
        return 0.0;
      }
  }
  // A rate within rounding of the free rate that the joint forces balanced
  // (gravity against the joint holding a pendulum) counts as zero.
  if (joints_) {
    Load(t, x, Side::kRight);
    const double te = std::nextafter(t, std::numeric_limits<double>::infinity());
    m.f_tape.tape->Evaluate(te, sim_.values(lane_) + m.f_tape.shift, fg_.data(), &sim_.externs(), 0,
                            lane_);
    bool balanced = true;
    for (size_t j = 0; j < n && balanced; ++j)
      balanced =
          !(tested(j) && joint_rows_[j] && std::abs(f[j]) > kRestRounding * std::abs(fg_[j]));
    if (!balanced) {
      // The rounding of a cancellation is that of the terms cancelled: in a
      // hanging chain a body's joint terms carry the weight of the bodies
      // below it, far more than its own.  The rates again, with the size of
      // their joint terms and the joint forces refined twice (a long
      // chain's K is less well conditioned): at rest they are rounding,
      // where the sample's own rates (f) may be a little more.  r_ and est_
      // are free here (step scratch).
      std::copy(fg_.data(), fg_.data() + n, r_.data());
      std::fill(est_.data(), est_.data() + n, 0.0);
      joints_->Apply(te, sim_.values(lane_), r_.data(), Prescribed(m), &sim_.externs(), est_.data(),
                     2);
      for (size_t j = 0; j < n; ++j)
        if (tested(j) && joint_rows_[j] &&
            std::abs(r_[j]) > kRestRounding * (std::abs(fg_[j]) + est_[j]))
          fn = std::max(fn, weighted(j));
    }
  }
  if (fn == 0.0) return std::numeric_limits<double>::infinity();
  const double first = kRestFraction / fn;
  if (!(first >= kRestMinGain * h)) return 0.0;
  const double delta = 1.0 / fn;
  for (size_t j = 0; j < n; ++j) y_[j] = tested(j) ? x[j] + delta * f[j] : x[j];
  EvalF(m, t, y_.data(), fy_.data(), Side::kRight, false);
  double jf = 0.0;
  for (size_t j = 0; j < n; ++j)
    if (tested(j))
      jf = std::max(jf, std::abs(fy_[j] - f[j]) / delta / (o.atol + o.rtol * std::abs(x[j])));
  const double second =
      jf > 0 ? std::sqrt(2.0 * kRestFraction / jf) : std::numeric_limits<double>::infinity();
  const double span = std::min(first, second);
  return span >= kRestMinGain * h ? span : 0.0;
}

bool Component::Step() {
  if (PendingRestart()) Restart();
  if (!CheckFinite()) return false;
  if (finished()) return true;
  const int k = wave_.size() - 1;
  const double t = wave_.time(k);
  const SolverOptions& o = sim_.options();
  const double span = sys_.t1 - sys_.t0;
  const double h_max = o.max_step > 0 ? o.max_step : span;
  const double h_min =
      std::max(1e-13 * span, 8 * std::numeric_limits<double>::epsilon() * std::abs(t));
  const SampleInfo info = wave_.info(k);
  newton_eta_ = info.newton_eta;  // kept with the sample: a resumed run sees the same
  Mode& mode = ModeAt(t);
  const bool implicit = UseImplicit(mode, info);
  const bool auto_method = o.method == SolverOptions::Method::kAuto && !mode.any_prescribed;
  double h = std::min(info.h_next, h_max);
  if (mode.autonomous && inputs_.empty()) {
    const double rest = RestSpan(mode, std::min(h, h_max));
    if (rest > 0) {
      const Plan plan = PlanStep(t, std::min(rest, h_max), NextBreakpoint(t), sys_.t1);
      SampleInfo next = info;
      next.restart = false;
      std::copy(wave_.x(k), wave_.x(k) + vars_.size(), x_.begin());
      std::copy(wave_.f(k), wave_.f(k) + vars_.size(), rate_.begin());
      wave_.Append(plan.t_end, x_.data(), rate_.data(), next);
      ++counters_.steps;
      ++counters_.rest_steps;
      jac_sample_ = -1;
      if (plan.landing) Restart();
      return true;
    }
  }
  if (o.method == SolverOptions::Method::kAuto && !mode.ballistic.rows.empty()) {
    const double ballistic = BallisticSpan(mode, std::min(h, h_max));
    if (ballistic > 0) {
      BallisticStep(mode, t, std::min(ballistic, h_max));
      return true;
    }
  }
  bool rejected = false;
  bool fresh_jacobian = false;
  double newton_failed = 0.0;  // the last step size Newton failed at here
  const long rhs_before = counters_.rhs_evaluations, lu_before = counters_.factorizations;
  for (;;) {
    const Plan plan = PlanStep(t, h, NextBreakpoint(t), sys_.t1);
    const double h_eff = plan.t_end - t;
    Attempt att;
    const bool ok = implicit ? TryStep(h_eff, plan.landing, fresh_jacobian, att)
                             : TryExplicitStep(mode, plan.t_end, plan.landing, att);
    if (ok && att.err <= 1.0) {
      SampleInfo next;
      next.implicit = implicit;
      next.err_prev = std::max(att.err, 1e-4);
      next.cheaper_returns = info.cheaper_returns;
      if (implicit) next.newton_eta = newton_eta_;
      double factor;
      bool cheaper_explicit = false;
      if (implicit) {
        const double grow = rejected ? 1.0 : kImplicitMaxFactor;
        factor = att.err > 0 ? std::clamp(kImplicitSafety * std::cbrt(1.0 / att.err),
                                          kImplicitMinFactor, grow)
                             : grow;
        const double cost = static_cast<double>(counters_.rhs_evaluations - rhs_before +
                                                counters_.factorizations - lu_before);
        next.implicit_cost = static_cast<float>(
            info.implicit_cost > 0 ? kCostMemory * info.implicit_cost + (1 - kCostMemory) * cost
                                   : cost);
        // Stiffness gone: ρ below the starting threshold and h·ρ small
        // enough for explicit steps — or explicit steps at their stability
        // limit would have covered this step for less (kExplicitStepCost).
        const bool calm = att.h_rho * factor < kExplicitComfort;
        cheaper_explicit =
            !calm && att.h_rho * kExplicitStepCost < kExplicitStability * next.implicit_cost;
        if (auto_method && rho_ <= kStartStiffRho && (calm || cheaper_explicit))
          next.stiff_votes = info.stiff_votes + 1;
        // Newton converged briskly: the next step keeps this Jacobian, and
        // its LU too when the step would grow only a little.
        const int age = wave_.size() - att.jac_sample;
        if (att.newton_iterations <= kReuseIterations * att.solves && age < kMaxJacobianAge) {
          next.jac_from = att.jac_sample;
          if (factor >= 1.0 && factor <= kKeepStepFactor) factor = 1.0;
        }
      } else {
        // err^−α err_prev^β as one exponential (two powers were 7% of a
        // torque-free top's run at rtol 1e-6).
        factor = std::exp(dp::kBeta * std::log(info.err_prev) - dp::kAlpha * std::log(att.err)) *
                 dp::kSafety;
        factor = std::clamp(factor, dp::kMinFactor, rejected ? 1.0 : dp::kMaxFactor);
        if (auto_method && att.h_rho > kExplicitStability) {
          next.stiff_votes = info.stiff_votes + 1;
        } else if (auto_method && att.h_rho > 0.0) {
          next.calm_votes = info.calm_votes + 1;
          next.stiff_votes = next.calm_votes >= kCalmVotes ? 0 : info.stiff_votes;
          if (next.calm_votes >= kCalmVotes) next.calm_votes = 0;
        } else {  // no information (the state did not change)
          next.stiff_votes = info.stiff_votes;
          next.calm_votes = info.calm_votes;
        }
      }
      const int votes = !implicit ? kSwitchVotes << std::min<int>(info.cheaper_returns, kMaxReturns)
                        : cheaper_explicit ? kCalmVotes
                                           : kSwitchVotes;
      if (next.stiff_votes >= votes) {
        next.implicit = !implicit;
        next.stiff_votes = 0;
        ++counters_.method_switches;
        if (cheaper_explicit && next.cheaper_returns < kMaxReturns) ++next.cheaper_returns;
      }
      next.h_next = std::min(h_eff * factor, h_max);
      if (implicit) {
        next.h_newton =
            newton_failed > 0 ? kNewtonCap * newton_failed : info.h_newton * kNewtonCapGrowth;
        next.h_next = std::min(next.h_next, std::max(next.h_newton, h_eff));
      }
      wave_.Append(plan.t_end, y_.data(), rate_.data(), next,
                   att.explicit_step ? bubble_.data() : nullptr);
      ++counters_.steps;
      if (att.trbdf2) ++counters_.trbdf2_steps;
      if (att.esdirk) ++counters_.esdirk_steps;
      if (att.explicit_step) ++counters_.explicit_steps;
      if (plan.landing) Restart();
      return true;
    }
    ++counters_.rejected_steps;
    rejected = true;
    if (!ok && implicit && att.jac_sample != wave_.size() - 1 && !fresh_jacobian) {
      fresh_jacobian = true;  // an old Jacobian: take it here and try the same step
      continue;
    }
    if (!ok && implicit) newton_failed = h_eff;
    if (!ok)
      h = h_eff * kNewtonFailureCut;
    else if (implicit)
      h = h_eff * std::max(kImplicitMinFactor, kImplicitSafety * std::cbrt(1.0 / att.err));
    else
      h = h_eff * std::max(dp::kMinFactor, dp::kSafety * std::pow(att.err, -dp::kAlpha));
    if (!(h >= h_min)) {
      std::ostringstream msg;
      msg << "component " << index_ << " (" << Describe() << ") failed at t=" << t << ": "
          << (ok         ? "error estimate stays above tolerance"
              : implicit ? "Newton iteration does not converge"
                         : "the right-hand side is not finite")
          << " even with step " << h_eff;
      error_ = msg.str();
      return false;
    }
  }
}

// Starts afresh at the last sample's time: appends a restart sample
// (RestartSample).
void Component::Restart() {
  const int k = wave_.size() - 1;
  const double t = wave_.time(k);
  SampleInfo info = RestartSample(t, wave_.x(k), wave_.info(k).implicit);
  info.cheaper_returns = wave_.info(k).cheaper_returns;
  wave_.Append(t, y_.data(), rate_.data(), info);
  ++counters_.restarts;
  jac_sample_ = -1;
}

// The restart sample at t from state x: applies jumps at t and prescribed
// values, evaluates right-hand-limit rates; state in y_, rates in rate_.
SampleInfo Component::RestartSample(double t, const double* x, bool implicit) {
  const size_t n = vars_.size();
  std::copy(x, x + n, y_.begin());
  bool jumped = false;
  for (auto [j, end] = JumpsAt(t); j != end; ++j) {
    y_[j->local] = j->value;
    jumped = true;
  }
  Mode& m = ModeAt(t);
  if (jumped && joints_) {
    // An impulse on a jointed body moves its whole group (joint impulses).
    Load(t, y_.data(), Side::kRight);
    joints_->ProjectVelocities(t, sim_.values(lane_), y_.data(), Prescribed(m), &sim_.externs());
  }
  // Prescribed rows take their values from their equations (twice: a
  // prescribed value may read another).
  for (int pass = 0; pass < 2 && m.any_prescribed; ++pass) {
    EvalF(m, t, y_.data(), fy_.data(), Side::kRight, false);
    for (size_t j = 0; j < n; ++j)
      if (m.prescribed[j]) y_[j] = fy_[j];
  }
  EvalF(m, t, y_.data(), fy_.data(), Side::kRight, false);
  Rates(m, t, y_.data(), fy_.data(), y_.data(), 0.0, rate_.data(), Side::kRight);
  SampleInfo info;
  info.h_next = sim_.restart_step();
  info.restart = true;
  info.jumps_seen = jump_generation_;
  info.implicit = implicit;
  return info;
}

bool Component::IsBreakpoint(double t) const {
  if (std::binary_search(static_breakpoints_.begin(), static_breakpoints_.end(), t)) return true;
  if (std::binary_search(own_times_.begin(), own_times_.end(), t)) return true;
  if (std::binary_search(inherited_.begin(), inherited_.end(), t)) return true;
  return false;
}

bool Component::PendingRestart() const {
  if (wave_.empty()) return false;
  const int k = wave_.size() - 1;
  const SampleInfo& info = wave_.info(k);
  if (!info.restart) return IsBreakpoint(wave_.time(k));
  // A restart sample is stale when a jump at its time came after it (an
  // impact at the very start, where the first sample is a restart).
  if (info.jumps_seen == jump_generation_) return false;
  for (auto [j, end] = JumpsAt(wave_.time(k)); j != end; ++j)
    if (j->generation > info.jumps_seen) return true;
  return false;
}

double Component::NextBreakpoint(double t) const {
  double best = std::numeric_limits<double>::infinity();
  auto it = std::upper_bound(static_breakpoints_.begin(), static_breakpoints_.end(), t);
  if (it != static_breakpoints_.end()) best = *it;
  for (const auto* times : {&own_times_, &inherited_}) {
    auto jt = std::upper_bound(times->begin(), times->end(), t);
    if (jt != times->end()) best = std::min(best, *jt);
  }
  return best;
}

// ---- truncation and events -----------------------------------------------------

double Component::Truncate(double t, bool strict) {
  int keep = wave_.KeepIndex(t);
  while (strict && keep > 0 && wave_.time(keep) >= t) --keep;
  const int removed = wave_.size() - 1 - keep;
  if (removed > 0) {
    counters_.truncated_steps += removed;
    wave_.Resize(keep + 1);
  }
  jac_sample_ = -1;
  return wave_.t_end();
}

void Component::CopyResults(const Component& from) {
  wave_ = from.wave_;
  jumps_ = from.jumps_;
  jump_generation_ = from.jump_generation_;
  holds_ = from.holds_;
  own_times_ = from.own_times_;
  last_mode_ = nullptr;
  jac_sample_ = -1;
}

// Jumps are kept in time order (ties in the order they were added), so the
// jumps at t are one binary search away and a new jump, which is almost
// always the latest (a change at t first forgets what follows t), is
// appended.  The component's own event times are kept sorted alongside
// (with repeats, so removing one occurrence leaves the others).
std::pair<std::vector<Component::Jump>::const_iterator,
          std::vector<Component::Jump>::const_iterator>
Component::JumpsAt(double t) const {
  auto lo =
      std::partition_point(jumps_.begin(), jumps_.end(), [t](const Jump& j) { return j.t < t; });
  auto hi = lo;
  while (hi != jumps_.end() && hi->t == t) ++hi;
  return {lo, hi};
}

void Component::AddTime(double t) {
  own_times_.insert(std::upper_bound(own_times_.begin(), own_times_.end(), t), t);
}

void Component::RemoveTime(double t) {
  auto it = std::lower_bound(own_times_.begin(), own_times_.end(), t);
  if (it != own_times_.end() && *it == t) own_times_.erase(it);
}

void Component::AddJump(double t, int local, double value) {
  // A later jump of the same variable at the same time supersedes it.
  ++jump_generation_;
  auto [lo, hi] = JumpsAt(t);
  for (auto j = lo; j != hi; ++j)
    if (j->local == local) {
      Jump& same = jumps_[static_cast<size_t>(j - jumps_.cbegin())];
      same.value = value;
      same.generation = jump_generation_;
      return;
    }
  jumps_.insert(hi, {t, local, value, jump_generation_});
  AddTime(t);
}

void Component::AddHold(double t, int local, double value) {
  holds_.push_back({t, std::numeric_limits<double>::infinity(), local, value});
  AddTime(t);
  last_mode_ = nullptr;
}

void Component::ReleaseHold(double t, int local) {
  for (Hold& h : holds_)
    if (h.local == local && h.from < t && t < h.to) {
      if (std::isfinite(h.to)) RemoveTime(h.to);
      h.to = t;
      AddTime(t);
    }
  last_mode_ = nullptr;
}

bool Component::Held(int local, double t) const {
  for (const Hold& h : holds_)
    if (h.local == local && h.from <= t && t < h.to) return true;
  return false;
}

void Component::ForgetAfter(double t, bool strict) {
  auto after = [t, strict](double x) { return strict ? x >= t : x > t; };
  // Every event time dropped here (a jump's, a hold's start or end) is after
  // t, and every one kept is not: the sorted lists lose their tails.
  jumps_.erase(std::partition_point(jumps_.begin(), jumps_.end(),
                                    [&](const Jump& j) { return !after(j.t); }),
               jumps_.end());
  own_times_.erase(std::partition_point(own_times_.begin(), own_times_.end(),
                                        [&](double x) { return !after(x); }),
                   own_times_.end());
  std::erase_if(holds_, [&](const Hold& h) { return after(h.from); });
  for (Hold& h : holds_)
    if (after(h.to)) h.to = std::numeric_limits<double>::infinity();
  last_mode_ = nullptr;
}

void Component::BreakpointsInto(std::vector<double>& out) const {
  out.insert(out.end(), own_times_.begin(), own_times_.end());
  out.insert(out.end(), inherited_.begin(), inherited_.end());
}

void Component::SetDynamicBreakpoints(const std::vector<double>& upstream) {
  // `upstream` is a concatenation of sorted lists (own and inherited times
  // of each upstream component): merge the runs in linear time in the usual
  // case rather than sorting.  The component's own times are kept sorted as
  // events come and go, so a component with no upstream (a body on its own
  // colliding thousands of times) pays nothing here.
  std::vector<double> times = upstream;
  constexpr int kMaxRuns = 16;  // beyond this many runs a sort is cheaper
  int runs = 0;
  auto run_start = times.begin();
  while (run_start != times.end() && ++runs <= kMaxRuns) {
    auto run_end = std::is_sorted_until(run_start, times.end());
    if (run_start != times.begin()) std::inplace_merge(times.begin(), run_start, run_end);
    run_start = run_end;
  }
  if (run_start != times.end()) std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  inherited_ = std::move(times);
}

std::string Component::Describe() const {
  std::string s;
  for (size_t j = 0; j < vars_.size() && j < 6; ++j) {
    if (j) s += ", ";
    s += sys_.variables[vars_[j]].name;
  }
  if (vars_.size() > 6) s += ", ... (" + std::to_string(vars_.size()) + " variables)";
  return s;
}

}  // namespace asgard::solver
