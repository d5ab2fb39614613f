// 8-bit RGB images and their files (PNG through libpng, binary PPM).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace asgard::render {

struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // row-major from the top, 3 bytes per pixel

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(static_cast<size_t>(w) * h * 3, 0) {}
  uint8_t* Pixel(int x, int y) { return &rgb[(static_cast<size_t>(y) * width + x) * 3]; }
  const uint8_t* Pixel(int x, int y) const {
    return &rgb[(static_cast<size_t>(y) * width + x) * 3];
  }
};

// Each returns false (and leaves `error` set) on failure.
bool WritePng(const Image& image, const std::string& path, std::string* error = nullptr);
bool WritePpm(const Image& image, const std::string& path, std::string* error = nullptr);
// Reads 8-bit PNG (grey, RGB, with or without alpha; alpha is composited on white).
std::optional<Image> ReadPng(const std::string& path, std::string* error = nullptr);

// Box-filter reduction by an integer factor (supersampling antialiasing);
// `src` is RGBA, `bottom_up` when row 0 is the bottom (OpenGL order).
Image DownsampleRgba(const uint8_t* src, int width, int height, int factor, bool bottom_up);

// Comparison for golden tests: mean absolute channel difference (0..255) and
// the fraction of pixels whose largest channel difference exceeds `threshold`.
struct ImageDifference {
  double mean = 0.0;
  double fraction_over = 0.0;
  bool same_size = false;
};
ImageDifference Compare(const Image& a, const Image& b, int threshold = 48);

}  // namespace asgard::render
