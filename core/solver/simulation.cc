// The event-driven scheduler and truncation (design note in simulation.h).
#include "core/solver/simulation.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <limits>
#include <sstream>
#include <thread>

#include "core/expr/expr.h"

namespace asgard::solver {
namespace {

// How far (a fraction of the run's span) a component may run ahead of the
// component furthest behind when no observer watches the steps, and how many
// steps it may take in a row (locality gains little beyond a few dozen; the
// bound keeps progress reports and the interleaving fine-grained).
constexpr double kRunAhead = 1.0 / 8.0;
constexpr int kRunSteps = 64;
// Under an observer (collision checks) a component runs ahead only after
// this many steps without being cut back (StepOnce).
constexpr int kCalmSteps = 32;

// A body held by a spring this fast is not fused (FusableBodies).  The
// explicit pair is stable for h·ρ up to about 3.3, so such a spring bounds
// its steps to 0.07 s or less, finer than smooth motion needs at moderate
// tolerance: its component takes the implicit path wherever the spring's
// rate, not accuracy, bounds the steps.
constexpr double kStiffSpringRate = 50.0;

// Per body: whether its components may be fused into one (PartitionEquations'
// body_of).  A body on the implicit path because of some of its rows stays
// apart, so that its other rows (a resting spin, an idle axis) do not ride
// along in the Newton matrix: a body whose state a trajectory prescribes,
// and one held by a stiff spring.
std::vector<char> FusableBodies(const physics::EquationSystem& sys) {
  std::vector<char> fusable(sys.bodies.size(), 1);
  for (size_t b = 0; b < sys.bodies.size(); ++b)
    fusable[b] = sys.bodies[b].spring_rate < kStiffSpringRate;
  for (const auto& v : sys.variables)
    if (v.body >= 0 && !v.overrides.empty()) fusable[v.body] = 0;
  return fusable;
}

// The reference graph.  With `fusable` (per body, bodies fused:
// PartitionEquations' body_of), a fusable body whose equations read only its
// own variables and whose variables no other equation reads is listed as an
// island and its arcs are left out: it is one component whatever they are,
// and a scene of many idle bodies costs one walk of each body's
// expressions, not one per variable, a sort per row and a search of its
// cycles.
ReadGraph ReadsOf(const physics::EquationSystem& sys, const std::vector<char>& fusable) {
  // An exact joint's force depends on the whole state of every body it
  // connects, directly or through other joints: a jointed group must be one
  // component.  Each body's acceleration rows read its own state and the
  // next body's (a ring): the group is one strongly connected component, as
  // it would be with every row reading every variable, at a cost linear in
  // the group's size rather than quadratic.
  const int nb = static_cast<int>(sys.bodies.size());
  std::vector<int> root(nb);
  for (int b = 0; b < nb; ++b) root[b] = b;
  auto find = [&](int b) {
    while (root[b] != b) b = root[b] = root[root[b]];
    return b;
  };
  std::vector<char> jointed(nb, 0);
  for (const auto& j : sys.joints) {
    jointed[j.body_a] = 1;
    if (j.body_b >= 0) {
      jointed[j.body_b] = 1;
      root[find(j.body_a)] = find(j.body_b);
    }
  }
  // next[b]: the next jointed body of b's group in index order (wrapping),
  // or -1 for a body in no joint.
  std::vector<int> next(nb, -1), first(nb, -1), last(nb, -1);
  for (int b = 0; b < nb; ++b) {
    if (!jointed[b] || sys.bodies[b].first_var < 0) continue;
    const int g = find(b);
    if (last[g] >= 0)
      next[last[g]] = b;
    else
      first[g] = b;
    last[g] = b;
  }
  for (int g = 0; g < nb; ++g)
    if (last[g] >= 0) next[last[g]] = first[g];

  // Walks over expression nodes marked with a fresh stamp each (Pool::
  // Variables builds a hash set per call, which was a quarter of a resting
  // body's set-up); `read` sees each variable once per walk.
  const size_t nv = sys.variables.size();
  std::vector<uint32_t> stamp(sys.pool.size(), 0), seen(nv, 0);
  uint32_t mark = 0;
  std::vector<expr::NodeId> stack;
  auto walk = [&](size_t begin, size_t end, auto&& read) {
    ++mark;
    stack.clear();
    for (size_t i = begin; i < end; ++i) {
      const auto& v = sys.variables[i];
      stack.push_back(v.rhs);
      for (const auto& o : v.overrides) stack.push_back(o.expr);
    }
    while (!stack.empty()) {
      const expr::NodeId id = stack.back();
      stack.pop_back();
      if (stamp[id] == mark) continue;
      stamp[id] = mark;
      const expr::Node& n = sys.pool.node(id);
      if (n.op == expr::Op::kVar && seen[n.index] != mark) {
        seen[n.index] = mark;
        read(n.index);
      }
      stack.insert(stack.end(), n.args.begin(), n.args.end());
    }
  };

  // Islands: a body with state, no override, alone in its joint group (if
  // any), whose rows read only its own variables...
  std::vector<char> island(nb, 0);
  if (!fusable.empty())
    for (int b = 0; b < nb; ++b) {
      const int v0 = sys.bodies[b].first_var;
      if (v0 < 0 || !fusable[b] || (next[b] >= 0 && next[b] != b)) continue;
      bool closed = static_cast<size_t>(v0 + physics::kBodySlots) <= nv;
      // (A body with an override is not fusable: FusableBodies.)
      for (int k = 0; closed && k < physics::kBodySlots; ++k)
        closed = sys.variables[v0 + k].body == b;
      if (!closed) continue;
      walk(v0, v0 + physics::kBodySlots,
           [&](int r) { closed = closed && r >= v0 && r < v0 + physics::kBodySlots; });
      island[b] = closed;
    }
  auto island_of = [&](int v) {
    const int b = sys.variables[v].body;
    return b >= 0 && island[b] ? b : -1;
  };
  // ...and that no other row reads.  Rows are walked in order, so a body
  // found read by a later row has had its own rows skipped: it is no island,
  // and the graph is built again (only once: its rows read no other body).
  for (;;) {
    ReadGraph g;
    g.start.reserve(nv + 1);
    g.vars.reserve(8 * nv);
    bool spoiled = false;
    for (size_t i = 0; i < nv; ++i) {
      const int own = island_of(static_cast<int>(i));
      if (own >= 0) {
        if (static_cast<int>(i) == sys.bodies[own].first_var)
          g.islands.push_back({static_cast<int>(i), physics::kBodySlots});
        g.start.push_back(static_cast<int>(g.vars.size()));
        continue;
      }
      const size_t begin = g.vars.size();
      auto read = [&](int r) {
        if (const int b = island_of(r); b >= 0) {
          island[b] = 0;
          spoiled = true;
        }
        g.vars.push_back(r);
      };
      walk(i, i + 1, read);
      const auto& v = sys.variables[i];
      if (v.body >= 0 && next[v.body] >= 0) {
        const int first_var = sys.bodies[v.body].first_var;
        const int slot = static_cast<int>(i) - first_var;
        if (slot == physics::kDx || slot == physics::kDy || slot == physics::kDz ||
            slot == physics::kW1 || slot == physics::kW2 || slot == physics::kW3) {
          for (int k = 0; k <= physics::kBodySlots; ++k) {
            const int r =
                k < physics::kBodySlots ? first_var + k : sys.bodies[next[v.body]].first_var;
            if (seen[r] != mark) {
              seen[r] = mark;
              read(r);
            }
          }
        }
      }
      std::sort(g.vars.begin() + static_cast<std::ptrdiff_t>(begin), g.vars.end());
      g.start.push_back(static_cast<int>(g.vars.size()));
    }
    if (!spoiled) return g;
  }
}

// How many queue entries a batch looks at for partners of the component
// furthest behind (each costs a pop and, if refused, a push).
constexpr int kPartnerLook = 8;
// Batches whose partners each took at most kThinRun steps save less than
// their hand-overs cost (1000 pendulums at rest: one rest step each, 0.88×
// the time of one thread): after kThinBatches of them in a row the calling
// thread goes alone for kSoloTurns turns of the queue, twice as many after
// each further such streak (at most kSoloTurnsMax), and tries again.  The
// decision reads step counts only, so a run's batches still do not depend
// on timing.
constexpr int kThinRun = 2;
constexpr int kThinBatches = 8;
constexpr long kSoloTurns = 64;
constexpr long kSoloTurnsMax = 1L << 16;
// How long a thread spins for a change of its slot before it sleeps: longer
// than the gap between batches of a busy run, short enough that an idle
// worker (a run with no partners, a machine shared with other work) gives
// its core up at once.
constexpr auto kSpin = std::chrono::microseconds(50);

void Pause() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

// Waits until `ok(state)`, spinning for kSpin and then sleeping; returns the state.
template <typename Ok>
int Await(const std::atomic<int>& state, Ok ok) {
  const auto until = std::chrono::steady_clock::now() + kSpin;
  for (int spins = 0;; ++spins) {
    const int v = state.load(std::memory_order_acquire);
    if (ok(v)) return v;
    if ((spins & 63) == 63 && std::chrono::steady_clock::now() > until) break;
    Pause();
  }
  for (;;) {
    const int v = state.load(std::memory_order_acquire);
    if (ok(v)) return v;
    state.wait(v, std::memory_order_acquire);
  }
}

}  // namespace

int MachineThreads() {
  const unsigned cores = std::thread::hardware_concurrency();
  return static_cast<int>(std::clamp(cores, 1u, static_cast<unsigned>(expr::Tape::kLanes)));
}

// The worker threads: lane k (1 ...) is thread k − 1, with a slot through
// which the calling thread posts a run of one component and the worker
// posts back its result.
struct Simulation::Crew {
  // A posted run is claimed by its worker (kPosted → kRunning), or taken
  // back by the calling thread when it is done with its own run first
  // (kPosted → kIdle, TakeBack): a worker that has gone to sleep then
  // costs no wake-up latency.
  enum State : int { kIdle, kPosted, kRunning, kDone, kQuit };
  struct alignas(64) Slot {
    std::atomic<int> state{kIdle};
    int c = -1;
    double ahead = 0.0, limit = 0.0;
    RunResult result;
    std::exception_ptr thrown;
  };
  std::vector<std::unique_ptr<Slot>> slots;
  std::vector<std::thread> threads;

