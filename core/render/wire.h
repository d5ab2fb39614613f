// Line drawings with Cairo (the seed's PostScript output, seed 3.3.4/4.1.10):
// hull edges and sphere outlines in perspective, with optional overlays —
// handles at body centres, link springs, force vectors, body paths — to PNG,
// PPM (through an Image), SVG, PDF and PostScript.
#pragma once

#include <cairo.h>

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "core/render/image.h"
#include "core/render/sampler.h"
#include "core/render/view.h"

namespace asgard::render {

struct Overlays {
  bool handles = false;  // small discs at body centres of mass
  bool links = false;    // link springs as zigzags between their end points
  bool forces = false;   // force vectors as arrows (scaled, see force_length)
  bool paths = false;    // centre-of-mass paths over the whole animation
  bool any() const { return handles || links || forces || paths; }
};

struct WireStyle {
  Rgb background{1, 1, 1};
  double line_width = 0.0;    // pixels; 0: max(1, width / 480)
  double force_length = 0.0;  // world length of the largest force; 0: radius / 5
};

// Everything a picture at one time needs.
struct FrameInput {
  const SceneSampler* sampler = nullptr;
  double t = 0.0;
  std::vector<Pose> poses;
  Camera camera;
  double view_radius = 1.0;  // world radius of the framing sphere (for overlay sizes)
  const std::vector<std::vector<Eigen::Vector3d>>* paths = nullptr;  // when overlays.paths
};

// Draws the background and the bodies' lines, then the overlays.
void DrawWire(cairo_t* cr, const FrameInput& frame, const Overlays& overlays,
              const WireStyle& style = {});
// Draws only the overlays (over a shaded frame, for instance).
void DrawOverlays(cairo_t* cr, const FrameInput& frame, const Overlays& overlays,
                  const WireStyle& style = {});

Image RenderWire(const FrameInput& frame, const Overlays& overlays, const WireStyle& style = {});
// Draws overlays on top of an existing raster.
void OverlayImage(Image& image, const FrameInput& frame, const Overlays& overlays,
                  const WireStyle& style = {});

// A vector document: one page per frame for PDF and PostScript; SVG holds
// one picture (one file per frame).
class VectorDocument {
 public:
  enum class Format { kSvg, kPdf, kPs };
  VectorDocument(const std::string& path, Format format, int width, int height);
  ~VectorDocument();
  bool ok() const;  // the surface was created
  std::string error() const;
  void AddPage(const FrameInput& frame, const Overlays& overlays, const WireStyle& style = {});
  bool Finish();  // flushes and closes; false on a write error

 private:
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cr_ = nullptr;
  int pages_ = 0;
  std::string error_;
};

}  // namespace asgard::render
