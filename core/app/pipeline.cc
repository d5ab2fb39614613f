// The simulate pipeline (see pipeline.h).
#include "core/app/pipeline.h"

#include <chrono>
#include <cmath>

#include "core/lang/lang.h"

namespace asgard::app {

namespace {
void Prepare(Run& run, std::string_view text, const RunOptions& options, bool simulate) {
  run.scene = lang::Evaluate(text);
  run.diagnostics = run.scene.diagnostics;
  scene::Scene scene = run.scene;
  if (options.until) {
    if (!scene.simulator) scene.simulator.emplace();
    scene.simulator->finish = *options.until;
  }
  run.equations = std::make_unique<physics::EquationSystem>(physics::FormEquations(scene));
  for (const auto& d : run.equations->diagnostics) run.diagnostics.push_back(d);
  bool errors = false;
  for (const auto& d : run.diagnostics) errors |= d.severity == scene::Severity::kError;
  if (options.allow_scene_errors && simulate) errors = false;
  if (errors || !simulate) {
    run.ok = !errors;
    return;
  }
  solver::SolverOptions so = options.solver;
  if (options.use_scene_tolerances && scene.simulator) {
    const auto& s = *scene.simulator;
    if (s.rtol) so.rtol = *s.rtol;
    if (s.atol) so.atol = *s.atol;
    if (s.step) so.initial_step = *s.step;
    if (s.max_step) so.max_step = *s.max_step;
  }
  const auto start = std::chrono::steady_clock::now();
  run.simulation = std::make_unique<solver::Simulation>(*run.equations, so);
  const bool collide = options.collisions.value_or(!scene.simulator || scene.simulator->collisions);
  if (collide && run.equations->bodies.size() >= 2)
    run.collisions = std::make_unique<solver::CollisionMonitor>(*run.simulation);
  if (options.prepare_only) {
    run.ok = true;
    return;
  }
  const bool ok = run.simulation->Run(options.progress);
  if (run.collisions)
    for (const auto& w : run.collisions->warnings()) run.diagnostics.push_back(w);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!ok) run.solver_error = run.simulation->error();
  run.ok = ok;
}
}  // namespace

Run Simulate(std::string_view text, const RunOptions& options) {
  Run run;
  Prepare(run, text, options, true);
  return run;
}

Run Check(std::string_view text) {
  Run run;
  Prepare(run, text, {}, false);
  return run;
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

Frames SampleFrames(const physics::EquationSystem& eq, const solver::Simulation& sim,
                    double rate) {
  Frames frames;
  for (const auto& b : eq.bodies) frames.bodies.push_back(b.name);
  const double span = eq.t1 - eq.t0;
  const long count = std::max(1L, std::lround(std::floor(span * rate + 1e-9))) + 1;
  for (long k = 0; k < count; ++k) {
    const double t = k + 1 == count ? eq.t1 : eq.t0 + static_cast<double>(k) / rate;
    frames.times.push_back(std::min(t, eq.t1));
    std::vector<BodyFrame> row;
    for (size_t b = 0; b < eq.bodies.size(); ++b)
      row.push_back(SampleBody(eq, sim, static_cast<int>(b), frames.times.back()));
    frames.states.push_back(std::move(row));
  }
  return frames;
}

}  // namespace asgard::app