  Crew(Simulation& sim, int lanes) {
    for (int k = 1; k < lanes; ++k) slots.push_back(std::make_unique<Slot>());
    for (int k = 1; k < lanes; ++k)
      threads.emplace_back([&sim, &slot = *slots[static_cast<size_t>(k) - 1]] {
        for (;;) {
          int v = Await(slot.state, [](int s) { return s == kPosted || s == kQuit; });
          if (v == kQuit) return;
          if (!slot.state.compare_exchange_strong(v, kRunning, std::memory_order_acquire))
            continue;  // taken back
          try {
            slot.result = sim.RunSteps(slot.c, slot.ahead, slot.limit);
          } catch (...) {
            slot.result = {0, false};
            slot.thrown = std::current_exception();
          }
          slot.state.store(kDone, std::memory_order_release);
          slot.state.notify_one();
        }
      });
  }
  ~Crew() {
    for (auto& slot : slots) {
      slot->state.store(kQuit, std::memory_order_release);
      slot->state.notify_one();
    }
    for (auto& t : threads) t.join();
  }
  void Post(int lane, int c, double ahead, double limit) {
    Slot& slot = *slots[static_cast<size_t>(lane) - 1];
    slot.c = c;
    slot.ahead = ahead;
    slot.limit = limit;
    slot.thrown = nullptr;
    slot.state.store(kPosted, std::memory_order_release);
    slot.state.notify_one();
  }
  // Whether the run posted to `lane` was taken back before its worker
  // claimed it (the caller then takes it itself).
  bool TakeBack(int lane) {
    int posted = kPosted;
    return slots[static_cast<size_t>(lane) - 1]->state.compare_exchange_strong(
        posted, kIdle, std::memory_order_acquire);
  }
  Slot& Wait(int lane) {
    Slot& slot = *slots[static_cast<size_t>(lane) - 1];
    Await(slot.state, [](int s) { return s == kDone; });
    slot.state.store(kIdle, std::memory_order_relaxed);
    return slot;
  }
};

Simulation::Simulation(const physics::EquationSystem& system, SolverOptions options)
    : sys_(system), options_(options), lanes_(std::clamp(options.threads, 1, expr::Tape::kLanes)) {
  const bool fuse = options_.partition && options_.fuse_chains && options_.fuse_bodies;
  const std::vector<char> fusable = fuse ? FusableBodies(sys_) : std::vector<char>();
  reads_ = ReadsOf(sys_, fusable);
  std::vector<int> body_of;
  if (fuse) {
    body_of.assign(sys_.variables.size(), -1);
    for (size_t i = 0; i < sys_.variables.size(); ++i)
      if (const int b = sys_.variables[i].body; b >= 0 && fusable[b]) body_of[i] = b;
  }
  partition_ = PartitionEquations(reads_, !options_.partition, options_.fuse_chains, body_of);
  values_.assign(sys_.variables.size(), 0.0);
  externs_ = sys_.externs();
  const double span = sys_.t1 - sys_.t0;
  restart_step_ = options_.initial_step > 0 ? options_.initial_step : 1e-4 * span;
  if (options_.max_step > 0) restart_step_ = std::min(restart_step_, options_.max_step);
  local_index_.assign(sys_.variables.size(), -1);
  for (size_t c = 0; c < partition_.components.size(); ++c) {
    const auto& vars = partition_.components[c];
    for (size_t j = 0; j < vars.size(); ++j) local_index_[vars[j]] = static_cast<int>(j);
    components_.push_back(std::make_unique<Component>(*this, static_cast<int>(c), vars));
  }
  joints_of_.assign(partition_.components.size(), {});
  for (size_t j = 0; j < sys_.joints.size(); ++j) {
    const int v = sys_.bodies[sys_.joints[j].body_a].first_var;
    if (v >= 0) joints_of_[partition_.component_of[v]].push_back(static_cast<int>(j));
  }
  // Dependency order: each component after those it reads from.
  for (auto& comp : components_) comp->Initialize();
  stamp_.assign(components_.size(), 0);
  queued_.assign(components_.size(), 0);
  calm_steps_.assign(components_.size(), kCalmSteps);
  for (size_t c = 0; c < components_.size(); ++c) Push(static_cast<int>(c));
}

Simulation::~Simulation() { crew_.reset(); }

double Simulation::InputValue(int var, double t, Side side) const {
  return components_[partition_.component_of[var]]->waveform().Value(local_index_[var], t, side);
}

double Simulation::Value(int var, double t, Side side) const { return InputValue(var, t, side); }

void Simulation::Interpolate(const int* vars, int n, double t, Side side, bool rate,
                             double* out) const {
  constexpr int kRun = 16;
  int local[kRun];
  for (int j = 0; j < n;) {
    const int c = partition_.component_of[vars[j]];
    int m = 0;
    while (j + m < n && m < kRun && partition_.component_of[vars[j + m]] == c) {
      local[m] = local_index_[vars[j + m]];
      ++m;
    }
    components_[c]->waveform().Interpolate(local, m, t, side, rate, out + j);
    j += m;
  }
}

double Simulation::Rate(int var, double t, Side side) const {
  return components_[partition_.component_of[var]]->waveform().Rate(local_index_[var], t, side);
}

Counters Simulation::totals() const {
  Counters total;
  for (const auto& c : components_) total += c->counters();
  return total;
}

double Simulation::time_reached() const {
  double t = sys_.t1;
  for (const auto& c : components_) t = std::min(t, c->t_end());
  return t;
}

bool Simulation::Eligible(int c) const {
  const Component& comp = *components_[c];
  if (comp.finished()) return false;
  const double end = comp.NextEnd();
  for (int u : partition_.upstream[c]) {
    if (components_[u]->t_end() < end) return false;
  }
  return true;
}

void Simulation::Push(int c) {
  if (queued_[c] || !Eligible(c)) return;
  queued_[c] = 1;
  queue_.push({components_[c]->t_end(), c, stamp_[c]});
}

bool Simulation::StepOnce() {
  while (!failed_ && !queue_.empty()) {
    const Entry e = queue_.top();
    queue_.pop();
    if (e.stamp != stamp_[e.c]) continue;  // superseded by a truncation
    queued_[e.c] = 0;
    if (!Eligible(e.c)) continue;
    ++turns_;
    if (lanes_ > 1 && turns_ >= solo_until_ && MayRun(e.c)) {
      // Partners for the lanes: eligible components that may take a run of
      // steps, that neither read from the batch nor are read by it; the
      // others go back to the queue.  (Under an observer a component in
      // contact takes one step at a time: a batch of single steps costs
      // more in hand-overs than it saves.)
      int batch[expr::Tape::kLanes] = {e.c};
      int size = 1;
      Entry refused[kPartnerLook];
      int n_refused = 0;
      for (int looked = 0; size < lanes_ && looked < kPartnerLook && !queue_.empty(); ++looked) {
        const Entry p = queue_.top();
        queue_.pop();
        if (p.stamp != stamp_[p.c]) continue;
        if (!MayRun(p.c) || Related(p.c, batch, size)) {
          refused[n_refused++] = p;
          continue;
        }
        queued_[p.c] = 0;
        if (Eligible(p.c)) batch[size++] = p.c;
      }
      for (int k = 0; k < n_refused; ++k) queue_.push(refused[k]);
      if (size > 1) return StepBatch(batch, size);
    }
    Component& comp = *components_[e.c];
    // The component keeps stepping while it stays within a window ahead of
    // the one furthest behind (the queue's top): runs of steps of one
    // component keep its state in cache, where a strict round-robin over
    // many components reloads each from memory for every step.  Results do
    // not depend on the order of steps (a step reads only its own last
    // sample and its inputs' finished waveforms; an observer's checks wait
    // for every body to pass a window, and an impact cuts back whatever ran
    // past it).  Under an observer only a calm component runs ahead (no cut
    // in its last kCalmSteps steps): one in contact would be cut back at the
    // next impact and its run thrown away.
    const double ahead = MayRun(e.c) ? kRunAhead * (sys_.t1 - sys_.t0) : 0.0;
    const double limit = (queue_.empty() ? sys_.t1 : queue_.top().t) + ahead;
    int run = 0;
    do {
      if (!comp.Step()) {
        error_ = comp.error();
        failed_variable_ = comp.failed_variable();
        failed_ = true;
        return false;
      }
      if (!Charge(e.c)) return false;
      ++calm_steps_[e.c];
      if (after_step) after_step(*this, e.c);
      if (failed_) return false;
    } while (ahead > 0.0 && ++run < kRunSteps && comp.t_end() < limit && Eligible(e.c));
    Push(e.c);
    for (int d : partition_.downstream[e.c]) Push(d);
    return true;
  }
  return false;
}

bool Simulation::MayRun(int c) const {
  return !after_step || calm_steps_[static_cast<size_t>(c)] >= kCalmSteps;
}

bool Simulation::Related(int c, const int* batch, int size) const {
  for (int k = 0; k < size; ++k) {
    const auto& up = partition_.upstream[static_cast<size_t>(c)];
    const auto& down = partition_.downstream[static_cast<size_t>(c)];
    if (std::binary_search(up.begin(), up.end(), batch[k]) ||
        std::binary_search(down.begin(), down.end(), batch[k]))
      return true;
  }
  return false;
}

Simulation::RunResult Simulation::RunSteps(int c, double ahead, double limit) {
  Component& comp = *components_[static_cast<size_t>(c)];
  RunResult r;
  do {
    if (!comp.Step()) {
      r.ok = false;
      return r;
    }
    ++r.steps;
  } while (ahead > 0.0 && r.steps < kRunSteps && comp.t_end() < limit && Eligible(c));
  return r;
}

bool Simulation::StepBatch(const int* batch, int size) {
  if (!crew_) {
    lane_values_.assign(static_cast<size_t>(lanes_) - 1, std::vector<double>(values_.size(), 0.0));
    crew_ = std::make_unique<Crew>(*this, lanes_);
  }
  ++batches_;
  // Each run's bound, as StepOnce gives it, from the component now furthest
  // behind.
  const double next = queue_.empty() ? sys_.t1 : queue_.top().t;
  auto ahead = [&](int c) { return MayRun(c) ? kRunAhead * (sys_.t1 - sys_.t0) : 0.0; };
  for (int k = 1; k < size; ++k) {
    components_[static_cast<size_t>(batch[k])]->set_lane(k);
    crew_->Post(k, batch[k], ahead(batch[k]), next + ahead(batch[k]));
  }
  RunResult results[expr::Tape::kLanes];
  std::exception_ptr thrown;
  try {
    results[0] = RunSteps(batch[0], ahead(batch[0]), next + ahead(batch[0]));
  } catch (...) {
    thrown = std::current_exception();
  }
  for (int k = 1; k < size; ++k) {
    Component& comp = *components_[static_cast<size_t>(batch[k])];
    if (crew_->TakeBack(k)) {
      comp.set_lane(0);
      if (thrown) continue;
      try {
        results[k] = RunSteps(batch[k], ahead(batch[k]), next + ahead(batch[k]));
      } catch (...) {
        thrown = std::current_exception();
      }
      continue;
    }
    Crew::Slot& slot = crew_->Wait(k);
    results[k] = slot.result;
    if (!thrown) thrown = slot.thrown;
    comp.set_lane(0);
  }
  if (thrown) std::rethrow_exception(thrown);
  bool thin = true;
  for (int k = 1; k < size; ++k) thin = thin && results[k].steps <= kThinRun;
  if (!thin) {
    thin_batches_ = 0;
    solo_turns_ = kSoloTurns;
  } else if (++thin_batches_ >= kThinBatches) {
    thin_batches_ = 0;
    solo_until_ = turns_ + solo_turns_;
    solo_turns_ = std::min(2 * solo_turns_, kSoloTurnsMax);
  }
  // The runs in batch order, as one thread would have taken them.
  for (int k = 0; k < size; ++k) {
    const int c = batch[k];
    Component& comp = *components_[static_cast<size_t>(c)];
    if (!results[k].ok) {
      error_ = comp.error();
      failed_variable_ = comp.failed_variable();
      failed_ = true;
      return false;
    }
    if (!Charge(c, results[k].steps)) return false;
    calm_steps_[static_cast<size_t>(c)] += results[k].steps;
    if (after_step) after_step(*this, c);
    if (failed_) return false;
  }
  for (int k = 0; k < size; ++k) {
    Push(batch[k]);
    for (int d : partition_.downstream[static_cast<size_t>(batch[k])]) Push(d);
  }
  return true;
}

void Simulation::StartRun() {
  run_steps_ = 0;
  impulses_.assign(sys_.bodies.size(), 0);
  last_impulse_t_.assign(sys_.bodies.size(), std::numeric_limits<double>::quiet_NaN());
  steps_at_run_start_.resize(components_.size());
  for (size_t c = 0; c < components_.size(); ++c)
    steps_at_run_start_[c] = components_[c]->counters().steps;
  if (before_run) before_run(*this);
}

double Simulation::WaveformBytes() const {
  double bytes = 0.0;
  for (const auto& c : components_) {
    const Waveform& w = c->waveform();
    // Per sample: the time, x, f and the bubble per variable, and its SampleInfo.
    bytes += static_cast<double>(w.size()) *
             (sizeof(double) * (1.0 + 3.0 * w.variable_count()) + sizeof(SampleInfo));
  }
  return bytes;
}

std::string Simulation::BodiesOf(int c) const {
  std::vector<int> bodies;
  for (int v : components_[c]->variables())
    if (const int b = sys_.variables[v].body; b >= 0) bodies.push_back(b);
  std::sort(bodies.begin(), bodies.end());
  bodies.erase(std::unique(bodies.begin(), bodies.end()), bodies.end());
  if (bodies.empty()) return "component " + std::to_string(c);
  std::string names = bodies.size() == 1 ? "body " : "bodies ";
  for (size_t k = 0; k < bodies.size(); ++k) {
    if (k == 5) {
      names += " and " + std::to_string(bodies.size() - k) + " more";
      break;
    }
    names += (k ? ", " : "") + sys_.bodies[bodies[k]].name;
  }
  return names;
}

bool Simulation::Charge(int c, long steps) {
  run_steps_ += steps;
  const bool out_of_steps = budget_.steps > 0 && run_steps_ > budget_.steps;
  // Memory every 1024 steps: when this charge passed a multiple of 1024.
  const bool check = budget_.memory_mb > 0 && (run_steps_ >> 10) != ((run_steps_ - steps) >> 10);
  const double bytes = check ? WaveformBytes() : 0.0;
  const bool out_of_memory = bytes > budget_.memory_mb * 1048576.0;
  if (!out_of_steps && !out_of_memory) return true;
  // Name the component that spent most of it: steps this run, or samples held.
  int busiest = c;
  double most = -1.0;
  for (size_t k = 0; k < components_.size(); ++k) {
    const Component& comp = *components_[k];
    const double spent =
        out_of_steps
            ? static_cast<double>(comp.counters().steps -
                                  (k < steps_at_run_start_.size() ? steps_at_run_start_[k] : 0))
            : static_cast<double>(comp.waveform().size()) * comp.waveform().variable_count();
    if (spent > most) most = spent, busiest = static_cast<int>(k);
  }
  std::ostringstream msg;
  if (out_of_steps)
    msg << "the run exceeded its budget of " << budget_.steps << " steps";
  else
    msg << "the run exceeded its memory budget (" << budget_.memory_mb << " MB of trajectories)";
  msg << " at t=" << time_reached() << " of [" << sys_.t0 << ", " << sys_.t1 << "]; "
      << BodiesOf(busiest) << (out_of_steps ? " took most of them" : " hold most of it")
      << ", reaching t=" << components_[busiest]->t_end();
  Fail(msg.str());
  if (!components_[busiest]->variables().empty())
    failed_variable_ = components_[busiest]->variables().front();
  return false;
}

bool Simulation::Run(const std::function<void(double)>& progress) {
  StartRun();
  if (options_.schedule == SolverOptions::Schedule::kSequential) {
    // Each component to the end, in dependency order (seed 5.2.4 variant 5).
    // A truncation of an earlier component restarts the sweep from it.
    for (size_t c = 0; c < components_.size(); ++c) {
      while (!components_[c]->finished()) {
        const long repairs = repairs_;
        if (!components_[c]->Step()) {
          error_ = components_[c]->error();
          failed_variable_ = components_[c]->failed_variable();
          return false;
        }
        if (!Charge(static_cast<int>(c))) return false;
        if (after_step) after_step(*this, static_cast<int>(c));
        if (failed_) return false;
        // Only a truncation (which repairs the queue) can make an earlier
        // component unfinished again.
        if (repairs_ == repairs) continue;
        for (size_t e = 0; e <= c; ++e) {
          if (!components_[e]->finished()) {
            c = e;
            break;
          }
        }
      }
      if (progress) progress(time_reached());
    }
    return true;
  }
  long report = 256;  // steps between progress reports (a StepOnce may take several)
  while (StepOnce()) {
    if (progress && run_steps_ >= report) {
      report = run_steps_ + 256;
      progress(time_reached());
    }
  }
  if (failed_) return false;
  if (progress) progress(time_reached());
  return true;
}

void Simulation::Truncate(int c, double t, bool strict) { TruncateAll({c}, t, strict); }

void Simulation::TruncateAll(const std::vector<int>& cs, double t, bool strict) {
  // Cut times propagate in dependency order (components are numbered in
  // it), so each component is cut once, to the earliest time required.
  TruncationScope scope(*this);
  const size_t n = components_.size();
  std::vector<double> cut(n, std::numeric_limits<double>::infinity());
  std::vector<char> source(n, 0);
  size_t first = n;
  for (int c : cs) {
    cut[c] = t;
    source[c] = 1;
    first = std::min(first, static_cast<size_t>(c));
  }
  std::vector<int> affected;
  for (size_t k = first; k < n; ++k) {
    if (cut[k] == std::numeric_limits<double>::infinity()) continue;
    const double kept = components_[k]->Truncate(cut[k], strict && source[k]);
    // Events after the requested time are void; earlier ones stand (a
    // component cut back further than t only recomputes up to them).
    components_[k]->ForgetAfter(t, strict);
    affected.push_back(static_cast<int>(k));
    calm_steps_[k] = 0;
    if (on_truncate) on_truncate(*this, static_cast<int>(k), kept);
    for (int d : partition_.downstream[k]) cut[d] = std::min(cut[d], kept);
  }
  RebuildBreakpoints(cs);
  RepairQueue(affected);
}

void Simulation::CopyResults(int c, const Component& from) {
  components_[c]->CopyResults(from);
  RebuildBreakpoints({c});
  RepairQueue({c});
}

void Simulation::ResetToStart(int c) {
  TruncationScope scope(*this);
  Truncate(c, sys_.t0);
  // Every component Truncate reached now holds only its first sample; rebuild
  // those in dependency order so readers see their inputs' new start.
  std::vector<char> reached(components_.size(), 0);
  reached[c] = 1;
  for (size_t k = static_cast<size_t>(c); k < components_.size(); ++k) {
    if (!reached[k]) continue;
    components_[k]->StartSample();
    for (int d : partition_.downstream[k]) reached[d] = 1;
  }
  std::vector<int> affected;
  for (size_t k = 0; k < components_.size(); ++k)
    if (reached[k]) affected.push_back(static_cast<int>(k));
  RepairQueue(affected);
}

void Simulation::RebuildBreakpoints(const std::vector<int>& cs) {
  // Dependency order: upstream components are final when a reader is rebuilt.
  std::vector<char> dirty(components_.size(), 0);
  size_t first = components_.size();
  for (int c : cs) {
    dirty[c] = 1;
    first = std::min(first, static_cast<size_t>(c));
  }
  for (size_t k = first; k < components_.size(); ++k) {
    if (!dirty[k]) continue;
    std::vector<double> inherited;
    for (int u : partition_.upstream[k]) components_[u]->BreakpointsInto(inherited);
    components_[k]->SetDynamicBreakpoints(inherited);
    for (int d : partition_.downstream[k]) dirty[d] = 1;
  }
}

void Simulation::ApplyAt(double t, const std::vector<Edit>& edits) {
  if (edits.empty()) return;
  TruncationScope scope(*this);
  std::vector<int> cs;
  cs.reserve(edits.size());
  for (const Edit& e : edits) cs.push_back(partition_.component_of[e.var]);
  std::sort(cs.begin(), cs.end());
  cs.erase(std::unique(cs.begin(), cs.end()), cs.end());
  TruncateAll(cs, t, /*strict=*/false);
  for (const Edit& e : edits) {
    Component& c = *components_[partition_.component_of[e.var]];
    const int local = local_index_[e.var];
    switch (e.kind) {
      case Edit::Kind::kSet:
        c.AddJump(t, local, e.value);
        break;
      case Edit::Kind::kHold:
        c.AddHold(t, local, e.value);
        break;
      case Edit::Kind::kRelease:
        c.ReleaseHold(t, local);
        break;
    }
  }
  RebuildBreakpoints(cs);
  RepairQueue(cs);
  for (const Edit& e : edits)
    if (e.kind == Edit::Kind::kSet) ChargeImpulse(e.var, t);
}

void Simulation::SetValueAt(int var, double t, double value) {
  ApplyAt(t, {{Edit::Kind::kSet, var, value}});
}

long Simulation::impulses_this_run(int body) const {
  return body >= 0 && static_cast<size_t>(body) < impulses_.size() ? impulses_[body] : 0;
}

void Simulation::ChargeImpulse(int var, double t) {
  const int b = sys_.variables[var].body;
  if (b < 0 || budget_.impulses_per_body <= 0 || failed_) return;
  if (impulses_.size() != sys_.bodies.size()) {  // a jump outside Run
    impulses_.assign(sys_.bodies.size(), 0);
    last_impulse_t_.assign(sys_.bodies.size(), std::numeric_limits<double>::quiet_NaN());
  }
  if (last_impulse_t_[b] == t) return;  // another variable of the same impulse
  last_impulse_t_[b] = t;
  if (++impulses_[b] <= budget_.impulses_per_body) return;
  std::ostringstream msg;
  msg << "the run exceeded its budget of " << budget_.impulses_per_body << " impulses on body "
      << sys_.bodies[b].name << " at t=" << t << " of [" << sys_.t0 << ", " << sys_.t1 << "]";
  Fail(msg.str());
  failed_variable_ = var;
}

void Simulation::HoldAt(int var, double t, double value) {
  ApplyAt(t, {{Edit::Kind::kHold, var, value}});
}

void Simulation::ReleaseAt(int var, double t) { ApplyAt(t, {{Edit::Kind::kRelease, var}}); }

bool Simulation::Held(int var, double t) const {
  return components_[partition_.component_of[var]]->Held(local_index_[var], t);
}

void Simulation::RepairQueue(const std::vector<int>& affected) {
  ++repairs_;
  for (int k : affected) {
    ++stamp_[k];
    queued_[k] = 0;
  }
  for (int k : affected) Push(k);
  // Components upstream of an affected one are unchanged; their readers that
  // were waiting may now be eligible again only through them, which Push on
  // the next step handles.
}

}  // namespace asgard::solver
