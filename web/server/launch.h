// Starting the editor server on a document or a bare scene:
//   dochost serve DOC.ens [--port P] [--open]   → ServeDocument
//   asgard studio SCENE.al [--port P] [--open]  → ServeScene (a one-animation document)
// Both print the URL on standard output when the server listens.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "web/server/server.h"

namespace asgard::serve {

struct LaunchOptions {
  int port = 0;          // 0: any free port
  bool open = false;     // open the page with xdg-open
  std::string core;      // asgard-core; empty: next to the executables
  std::string web_root;  // the bundle; empty: $ASGARD_WEB_ROOT or the build tree
};

// Parses [--port P] [--open] [--core PATH] after the file; false with a
// message on bad usage.
bool ParseLaunchArgs(const std::vector<std::string>& args, std::string* file, LaunchOptions* o,
                     std::string* error);

// The host's part of `dochost serve` (host-shim/serve_host.h): given an
// <ASGARD> element's place in the document (child indices from the
// document's top nodes), gives its animation the host's slave channel and
// rendition; an animation left without a channel gets an asgard-core of the
// server's own.
using AttachHost =
    std::function<void(const std::vector<size_t>& element_path, Animation& animation)>;

// The host's own layout of the document (dochost serve), when it has one:
// each page's size, its lines of text (to select, copy, find and read aloud) and where each
// <ASGARD> element's region lies on it, in the page's CSS pixels; and the
// page's picture as the host draws its PDF pages (a PNG, the animations'
// regions with their posters and captions), drawn when the browser first
// asks for it.  The document view then shows these pages with a live
// rendition over each animation's region; without them it shows the
// document's text as paragraphs.
struct PageRegion {
  std::vector<size_t> element_path;  // as AttachHost's
  double x = 0, y = 0, w = 0, h = 0;
};
// A line of the page's text where the host set it (CSS pixels): the
// document view lays it, transparent, over the page's picture, stretched
// to the line's width, so that it can be selected, copied and found.
struct PageLine {
  double x = 0, y = 0, w = 0, h = 0;
  double font_px = 0;
  std::string family;
  bool bold = false;
  std::string text;
};
struct HostPage {
  double width = 0, height = 0;  // CSS pixels
  std::vector<PageLine> lines;
  std::vector<PageRegion> regions;
};
struct HostPages {
  std::vector<HostPage> pages;
  // Page k's PNG (empty when it cannot be drawn); called from the server's
  // threads, so it must be safe to call from any of them.
  std::function<std::string(size_t k)> picture;
};

int ServeDocument(const std::string& path, const LaunchOptions& o, const AttachHost& attach = {},
                  const HostPages& pages = {});
int ServeScene(const std::string& path, const LaunchOptions& o);

// The folder of the browser bundle (index.html, editor.js, player.js):
// `given` when not empty, else $ASGARD_WEB_ROOT, else ../web or ../../web
// from the executable.
std::string WebRoot(const std::string& given = "");

// The usage text of both commands.
extern const char* const kServeUsage;

}  // namespace asgard::serve
