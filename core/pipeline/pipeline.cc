// The simulate pipeline (see pipeline.h).
#include "core/pipeline/pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>
#include <string_view>
#include <unordered_map>

#include "core/lang/lang.h"
#include "core/protocol/protocol.h"

namespace asgard::pipeline {
namespace {

// "name (line N)" of every body of the equations, for budget messages.
std::vector<std::string> BodyLabels(const scene::Scene& scene, const physics::EquationSystem& eq) {
  // By name through one map (the first body of a name, as Scene::FindBody):
  // a search per body was quadratic, 16M instructions for 1000 bodies.
  std::unordered_map<std::string_view, const scene::Body*> by_name;
  for (const scene::Body& b : scene.bodies) by_name.emplace(b.name, &b);
  std::vector<std::string> label;
  for (const auto& m : eq.bodies) {
    label.push_back(m.name);
    const auto it = by_name.find(m.name);
    if (it != by_name.end() && it->second->command.known())
      label.back() += " (line " + std::to_string(it->second->command.line) + ")";
  }
  return label;
}

// Enforces the budget's impacts per run around the monitor's own after_step
// hook: once a run has applied more impulses than that, it fails naming the
// time and the bodies (and their scene lines) of the latest impact.
void LimitImpacts(const scene::Scene& scene, solver::Simulation& sim,
                  const solver::CollisionMonitor& monitor) {
  auto at_start = std::make_shared<long>(0);
  sim.before_run = [at_start, &monitor](solver::Simulation&) {
    *at_start = monitor.counters().impacts;
  };
  sim.after_step = [inner = sim.after_step, at_start, &monitor,
                    label = BodyLabels(scene, sim.system())](solver::Simulation& s, int c) {
    if (inner) inner(s, c);
    const long limit = s.budget().impacts;
    if (monitor.counters().impacts - *at_start <= limit || monitor.impacts().empty()) return;
    const solver::Impact& last = monitor.impacts().back();
    std::ostringstream msg;
    msg << "the run exceeded its budget of " << limit << " impacts at t=" << s.time_reached()
        << " of [" << s.system().t0 << ", " << s.system().t1 << "]; the latest between bodies "
        << label[last.a] << " and " << label[last.b] << " at t=" << last.t;
    s.Fail(msg.str());
  };
}

// The latest impact of body b, "; the latest against NAME (line N) at t=T",
// or "" when it has none.
std::string LatestImpactOf(const Run& run, int b) {
  if (!run.collisions) return "";
  const auto& impacts = run.collisions->impacts();
  for (auto it = impacts.rbegin(); it != impacts.rend(); ++it) {
    if (it->a != b && it->b != b) continue;
    std::ostringstream s;
    s << "; the latest against "
      << BodyLabels(run.scene, *run.equations)[it->a == b ? it->b : it->a] << " at t=" << it->t;
    return s.str();
  }
  return "";
}

}  // namespace

Run Check(scene::Scene scene, const RunOptions& options) {
  Run run;
  run.scene = std::move(scene);
  run.diagnostics = run.scene.diagnostics;
  if (options.until) {
    scene::Scene until = run.scene;
    if (!until.simulator) until.simulator.emplace();
    until.simulator->finish = *options.until;
    run.equations = std::make_unique<physics::EquationSystem>(physics::FormEquations(until));
  } else {
    run.equations = std::make_unique<physics::EquationSystem>(physics::FormEquations(run.scene));
  }
  for (const auto& d : run.equations->diagnostics) run.diagnostics.push_back(d);
  run.ok = true;
  for (const auto& d : run.diagnostics) run.ok &= d.severity != scene::Severity::kError;
  return run;
}

Run Check(std::string_view text) { return Check(lang::Evaluate(text)); }

bool Solve(Run& run, const RunOptions& options) {
  if (!run.equations || (!run.ok && !options.allow_scene_errors)) return run.ok = false;
  solver::SolverOptions so = options.solver;
  const auto& simulator = run.scene.simulator;
  if (options.use_scene_tolerances && simulator) {
    if (simulator->rtol) so.rtol = *simulator->rtol;
    if (simulator->atol) so.atol = *simulator->atol;
    if (simulator->step) so.initial_step = *simulator->step;
    if (simulator->max_step) so.max_step = *simulator->max_step;
  }
  // Looser than this the error estimate no longer holds a jointed body to
  // its joint: at rtol 0.3 a double pendulum's arms flew apart within 1.2 s
  // and the run failed (a chain of eight at 1.7 s); at 0.1 and 0.2 they swing.
  constexpr double kLoosestRtol = 0.1;
  if (so.rtol > kLoosestRtol) {
    std::ostringstream msg;
    msg << "rtol " << so.rtol << " is looser than " << kLoosestRtol
        << ", the loosest that keeps jointed bodies together; using " << kLoosestRtol;
    scene::SourceSpan span;
    if (const scene::Word* w = simulator && options.use_scene_tolerances && simulator->rtol
                                   ? simulator->option("rtol")
                                   : nullptr)
      span = w->span;
    run.diagnostics.push_back({scene::Severity::kWarning, msg.str(), span});
    so.rtol = kLoosestRtol;
  }
  const auto start = std::chrono::steady_clock::now();
  const bool collide = options.collisions.value_or(!simulator || simulator->collisions);
  run.simulation = std::make_unique<solver::Simulation>(*run.equations, so);
  run.simulation->set_budget(options.budget);
  if (collide && run.equations->bodies.size() >= 2) {
    run.collisions = std::make_unique<solver::CollisionMonitor>(*run.simulation);
    if (options.budget.impacts > 0) LimitImpacts(run.scene, *run.simulation, *run.collisions);
  }
  if (options.prepare_only) return run.ok = true;
  const bool ok = run.simulation->Run(options.progress);
  if (run.collisions)
    for (const auto& w : run.collisions->warnings()) run.diagnostics.push_back(w);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!ok) run.solver_error = run.simulation->error();
  // A value that stopped being finite, a budget a body exhausted: name the
  // body's command line too (and, for its impulses, what it kept hitting).
  if (const int v = run.simulation->failed_variable(); !ok && v >= 0) {
    const int b = run.equations->variables[v].body;
    if (b >= 0 && run.simulation->impulses_this_run(b) > options.budget.impulses_per_body &&
        options.budget.impulses_per_body > 0)
      run.solver_error += LatestImpactOf(run, b);
    for (const auto& body : run.scene.bodies)
      if (b >= 0 && body.name == run.equations->bodies[b].name && body.command.known())
        run.solver_error = "line " + std::to_string(body.command.line) + ": body " + body.name +
                           ": " + run.solver_error;
  }
  return run.ok = ok;
}

