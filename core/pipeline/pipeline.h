// The simulate pipeline shared by the executables, the session, the renderer,
// the tests and the benchmarks:
//
//   text ─lang::Evaluate─▶ Scene ─physics::FormEquations─▶ EquationSystem
//        ─solver::Simulation::Run─▶ waveforms ─SampleFrames─▶ Frames
//
// A request evaluates its text once: callers that already hold the evaluated
// scene (the session, a check before a simulation) pass the scene, not the
// text.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/physics/equations.h"
#include "core/scene/scene.h"
#include "core/solver/collisions.h"
#include "core/solver/simulation.h"

namespace asgard::pipeline {

// Everything a run produced.  `ok` is false when the scene had errors (see
// diagnostics) or the solver failed (see solver_error).
struct Run {
  scene::Scene scene;
  std::unique_ptr<physics::EquationSystem> equations;
  std::unique_ptr<solver::Simulation> simulation;
  std::unique_ptr<solver::CollisionMonitor> collisions;  // null when collisions are off
  std::vector<scene::Diagnostic> diagnostics;            // scene and equation problems
  std::string solver_error;
  double seconds = 0.0;  // solver wall time
  bool ok = false;
};

struct RunOptions {
  solver::SolverOptions solver;
  std::optional<double> until;       // overrides the simulator's -finish
  bool use_scene_tolerances = true;  // simulator -rtol/-atol/-step/-maxstep
  std::optional<bool> collisions;    // overrides simulator -collisions
  bool allow_scene_errors = false;   // simulate the valid part of a scene with errors
  bool prepare_only = false;         // build the simulation but do not run it
  solver::RunBudget budget;          // steps, impacts and memory one run may spend
  std::function<void(double)> progress;
};

// Evaluates, forms equations and (when there are no errors) simulates.
Run Simulate(std::string_view text, const RunOptions& options = {});
// The same for a scene already evaluated (its text is not evaluated again).
Run Simulate(scene::Scene scene, const RunOptions& options = {});
// Evaluates and forms equations only (no simulation): for `asgard check`.
Run Check(std::string_view text);
// Forms the equations of an evaluated scene (options.until applies); `ok`
// when neither the scene nor its equations have errors.
Run Check(scene::Scene scene, const RunOptions& options = {});
// Simulates a run that Check formed: nothing when it has errors (unless
// options.allow_scene_errors), else builds the simulation and runs it (unless
// options.prepare_only).  Returns run.ok.
bool Solve(Run& run, const RunOptions& options);

// The scene's frame rate: simulator -frames, or its default.
double FrameRate(const scene::Scene& scene);

// A body's state at one time, world frame.
struct BodyFrame {
  double p[3], q[4], v[3], w[3];
};
struct Frames {
  std::vector<std::string> bodies;
  std::vector<double> times;
  std::vector<std::vector<BodyFrame>> states;  // [frame][body]
};
// Frame times at `rate` per second from t0 to t1 inclusive, the last at t1.
std::vector<double> FrameTimes(double t0, double t1, double rate);
// Samples every body at FrameTimes(eq.t0, eq.t1, rate).
Frames SampleFrames(const physics::EquationSystem& eq, const solver::Simulation& sim, double rate);
BodyFrame SampleBody(const physics::EquationSystem& eq, const solver::Simulation& sim, int body,
                     double t);

}  // namespace asgard::pipeline
