// Core benchmarks: run time and solver work for the seed's pendulum, a
// 100-body scene and a stiff critically damped link.
//
//   build/bench/core_bench                      all
//   build/bench/core_bench --benchmark_filter=Stiff
//
// Each reports, per simulation: steps, rejected steps, right-hand-side and
// Jacobian evaluations, factorizations, Newton iterations, components, and the
// maximum error where a closed form exists.
#include <benchmark/benchmark.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/pipeline/pipeline.h"
#include "core/session/session.h"
#include "tests/solver/reference_problems.h"

namespace {

using SceneRun = asgard::pipeline::Run;

std::string ReadSample(const std::string& name) {
  std::ifstream in(std::string(ASGARD_SOURCE_DIR) + "/samples/" + name);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void Report(benchmark::State& state, const SceneRun& run) {
  if (!run.ok) {
    state.SkipWithError(run.solver_error.empty() ? "scene errors" : run.solver_error.c_str());
    return;
  }
  const auto c = run.simulation->totals();
  state.counters["steps"] = static_cast<double>(c.steps);
  state.counters["rejected"] = static_cast<double>(c.rejected_steps);
  state.counters["rhs_evals"] = static_cast<double>(c.rhs_evaluations);
  state.counters["jac_evals"] = static_cast<double>(c.jacobian_evaluations);
  state.counters["factorizations"] = static_cast<double>(c.factorizations);
  state.counters["newton_iters"] = static_cast<double>(c.newton_iterations);
  state.counters["components"] = run.simulation->component_count();
  state.counters["variables"] = static_cast<double>(run.equations->variables.size());
}

void Simulate(benchmark::State& state, const std::string& text, asgard::pipeline::RunOptions opts) {
  SceneRun last;
  for (auto _ : state) {
    last = asgard::pipeline::Simulate(text, opts);
    benchmark::DoNotOptimize(last.ok);
  }
  Report(state, last);
}

void BM_Pendulum(benchmark::State& state) {
  asgard::pipeline::RunOptions opts;
  opts.solver.partition = state.range(0) != 0;
  state.SetLabel(opts.solver.partition ? "partitioned" : "one component");
  Simulate(state, ReadSample("pendulum.al"), opts);
}
BENCHMARK(BM_Pendulum)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

// N independent pendulums of different lengths (time constants vary by a
// factor of 2), each a ball whose point at distance L is pinned by a stiff
// link to its own pivot, under gravity.
std::string ManyPendulums(int n) {
  std::ostringstream s;
  s << asgard::testing::kBallShape;
  for (int i = 0; i < n; ++i) {
    const double len = 1.0 + 3.0 * i / std::max(1, n - 1);
    const double px = 3.0 * i;
    s << "body p" << i << " -shape ball -mass 1 -init_pos {" << px + len * 0.6 << " " << -len * 0.8
      << " 0}\n"
      << "link -body1 p" << i << " -offset1 {" << -len * 0.6 << " " << len * 0.8 << " 0} -x " << px
      << " -y 0 -z 0 -tightness 1e5\n"
      << "force -body p" << i << " -x 0 -y -9.81 -z 0 -gravitational 1\n";
  }
  s << "simulator -finish 5\n";
  return s.str();
}

void BM_HundredBodies(benchmark::State& state) {
  asgard::pipeline::RunOptions opts;
  opts.solver.partition = state.range(0) != 0;
  state.SetLabel(opts.solver.partition ? "partitioned" : "one component");
  Simulate(state, ManyPendulums(100), opts);
}
BENCHMARK(BM_HundredBodies)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

void BM_StiffLink(benchmark::State& state) {
  const double k = std::pow(10.0, static_cast<double>(state.range(0)));
  const double w = std::sqrt(k);
  const double finish = 10.0;
  asgard::pipeline::RunOptions opts;
  const std::string text = asgard::testing::DampedLink(k, 1.0, 1.0, finish);
  SceneRun last;
  for (auto _ : state) {
    last = asgard::pipeline::Simulate(text, opts);
    benchmark::DoNotOptimize(last.ok);
  }
  Report(state, last);
  if (last.ok) {
    double err = 0;
    const int var = last.equations->bodies[0].first_var;
    for (double s = 0; s <= 50; s += 0.01) {
      const double t = s / w;
      err = std::max(err, std::abs(last.simulation->Value(var, t) -
                                   asgard::testing::DampedLinkExact(k, 1.0, 1.0, t)));
    }
    state.counters["max_error"] = err;
    state.counters["omega0"] = w;
  }
}
BENCHMARK(BM_StiffLink)->DenseRange(2, 8, 2)->Unit(benchmark::kMillisecond);

// Editing latency (issue: multiple-representation editing).  "Update": a
// language view hands over the seed pendulum's text and waits until its
// motion is simulated.  "Drag": a graphical view moves the ball's initial
// velocity (a text patch) and waits for the incremental re-simulation.
void BM_UpdateToSimulated(benchmark::State& state) {
  const std::string text = ReadSample("pendulum.al");
  for (auto _ : state) {
    asgard::session::Session session(text);
    benchmark::DoNotOptimize(session.Simulate());
  }
}
BENCHMARK(BM_UpdateToSimulated)->Unit(benchmark::kMillisecond);

void BM_DragToResimulated(benchmark::State& state) {
  asgard::session::Session session(ReadSample("pendulum.al"));
  session.Simulate();
  double vx = -3.0;
  long reset = 0, steps = 0, runs = 0;
  for (auto _ : state) {
    vx -= 0.01;  // each drag moves the handle a little
    session.SetParameter("b3", "init_dpos", {vx, 0, 0});
    benchmark::DoNotOptimize(session.Simulate());
    reset += session.last_stats().components_reset;
    steps += session.last_stats().steps;
    ++runs;
  }
  state.counters["components_reset"] = static_cast<double>(reset) / std::max(1L, runs);
  state.counters["steps"] = static_cast<double>(steps) / std::max(1L, runs);
  state.counters["components"] = session.last_stats().components;
}
BENCHMARK(BM_DragToResimulated)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
