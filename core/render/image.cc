// Image files and supersample reduction.
//
// Design: PNG is written and read with libpng directly (no cairo dependency
// for the shaded path); rows are 8-bit RGB, no gamma or text chunks, so the
// same image always gives the same bytes.  Downsampling sums integer channel
// values and rounds, so it is exact and deterministic.
#include "core/render/image.h"

#include <png.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

namespace asgard::render {

namespace {

struct FileCloser {
  void operator()(FILE* f) const {
    if (f) std::fclose(f);
  }
};
using File = std::unique_ptr<FILE, FileCloser>;

void SetError(std::string* error, const std::string& message) {
  if (error) *error = message;
}

}  // namespace

bool WritePng(const Image& image, const std::string& path, std::string* error) {
  File f(std::fopen(path.c_str(), "wb"));
  if (!f) {
    SetError(error, "cannot write '" + path + "'");
    return false;
  }
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_write_struct(&png, &info);
    SetError(error, "libpng: out of memory");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    SetError(error, "libpng failed writing '" + path + "'");
    return false;
  }
  png_init_io(png, f.get());
  png_set_IHDR(png, info, image.width, image.height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y)
    png_write_row(png, const_cast<png_bytep>(image.Pixel(0, y)));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fflush(f.get()) != 0) {
    SetError(error, "cannot write '" + path + "'");
    return false;
  }
  return true;
}

bool WritePpm(const Image& image, const std::string& path, std::string* error) {
  File f(std::fopen(path.c_str(), "wb"));
  if (!f) {
    SetError(error, "cannot write '" + path + "'");
    return false;
  }
  std::fprintf(f.get(), "P6\n%d %d\n255\n", image.width, image.height);
  const bool ok = std::fwrite(image.rgb.data(), 1, image.rgb.size(), f.get()) == image.rgb.size() &&
                  std::fflush(f.get()) == 0;
  if (!ok) SetError(error, "cannot write '" + path + "'");
  return ok;
}

std::optional<Image> ReadPng(const std::string& path, std::string* error) {
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, path.c_str())) {
    SetError(error, "cannot read PNG '" + path + "': " + img.message);
    return std::nullopt;
  }
  img.format = PNG_FORMAT_RGB;
  Image out(static_cast<int>(img.width), static_cast<int>(img.height));
  png_color white{255, 255, 255};
  if (!png_image_finish_read(&img, &white, out.rgb.data(), 0, nullptr)) {
    SetError(error, "cannot read PNG '" + path + "': " + img.message);
    png_image_free(&img);
    return std::nullopt;
  }
  return out;
}

Image DownsampleRgba(const uint8_t* src, int width, int height, int factor, bool bottom_up) {
  const int w = width / factor, h = height / factor;
  Image out(w, h);
  const int n = factor * factor;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      int sum[3] = {0, 0, 0};
      for (int dy = 0; dy < factor; ++dy) {
        const int sy = y * factor + dy;
        const int row = bottom_up ? height - 1 - sy : sy;
        const uint8_t* p = src + (static_cast<size_t>(row) * width + x * factor) * 4;
        for (int dx = 0; dx < factor; ++dx, p += 4)
          for (int c = 0; c < 3; ++c) sum[c] += p[c];
      }
      uint8_t* o = out.Pixel(x, y);
      for (int c = 0; c < 3; ++c) o[c] = static_cast<uint8_t>((sum[c] + n / 2) / n);
    }
  }
  return out;
}

ImageDifference Compare(const Image& a, const Image& b, int threshold) {
  ImageDifference d;
  d.same_size = a.width == b.width && a.height == b.height;
  if (!d.same_size || a.rgb.empty()) return d;
  double total = 0;
  size_t over = 0;
  for (size_t i = 0; i < a.rgb.size(); i += 3) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int diff = std::abs(int(a.rgb[i + c]) - int(b.rgb[i + c]));
      total += diff;
      worst = std::max(worst, diff);
    }
    if (worst > threshold) ++over;
  }
  d.mean = total / static_cast<double>(a.rgb.size());
  d.fraction_over = static_cast<double>(over) / (a.rgb.size() / 3);
  return d;
}

}  // namespace asgard::render
