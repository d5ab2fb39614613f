// Simulates a scene for a solver test at the given tolerances and method,
// ignoring the scene's own tolerances; every diagnostic and a failed run are
// test failures.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "core/pipeline/pipeline.h"

namespace asgard::testing {

inline pipeline::Run SimulateChecked(
    const std::string& text, double rtol, double atol,
    solver::SolverOptions::Method method = solver::SolverOptions::Method::kAuto) {
  pipeline::RunOptions opts;
  opts.solver.rtol = rtol;
  opts.solver.atol = atol;
  opts.solver.method = method;
  opts.use_scene_tolerances = false;
  pipeline::Run run = pipeline::Simulate(text, opts);
  for (const auto& d : run.diagnostics) ADD_FAILURE() << d.span.line << ": " << d.message;
  EXPECT_TRUE(run.ok) << run.solver_error;
  return run;
}

}  // namespace asgard::testing
