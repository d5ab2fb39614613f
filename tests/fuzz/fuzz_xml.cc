// The XML reader: any bytes parse or fail with a location; what parses
// writes back (as XML) to bytes that parse again.
#include <cstdint>
#include <string_view>

#include "formats/document/xml.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace asgard::document;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  ParseResult r = ParseXml(bytes);
  if (!r.ok()) {
    if (r.error.line < 1 || r.error.column < 1 || r.error.message.empty()) __builtin_trap();
    return 0;
  }
  const std::string once = WriteXml(*r.document);
  ParseResult again = ParseXml(once);
  if (!again.ok() || WriteXml(*again.document) != once) __builtin_trap();
  return 0;
}
