// The SGML-like reader: any bytes parse or fail with a location; what
// parses writes back to bytes that parse to the same bytes again.
#include "formats/document/document.h"
#include "tests/fuzz/round_trip.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace asgard::document;
  return asgard::fuzz::CheckRoundTrip(
      data, size, [](std::string_view s) { return Parse(s); },
      [](const Document& d) { return Write(d); });
}
