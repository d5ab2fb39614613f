// The XML reader (libxml2, no XML_PARSE_HUGE): any bytes parse or fail with
// a location; what parses writes back (as XML) to bytes that parse again.
#include "formats/document/xml.h"
#include "tests/fuzz/round_trip.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace asgard::document;
  return asgard::fuzz::CheckRoundTrip(
      data, size, [](std::string_view s) { return ParseXml(s); },
      [](const Document& d) { return WriteXml(d); });
}
