// The SGML-like reader: any bytes parse or fail with a location; what
// parses writes back to bytes that parse to the same bytes again.
#include <cstdint>
#include <string_view>

#include "formats/document/document.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace asgard::document;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  ParseResult r = Parse(bytes);
  if (!r.ok()) {
    if (r.error.line < 1 || r.error.column < 1 || r.error.message.empty()) __builtin_trap();
    return 0;
  }
  const std::string once = Write(*r.document);
  ParseResult again = Parse(once);
  if (!again.ok() || Write(*again.document) != once) __builtin_trap();
  return 0;
}
