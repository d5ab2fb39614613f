// Shaded-frame throughput: frames per second for 640×480 frames (2×
// supersampled, the CLI default) of the seed's pendulum and of a scene of
// 1000 bodies (500 boxes, 500 spheres in a 10×10×10 grid, spinning and
// drifting).  Simulation is done once, outside the timed loop; each iteration
// samples the poses at a new time and renders a frame.
#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>

#include "core/render/sampler.h"
#include "core/render/shaded.h"

namespace {

using namespace asgard;

std::string ReadSample(const char* name) {
  std::ifstream in(std::string(ASGARD_SOURCE_DIR) + "/samples/" + name);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string ThousandBodies() {
  return R"(simulator -finish 2
shape_set box -desc {-box {0.6 0.4 0.3}}
shape_set ball -desc {-sub {-sphere 0.3}}
for {set i 0} {$i < 1000} {incr i} {
  set x [expr {$i % 10}]
  set y [expr {($i / 10) % 10}]
  set z [expr {$i / 100}]
  set s [expr {$i % 2 ? "ball" : "box"}]
  body b$i -shape $s -init_pos [list $x $y $z] -init_dpos {0.1 0.2 0} -init_drot {0.5 1 0.3}
}
)";
}

void RenderFrames(benchmark::State& state, const std::string& text) {
  pipeline::Run run = pipeline::Simulate(text);
  if (!run.ok) {
    state.SkipWithError("simulation failed");
    return;
  }
  render::SceneSampler sampler(run.scene, *run.equations, *run.simulation);
  const render::ViewState view = *sampler.SceneView();
  const render::Camera camera = render::MakeCamera(view, 640, 480);
  render::ShadedRenderer renderer(640, 480);
  if (!renderer.ok()) {
    state.SkipWithError(renderer.error().c_str());
    return;
  }
  const auto times = sampler.FrameTimes();
  size_t k = 0;
  for (auto _ : state) {
    const auto poses = sampler.Poses(times[k++ % times.size()]);
    auto image = renderer.Render(sampler, poses, camera, {});
    benchmark::DoNotOptimize(image.rgb.data());
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["bodies"] = static_cast<double>(sampler.bodies().size());
}

void BM_ShadedPendulum(benchmark::State& state) { RenderFrames(state, ReadSample("pendulum.al")); }
void BM_Shaded1000Bodies(benchmark::State& state) { RenderFrames(state, ThousandBodies()); }

BENCHMARK(BM_ShadedPendulum)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Shaded1000Bodies)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
