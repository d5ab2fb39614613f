// The pipe protocol between the medium plugin (medium-plugin/) and its
// asgard-core slave (core/app/core_main.cc): the facts both ends must agree
// on, defined once.
//
//   plugin ── [u32 big-endian length][JSON-RPC 2.0 message] ──▶ asgard-core
//          ◀── progress notifications, then the answer, framed the same way
//
// This header is part of the contract, not of core's internals: it includes
// nothing of Asgard, so the plugin and the host (which may include only this
// and the C ABI in host-shim/include/asgard/) and every core module can use
// it.  It sits at the bottom of the dependency order.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace asgard::protocol {

// JSON-RPC 2.0 error codes of an answer: the standard ones, then Asgard's.
enum ErrorCode : int {
  kParseError = -32700,      // the message is not JSON
  kInvalidRequest = -32600,  // not a request object (or a length beyond kMaxMessage)
  kMethodNotFound = -32601,
  kInvalidParams = -32602,
  kInternalError = -32603,
  kSceneError = 1,    // no scene is loaded, it has errors, or it could not be simulated
  kNotSimulated = 2,  // a frame was asked for before a successful simulate
  kRenderError = 3,   // the shaded renderer could not be set up
};

// Longest message body either end accepts: far beyond any scene text or
// answer, and small enough that a corrupt length is caught, not allocated.
inline constexpr uint32_t kMaxMessage = 64u << 20;

// Largest rendition (and picture) side in pixels: one RGBA frame of
// 8192 × 8192 is 256 MiB, what the shared frame memory is sized for.
inline constexpr int kMaxRenditionSide = 8192;

// simulator -frames when a scene does not say: 30 frames per second, the rate
// of video; the plugin and the host assume it until a slave reports the
// scene's own rate.
inline constexpr double kDefaultFrameRate = 30.0;

// Deepest nesting of arrays and objects a message may have.  JSON parsers
// (nlohmann's included) recurse once per level, so a message of a few
// megabytes of '[' would otherwise exhaust the stack; no request or answer
// of the protocol is deeper than a handful of levels.
inline constexpr int kMaxJsonDepth = 64;

// Memory a slave may take (its data segment, asgard-core --memory) unless
// the host asks otherwise: the scene language's 512 MiB and the solver's
// work with OSMesa's buffers beside them, with room; a runaway slave then
// dies alone (and is restarted once) instead of starving the host.
inline constexpr int kDefaultSlaveMemoryMiB = 2048;

// The deepest nesting of '[' and '{' in a JSON text, outside strings (a
// linear scan, no recursion); stops counting once past `stop_at`.
inline int JsonNestingDepth(std::string_view text, int stop_at = kMaxJsonDepth) {
  int depth = 0, deepest = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > deepest) deepest = depth;
      if (deepest > stop_at) return deepest;
    } else if (c == ']' || c == '}') {
      if (depth > 0) --depth;
    }
  }
  return deepest;
}

// The 4-byte big-endian length that precedes every message.
inline std::array<unsigned char, 4> EncodeLength(uint32_t n) {
  return {static_cast<unsigned char>(n >> 24), static_cast<unsigned char>(n >> 16),
          static_cast<unsigned char>(n >> 8), static_cast<unsigned char>(n)};
}
inline uint32_t DecodeLength(const unsigned char head[4]) {
  return (uint32_t{head[0]} << 24) | (uint32_t{head[1]} << 16) | (uint32_t{head[2]} << 8) | head[3];
}

}  // namespace asgard::protocol
