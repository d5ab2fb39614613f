// Colour names → RGB.
//
// Design: a small sorted table of the X11/CSS names a scene is likely to use
// (the dissertation's scenes use "black"; users write "red", "gray", ...),
// searched after normalising case and removing spaces, plus the "#rgb" /
// "#rrggbb" web forms and three-number lists.  Unknown names are reported by
// the caller (the renderer falls back to the palette), never guessed.
#include "core/render/color.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdlib>
#include <sstream>
#include <string>
#include <utility>

namespace asgard::render {

namespace {

struct Named {
  const char* name;
  unsigned rgb;
};

// Sorted by name (binary search; checked at compile time below).
constexpr Named kNames[] = {
    {"aqua", 0x00ffff},        {"beige", 0xf5f5dc},       {"black", 0x000000},
    {"blue", 0x0000ff},        {"brown", 0xa52a2a},       {"chocolate", 0xd2691e},
    {"coral", 0xff7f50},       {"crimson", 0xdc143c},     {"cyan", 0x00ffff},
    {"darkblue", 0x00008b},    {"darkgray", 0xa9a9a9},    {"darkgreen", 0x006400},
    {"darkgrey", 0xa9a9a9},    {"darkorange", 0xff8c00},  {"darkred", 0x8b0000},
    {"darkviolet", 0x9400d3},  {"deepskyblue", 0x00bfff}, {"firebrick", 0xb22222},
    {"forestgreen", 0x228b22}, {"gold", 0xffd700},        {"goldenrod", 0xdaa520},
    {"gray", 0x808080},        {"green", 0x008000},       {"grey", 0x808080},
    {"hotpink", 0xff69b4},     {"indigo", 0x4b0082},      {"ivory", 0xfffff0},
    {"khaki", 0xf0e68c},       {"lavender", 0xe6e6fa},    {"lightblue", 0xadd8e6},
    {"lightgray", 0xd3d3d3},   {"lightgreen", 0x90ee90},  {"lightgrey", 0xd3d3d3},
    {"lightyellow", 0xffffe0}, {"lime", 0x00ff00},        {"magenta", 0xff00ff},
    {"maroon", 0x800000},      {"navy", 0x000080},        {"olive", 0x808000},
    {"orange", 0xffa500},      {"orchid", 0xda70d6},      {"peru", 0xcd853f},
    {"pink", 0xffc0cb},        {"plum", 0xdda0dd},        {"purple", 0x800080},
    {"red", 0xff0000},         {"royalblue", 0x4169e1},   {"salmon", 0xfa8072},
    {"seagreen", 0x2e8b57},    {"sienna", 0xa0522d},      {"silver", 0xc0c0c0},
    {"skyblue", 0x87ceeb},     {"slategray", 0x708090},   {"slategrey", 0x708090},
    {"steelblue", 0x4682b4},   {"tan", 0xd2b48c},         {"teal", 0x008080},
    {"tomato", 0xff6347},      {"turquoise", 0x40e0d0},   {"violet", 0xee82ee},
    {"wheat", 0xf5deb3},       {"white", 0xffffff},       {"yellow", 0xffff00},
};

constexpr bool Sorted() {
  for (size_t i = 1; i < std::size(kNames); ++i)
    if (!(std::string_view(kNames[i - 1].name) < std::string_view(kNames[i].name))) return false;
  return true;
}
static_assert(Sorted(), "kNames must be sorted");

Rgb FromHex(unsigned v) {
  return {((v >> 16) & 0xff) / 255.0, ((v >> 8) & 0xff) / 255.0, (v & 0xff) / 255.0};
}

std::optional<Rgb> ParseHex(const std::string& s) {
  if (s.size() != 4 && s.size() != 7) return std::nullopt;
  for (size_t i = 1; i < s.size(); ++i)
    if (!std::isxdigit(static_cast<unsigned char>(s[i]))) return std::nullopt;
  unsigned v = static_cast<unsigned>(std::strtoul(s.c_str() + 1, nullptr, 16));
  if (s.size() == 4)  // #rgb → #rrggbb
    v = ((v >> 8 & 0xf) * 0x110000) | ((v >> 4 & 0xf) * 0x1100) | ((v & 0xf) * 0x11);
  return FromHex(v);
}

std::optional<Rgb> ParseTriple(std::string_view text) {
  std::istringstream in{std::string(text)};
  std::array<double, 3> c{};
  for (double& x : c)
    if (!(in >> x) || x < 0) return std::nullopt;
  std::string rest;
  if (in >> rest) return std::nullopt;
  const bool bytes = std::any_of(c.begin(), c.end(), [](double x) { return x > 1.0; });
  const double k = bytes ? 1.0 / 255.0 : 1.0;
  return Rgb{std::min(1.0, c[0] * k), std::min(1.0, c[1] * k), std::min(1.0, c[2] * k)};
}

}  // namespace

std::optional<Rgb> ParseColor(std::string_view text) {
  std::string key;
  for (char ch : text)
    if (!std::isspace(static_cast<unsigned char>(ch)) && ch != '_')
      key += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (key.empty()) return std::nullopt;
  if (key[0] == '#') return ParseHex(key);
  if (std::isdigit(static_cast<unsigned char>(key[0])) || key[0] == '.') return ParseTriple(text);
  const auto* end = std::end(kNames);
  const auto* it = std::lower_bound(
      std::begin(kNames), end, key,
      [](const Named& n, const std::string& k) { return std::string_view(n.name) < k; });
  if (it == end || key != it->name) return std::nullopt;
  return FromHex(it->rgb);
}

Rgb PaletteColor(int index) {
  // Muted, distinguishable on white and under shading.
  static constexpr unsigned kPalette[] = {0x4e79a7, 0xf28e2b, 0xe15759, 0x76b7b2,
                                          0x59a14f, 0xedc948, 0xb07aa1, 0xff9da7};
  const int n = static_cast<int>(std::size(kPalette));
  return FromHex(kPalette[((index % n) + n) % n]);
}

Rgb SurfaceColor(Rgb c) {
  if (c.Luminance() >= 0.1) return c;
  return {c.r * 0.8 + 0.14, c.g * 0.8 + 0.14, c.b * 0.8 + 0.15};
}

}  // namespace asgard::render
