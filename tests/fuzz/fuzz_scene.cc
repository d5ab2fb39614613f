// The scene language through `check`: evaluation in the safe interpreter
// (with tight limits, so one input takes milliseconds) and the equations.
// Every diagnostic must carry a line and a column.
#include <cstdint>
#include <string_view>

#include "core/lang/lang.h"
#include "core/pipeline/pipeline.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace asgard;
  if (size > 4096) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  lang::EvalLimits limits;
  limits.command_limit = 20000;
  limits.time_limit_ms = 200;
  limits.memory_limit_mb = 64;
  scene::Scene scene = lang::Evaluate(text, limits);
  for (const auto& d : scene.diagnostics)
    if (d.message.empty() || !d.span.known()) __builtin_trap();
  pipeline::Run run = pipeline::Check(std::move(scene));
  (void)run;
  return 0;
}
