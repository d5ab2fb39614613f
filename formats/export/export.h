// Exports for other programs (seed 3.3.4, 4.1.10): ray-tracer scene files
// (Rayshade, as the seed wrote; POV-Ray, a maintained ray tracer), glTF 2.0
// binary with the simulated motion as animation, movies through ffmpeg, and
// numbered frame-file names.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "core/render/image.h"
#include "core/render/sampler.h"
#include "core/render/view.h"

namespace asgard::formats {

// One still scene: the bodies at time t, seen by `camera` (which also gives
// the picture size), lit by `lights` (empty: the default light).
struct StillScene {
  const render::SceneSampler* sampler = nullptr;
  double t = 0.0;
  render::Camera camera;
  std::vector<render::Light> lights;
  render::Rgb background{0.93, 0.94, 0.96};
};

// Each writer returns false and sets `error` when the file cannot be written.
bool WriteRayshade(const std::string& path, const StillScene& scene, std::string* error);
bool WritePovray(const std::string& path, const StillScene& scene, std::string* error);

// glTF 2.0 binary: one mesh per body (a primitive per piece, a material per
// colour), one node per body, a camera node, and one animation whose
// translation and rotation channels sample every moving body at `times`
// (seconds from the first time; linear interpolation).  Lights are written
// with KHR_lights_punctual.
bool WriteGltf(const std::string& path, const StillScene& scene, const std::vector<double>& times,
               std::string* error);

// Writes frames to ffmpeg's standard input as raw RGB and lets it encode:
//   .mp4  H.264 (libx264, yuv420p, faststart)   .webm VP9 (libvpx-vp9)
//   .gif  one palette for the whole movie (palettegen/paletteuse)
// Odd sizes are padded to even ones for the yuv420p codecs.
class MovieWriter {
 public:
  MovieWriter() = default;
  ~MovieWriter();
  MovieWriter(const MovieWriter&) = delete;
  MovieWriter& operator=(const MovieWriter&) = delete;

  // Starts ffmpeg; false (with error()) when the extension is not a movie
  // format or ffmpeg cannot be started.
  bool Open(const std::string& path, int width, int height, double fps);
  bool AddFrame(const render::Image& frame);
  // Closes the pipe and waits for ffmpeg; false when it failed.
  bool Finish();
  const std::string& error() const { return error_; }

  static bool IsMovie(const std::string& path);

 private:
  int pid_ = -1;
  FILE* pipe_ = nullptr;
  int width_ = 0, height_ = 0;
  std::string error_;
  std::string path_;
  std::string log_path_;
};

// Frame file names: PATTERN may hold a printf-style %d / %0Nd; otherwise
// "_NNNN" (enough digits for `count`) is inserted before the extension.
std::string FramePath(const std::string& pattern, int index, int count);

}  // namespace asgard::formats
