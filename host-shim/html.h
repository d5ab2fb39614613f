// The self-contained HTML output device.
//
// One file, no external resources: the document's blocks as HTML, and per
// embedded animation a <figure class="asgard-animation"> with a canvas, a
// play/pause button, a seek slider and a time readout.  Frames are PNGs in
// base64 data URIs inside a JSON block; the poster frame is drawn before
// anything plays.  A small script plays them in real time (requestAnimationFrame,
// looping), so the page animates in any browser without a server.
#pragma once

#include <string>
#include <vector>

#include "host-shim/layout.h"

namespace asgard::host {

struct HtmlAnimation {
  int width = 360, height = 240;    // CSS pixels
  std::vector<std::string> frames;  // PNG bytes
  std::vector<double> times;        // one per frame
  int poster = 0;                   // index of the poster frame
  std::string caption;
  bool live = false;  // false: only a poster (no controls)
  std::string scene;  // the medium text, for the viewer page
};

std::string WriteHtml(const std::string& title, const std::vector<Block>& blocks,
                      const std::vector<HtmlAnimation>& animations, bool show_scene = false);

}  // namespace asgard::host
