// The scene language through `check`: evaluation in the safe interpreter
// (with tight limits, so one input takes milliseconds) and the equations.
// Every diagnostic must carry a line and a column.
//
// The limits are the fuzzer's, not the product's: inputs that loop run into
// the time or command limit, and before they were lowered (200 ms, 20 000
// commands) those few inputs took about half of the fuzzer's time.  Both
// limits are still reached by mutated loops, so their paths stay exercised.
// Values are limited to 1 MB (the product: 16 MB; a command's arguments 4×,
// a result bound 16×): mutated scenes that build big strings reached the
// product's limits only after making megabytes, which was most of the rest
// of the time; the same checks refuse them now, at a smaller size.  The
// memory limit stays the product's order of magnitude.
#include <cstdint>
#include <string_view>

#include "core/lang/lang.h"
#include "core/pipeline/pipeline.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace asgard;
  if (size > 4096) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  lang::EvalLimits limits;
  limits.command_limit = 4000;
  limits.time_limit_ms = 40;
  limits.memory_limit_mb = 64;
  limits.value_bytes = size_t{1} << 20;
  scene::Scene scene = lang::Evaluate(text, limits);
  for (const auto& d : scene.diagnostics)
    if (d.message.empty() || !d.span.known()) __builtin_trap();
  pipeline::Run run = pipeline::Check(std::move(scene));
  (void)run;
  return 0;
}
