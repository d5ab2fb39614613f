// Colours of bodies, lights and backgrounds.
//
// Scene scripts name colours the way the dissertation's scenes do ("black",
// "red") or in web form ("#ff8800", "#f80"); a list of three numbers is also
// accepted ({1 0.5 0} in 0..1, or {255 128 0} when any value exceeds 1).
#pragma once

#include <optional>
#include <string_view>

namespace asgard::render {

struct Rgb {
  double r = 0.0, g = 0.0, b = 0.0;  // linear 0..1 (no gamma handling)

  bool operator==(const Rgb&) const = default;
  double Luminance() const { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }
};

// Parses a colour name (case-insensitive, spaces and '_' ignored: "Light Gray"
// == "lightgray"), "#rgb", "#rrggbb", or three numbers.  Returns nullopt for
// anything else.
std::optional<Rgb> ParseColor(std::string_view text);

// The colour given to the body with index `index` when neither the body nor
// its shape names one: a fixed palette, so pictures are reproducible.
Rgb PaletteColor(int index);

// The colour a lit surface is given: near-black colours are lifted to a dark
// grey so that shading (shaded frames, ray tracers) still shows their form.
Rgb SurfaceColor(Rgb c);

}  // namespace asgard::render
