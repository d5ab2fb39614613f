// Simulation: the partitioned, event-driven solution of a scene's equations
// (seed 5.2.3).
//
//   FormEquations ─▶ Partition (Tarjan) ─▶ Schedule ─▶ Component::Step ─▶ after_step hook
//                                             ▲                               │ (collisions)
//                                             └──────── Truncate ◀────────────┘
//
// Schedule (the seed's pseudo-code): a priority queue holds the components
// that may take their next step, ordered by the time they have reached (ties
// by component index, so runs are deterministic).  The component furthest
// behind steps next.  A component may step only when every component it reads
// from has been computed at least to the end of that step, so values are
// interpolated, never extrapolated.  After a step, the component itself and
// the components that read from it are checked for eligibility.
//
// Truncate(c, t) cuts c back to its last sample at or before t and,
// transitively, every component reading from it back to the time c keeps;
// the queue is repaired and the run resumes.  Because a component's step
// depends only on its own last sample and on its inputs' waveforms, a
// truncated component that resumes with unchanged inputs recomputes exactly
// the samples it lost.
//
// Threads (SolverOptions::threads > 1): each time the component furthest
// behind is taken from the queue, up to threads − 1 more eligible ones are
// taken with it, none reading another of the batch, and all take their runs
// of steps at once, one per thread ("lane").  A component's step reads its
// own samples and its inputs' finished waveforms only, and its inputs are
// not in the batch, so each run is the one a single thread would take.
// Observers (after_step: collision checks, truncations) hear of each run
// when the whole batch has ended, on the calling thread, before anything
// else is scheduled; what a batch holds is decided there too, so a run is
// the same sequence of batches whatever the threads' timing.  Each lane has
// its own value array and register file per tape (shared tapes:
// TapeCache); building a mode (the pool grows with derivatives, the tape
// cache with tapes) takes build_mutex.  The workers start with the first
// batch (a scene of one component never starts them), wait by spinning
// briefly and then sleeping, and end with the Simulation; a run its worker
// has not claimed when the calling thread is done with its own is taken
// back and run there (a sleeping worker costs no wake-up latency).  Batches
// of runs of a step or two save less than their hand-overs cost, so a
// streak of them makes the calling thread go alone for a while
// (simulation.cc, kThinRun).  Rejected: a task
// per component on a pool with work stealing — the order of observer calls
// and so a run's cost would depend on timing; results would not, but
// reproducible costs keep the benchmarks and budgets honest.
//
// Rejected alternatives: (1) one global step for all components — the seed's
// Figure 5.7 shows the cost grows with the product of size and stiffness;
// (2) waveform relaxation — iterates whole waveforms to convergence, wasteful
// when most coupling is one-way; (3) run each component to the end in order —
// a collision then throws away whole futures (seed 5.2.4, variant 5, kept as
// SolverOptions::Schedule::kSequential for comparison).
#pragma once

#include <functional>
#include <memory>
#include <mutex>
#include <queue>
#include <span>
#include <string>
#include <vector>

#include "core/physics/equations.h"
#include "core/solver/component.h"
#include "core/solver/partition.h"
#include "core/solver/tape_cache.h"

namespace asgard::solver {

// What one Run may spend.  A hostile or careless scene (a body at absurd
// speed in a closed box, a stiff system at a tiny step) must end with an
// error naming the time reached and the bodies involved, never run for hours
// or exhaust memory.  0 means no limit.
struct RunBudget {
  // Accepted steps of all components in one Run, recomputations after
  // truncations included (a run of the samples takes ~1e5; 5e7 is minutes).
  long steps = 50'000'000;
  // Velocity jumps (impacts and resting-contact events) one body may take
  // in one Run.  Each jump restarts the body's component (and truncates
  // its readers), so this also bounds the time a run can spend on one body
  // bouncing.  A body resting alone makes about one resting event per check
  // window (1024 per run) while awake; one in a pile makes one whenever any
  // pair of its island lands (~15 per window measured in an island of 52
  // cubes), which a 5 s pile of 100 cubes exhausts.
  long impulses_per_body = 10'000;
  // Impacts of all bodies in one Run, as the collision monitor counts them
  // (pipeline::Solve enforces it: the solver itself does not see impacts).
  long impacts = 200'000;
  // Waveform storage of all components, in MB (checked every 1024 steps).
  double memory_mb = 2048;
};

// The threads worth asking for on this machine: its cores, at most
// expr::Tape::kLanes (SolverOptions::threads).
int MachineThreads();

class Simulation {
 public:
  Simulation(const physics::EquationSystem& system, SolverOptions options);
  ~Simulation();

