// The self-contained HTML output device.
//
// One file, no external resources: the document's blocks as HTML, and per
// embedded animation a <figure class="asgard-animation"> with a canvas, a
// play/pause button, a seek slider and a time readout.  Frames are PNGs in
// base64 data URIs inside a JSON block; the poster frame is drawn before
// anything plays.  A small script plays them in real time (requestAnimationFrame,
// looping), so the page animates in any browser without a server.
//
// An animation that also has `player` data (PlayerJson: its meshes and the
// poses per frame, compact) is played in WebGL by the player script
// (web/src/player.js, bundled at build time and passed in whole), rotatable
// and at any time between frames; where WebGL is missing the frames play
// as before.
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
  bool live = false;   // false: only a poster (no controls)
  std::string scene;   // the medium text, for the viewer page
  std::string player;  // PlayerJson; empty: the frames only
};

// The medium's "player" reply (meshes, lights, poses at evenly spaced times,
// camera; core/app/editor_rpc.h) as the player's data: vertices and poses
// as little-endian float32 in base64, triangles as uint16 (uint32 when
// needed), and only the bodies that move have a track of poses; the others
// one pose.  Empty, with `error` set, when the reply is not such data.
std::string PlayerJson(const std::string& reply, std::string* error);

// `player_script`: the WebGL player (empty: no animation plays in WebGL).
std::string WriteHtml(const std::string& title, const std::vector<Block>& blocks,
                      const std::vector<HtmlAnimation>& animations, bool show_scene = false,
                      const std::string& player_script = "");

}  // namespace asgard::host
