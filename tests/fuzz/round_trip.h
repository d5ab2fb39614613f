// The document readers' fuzz check, shared by fuzz_sgml and fuzz_xml: any
// bytes parse or fail with a location (line, column and a message); what
// parses writes back to bytes that parse again and write back the same.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "formats/document/document.h"

namespace asgard::fuzz {

template <typename Parse, typename Write>
int CheckRoundTrip(const uint8_t* data, size_t size, Parse parse, Write write) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  document::ParseResult r = parse(bytes);
  if (!r.ok()) {
    if (r.error.line < 1 || r.error.column < 1 || r.error.message.empty()) __builtin_trap();
    return 0;
  }
  const std::string once = write(*r.document);
  document::ParseResult again = parse(once);
  if (!again.ok() || write(*again.document) != once) __builtin_trap();
  return 0;
}

}  // namespace asgard::fuzz