  // Runs until every component reaches the end time.  Returns false when a
  // component fails; error() then names it, its variables and the time.
  // `progress` (may be empty) receives the least time reached, in [t0, t1].
  // Each call may spend budget() (steps, memory) afresh; exhausting it fails
  // the run.
  bool Run(const std::function<void(double)>& progress = {});
  const std::string& error() const { return error_; }
  // The variable whose value stopped the run by not being finite, or a
  // variable of the component that spent most of an exhausted budget, or -1.
  int failed_variable() const { return failed_variable_; }

  const RunBudget& budget() const { return budget_; }
  void set_budget(const RunBudget& budget) { budget_ = budget; }
  // Accepted steps since the current (or last) Run began.
  long steps_this_run() const { return run_steps_; }
  // Batches of runs taken on several threads at once (Threads, above).
  long batches() const { return batches_; }
  // Velocity jumps body b has taken since the current (or last) Run began.
  long impulses_this_run(int body) const;
  // Bytes the waveforms of all components hold.
  double WaveformBytes() const;
  // Names of the bodies whose variables component c holds ("b1, b2"), or
  // "component c" when it holds none.
  std::string BodiesOf(int c) const;

  // Takes one step of the component furthest behind (with no after_step
  // observer, a run of up to 64 of its steps while it stays within 1/8 of
  // the span ahead of the next in the queue); false when none is eligible
  // (done) or on failure.
  bool StepOnce();

  const physics::EquationSystem& system() const { return sys_; }
  const SolverOptions& options() const { return options_; }
  const Partition& partition() const { return partition_; }
  int component_count() const { return static_cast<int>(components_.size()); }
  const Component& component(int c) const { return *components_[c]; }
  int component_of(int var) const { return partition_.component_of[var]; }
  // Exact joints (indices into the system's joints) whose bodies component c holds.
  const std::vector<int>& joints_of(int c) const { return joints_of_[c]; }
  // The variables that the equation of `var` reads (its right-hand side and
  // overrides; a jointed group's acceleration rows also read their body and
  // the next body of the group, which makes the group one component).
  std::span<const int> reads(int var) const { return reads_.of(var); }
  // Index of `var` within its component's waveform.
  int local_index(int var) const { return local_index_[var]; }
  Counters totals() const;
  // The least time every component has reached.
  double time_reached() const;

  // Value and rate of variable `var` at time t (within what is computed).
  double Value(int var, double t, Side side = Side::kRight) const;
  // Value (Rate) of vars[j] at t for j < n into out, located once per run
  // of variables of one component.
  void Values(const int* vars, int n, double t, double* out, Side side = Side::kRight) const {
    Interpolate(vars, n, t, side, false, out);
  }
  void Rates(const int* vars, int n, double t, double* out, Side side = Side::kRight) const {
    Interpolate(vars, n, t, side, true, out);
  }
  double Rate(int var, double t, Side side = Side::kRight) const;

  // Takes over component `from` of an earlier simulation as component c
  // (same variables, same equations, same inputs).
  void CopyResults(int c, const Component& from);
  // Starts component c and everything reading from it afresh from the
  // initial values now in the equation system (after an edit changed them).
  void ResetToStart(int c);
  // Cuts component c back to t (with `strict`, to before t) and everything
  // reading from it (see above).
  void Truncate(int c, double t, bool strict = false);
  // Sets `var` to `value` at time t (right limit), as a collision impulse
  // does: truncates its component to t and makes it restart there.
  void SetValueAt(int var, double t, double value);
  // Holds `var` at `value` from t on (resting contact), or ends the hold at t.
  void HoldAt(int var, double t, double value);
  void ReleaseAt(int var, double t);
  bool Held(int var, double t) const;
  // One change of a variable at an instant: a jump to `value`, a hold at
  // `value`, or the end of a hold.
  struct Edit {
    enum class Kind { kSet, kHold, kRelease };
    Kind kind;
    int var;
    double value = 0.0;
  };
  // Makes all `edits` at t at once, in their order (a later jump of the same
  // variable supersedes an earlier one): every component they touch is cut
  // back once, its breakpoints and its readers' are rebuilt once, and
  // observers hear of it once.  The same result as calling SetValueAt,
  // HoldAt and ReleaseAt in turn, at the cost of one of them per component
  // (a resting event writes a dozen variables of every body in its island).
  // Values the caller reads for the edits must be read before: a component
  // cut back to t answers for t with its last sample before t.
  void ApplyAt(double t, const std::vector<Edit>& edits);

  // Stops the run with `message` (an observer found a problem it cannot
  // resolve); Run and StepOnce then return false and error() says why.
  void Fail(const std::string& message) {
    failed_ = true;
    error_ = message;
  }