Run Simulate(scene::Scene scene, const RunOptions& options) {
  Run run = Check(std::move(scene), options);
  Solve(run, options);
  return run;
}

Run Simulate(std::string_view text, const RunOptions& options) {
  return Simulate(lang::Evaluate(text), options);
}

double FrameRate(const scene::Scene& scene) {
  return scene.simulator ? scene.simulator->frame_rate : protocol::kDefaultFrameRate;
}

BodyFrame SampleBody(const physics::EquationSystem& eq, const solver::Simulation& sim, int b,
                     double t) {
  const physics::BodyModel& m = eq.bodies[b];
  BodyFrame f{};
  if (m.first_var < 0) {
    for (int a = 0; a < 3; ++a) f.p[a] = m.x0[a];
    f.q[0] = m.q0.w(), f.q[1] = m.q0.x(), f.q[2] = m.q0.y(), f.q[3] = m.q0.z();
    return f;
  }
  auto val = [&](int slot) { return sim.Value(m.first_var + slot, t); };
  for (int a = 0; a < 3; ++a) {
    f.p[a] = val(physics::kX + a);
    f.v[a] = val(physics::kDx + a);
  }
  Eigen::Quaterniond q(val(physics::kQw), val(physics::kQx), val(physics::kQy), val(physics::kQz));
  q.normalize();
  f.q[0] = q.w(), f.q[1] = q.x(), f.q[2] = q.y(), f.q[3] = q.z();
  const Eigen::Vector3d w_body(val(physics::kW1), val(physics::kW2), val(physics::kW3));
  const Eigen::Vector3d w = q.toRotationMatrix() * w_body;
  for (int a = 0; a < 3; ++a) f.w[a] = w[a];
  return f;
}

Frames SampleFrames(const physics::EquationSystem& eq, const solver::Simulation& sim, double rate) {
  Frames frames;
  for (const auto& b : eq.bodies) frames.bodies.push_back(b.name);
  frames.times = FrameTimes(eq.t0, eq.t1, rate);
  for (double t : frames.times) {
    std::vector<BodyFrame> row;
    for (size_t b = 0; b < eq.bodies.size(); ++b)
      row.push_back(SampleBody(eq, sim, static_cast<int>(b), t));
    frames.states.push_back(std::move(row));
  }
  return frames;
}

std::vector<double> FrameTimes(double t0, double t1, double rate) {
  const long count = std::max(1L, std::lround(std::floor((t1 - t0) * rate + 1e-9))) + 1;
  std::vector<double> times;
  for (long k = 0; k < count; ++k)
    times.push_back(k + 1 == count ? t1 : std::min(t1, t0 + static_cast<double>(k) / rate));
  return times;
}

}  // namespace asgard::pipeline
