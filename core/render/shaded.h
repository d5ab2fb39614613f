// Shaded frames with OSMesa (off-screen Mesa, OpenGL 2.1 fixed function):
// lights, depth test, per-piece colour, supersampling antialiasing.  The same
// input gives the same pixels (software rasteriser, fixed tessellation,
// integer box-filter reduction).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/render/image.h"
#include "core/render/sampler.h"
#include "core/render/view.h"

namespace asgard::render {

struct ShadedStyle {
  Rgb background{0.93, 0.94, 0.96};
  int supersample = 2;     // 1..4: render at k× the size and box-filter down
  int sphere_slices = 32;  // sphere tessellation
  double ambient = 0.22;   // global ambient light
};

class ShadedRenderer {
 public:
  ShadedRenderer(int width, int height, const ShadedStyle& style = {});
  ~ShadedRenderer();
  ShadedRenderer(const ShadedRenderer&) = delete;
  ShadedRenderer& operator=(const ShadedRenderer&) = delete;

  // False (with error()) when OSMesa could not create a context.
  bool ok() const;
  const std::string& error() const { return error_; }

  // Renders the bodies of `sampler` at `poses` seen by `camera` (whose size
  // must equal the renderer's).  Lights: `lights`, or DefaultLight when empty;
  // at most 8 are used.
  Image Render(const SceneSampler& sampler, const std::vector<Pose>& poses, const Camera& camera,
               const std::vector<Light>& lights);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string error_;
};

}  // namespace asgard::render