  // Called when Run begins (observers that keep per-run counts).
  std::function<void(Simulation&)> before_run;
  // Called after every accepted step of a component (collision detection).
  std::function<void(Simulation&, int component)> after_step;
  // Called for each component truncated, with the time it keeps, and once
  // after the outermost Truncate or SetValueAt call has finished (observers
  // that react by truncating more do it there, not inside on_truncate).
  std::function<void(Simulation&, int component, double t)> on_truncate;
  std::function<void(Simulation&)> after_truncate;

  // Used by components.  Each lane's (thread's) value array.
  double* values(int lane = 0) {
    return lane == 0 ? values_.data() : lane_values_[static_cast<size_t>(lane) - 1].data();
  }
  // Held while building a mode (Component::BuildMode, PrepareJacobian).
  std::mutex& build_mutex() { return build_mutex_; }
  double InputValue(int var, double t, Side side) const;
  void Interpolate(const int* vars, int n, double t, Side side, bool rate, double* out) const;
  const expr::ExternFn& externs() const { return externs_; }
  double restart_step() const { return restart_step_; }
  // Rate tapes shared among components with the same equations.
  TapeCache& tapes() { return tapes_; }

 private:
  // Counts nested truncations; the outermost one, when it ends, calls
  // after_truncate.
  struct TruncationScope {
    explicit TruncationScope(Simulation& s) : sim(s) { ++sim.truncate_depth_; }
    ~TruncationScope() {
      if (--sim.truncate_depth_ == 0 && sim.after_truncate) sim.after_truncate(sim);
    }
    Simulation& sim;
  };
  // Truncate for several components at once, each to t.
  void TruncateAll(const std::vector<int>& cs, double t, bool strict);
  bool Eligible(int c) const;
  // Counts `steps` accepted steps of c against the budget; false (and the
  // run failed) once it is exhausted.
  bool Charge(int c, long steps = 1);
  // A run of steps of component c without observers (a lane's work): up to
  // kRunSteps while it stays eligible and, with ahead > 0, before `limit`.
  struct RunResult {
    int steps = 0;
    bool ok = true;
  };
  RunResult RunSteps(int c, double ahead, double limit);
  // Takes the batch (its first the component furthest behind, already off
  // the queue) to the lanes at once (Threads, above).
  bool StepBatch(const int* batch, int size);
  // Whether c may take a run of steps (StepOnce): no observer watches, or c
  // has been calm for kCalmSteps.
  bool MayRun(int c) const;
  // Whether c reads from a member of batch[0..size) or one reads from c.
  bool Related(int c, const int* batch, int size) const;
  // Worker threads (simulation.cc), started with the first batch.
  struct Crew;
  std::unique_ptr<Crew> crew_;
  std::vector<std::vector<double>> lane_values_;  // lanes 1 ...
  std::mutex build_mutex_;
  long batches_ = 0;
  // Turns of the queue (StepOnce's components taken), and the batches of
  // short runs in a row: until turn solo_until_ no batches are formed
  // (simulation.cc, kThinRun).
  long turns_ = 0;
  int thin_batches_ = 0;
  long solo_until_ = 0;
  long solo_turns_ = 64;
  // Counts a jump of var at t against its body's budget of impulses.
  void ChargeImpulse(int var, double t);
  void StartRun();
  void Push(int c);
  void RepairQueue(const std::vector<int>& affected);
  // Recomputes the dynamic breakpoints of `cs` and of everything downstream.
  void RebuildBreakpoints(const std::vector<int>& cs);

  const physics::EquationSystem& sys_;
  SolverOptions options_;
  int lanes_;  // threads stepping components: options_.threads, within 1 … expr::Tape::kLanes
  Partition partition_;
  std::vector<int> local_index_;             // variable → index within its component
  std::vector<std::vector<int>> joints_of_;  // per component
  ReadGraph reads_;                          // per variable: what its equation reads
  std::vector<std::unique_ptr<Component>> components_;
  std::vector<double> values_;
  expr::ExternFn externs_;
  double restart_step_ = 0.0;
  TapeCache tapes_;
  struct Entry {
    double t;
    int c;
    uint64_t stamp;
    bool operator>(const Entry& o) const { return t != o.t ? t > o.t : c > o.c; }
  };
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue_;
  std::vector<uint64_t> stamp_;  // current stamp per component
  std::vector<char> queued_;
  // Steps each component has taken since a truncation last cut it (StepOnce:
  // a component an observer watches runs ahead only once calm).
  std::vector<int> calm_steps_;
  long repairs_ = 0;  // RepairQueue calls (the sequential schedule rescans after one)
  std::string error_;
  int failed_variable_ = -1;
  bool failed_ = false;
  int truncate_depth_ = 0;
  RunBudget budget_;
  long run_steps_ = 0;
  std::vector<long> steps_at_run_start_;  // per component
  std::vector<long> impulses_;            // per body, this run
  std::vector<double> last_impulse_t_;    // per body: jumps at one time are one impulse
};

}  // namespace asgard::solver
