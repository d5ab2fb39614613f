// The editor server (issue 13): HTTP and WebSocket on 127.0.0.1 for the
// browser editor of seed chapter 4 and the live document view of seed 6.2.4.
//
//   browser ──HTTP GET──▶ /            the document page (or the editor of a
//                          /edit?a=N    bare scene), the editor of animation N
//                          /editor.js   the bundle built from web/
//                          /download?a=N&id=K  an export the server made (a movie)
//                          /frame?a=N&t=T[&handles=1]  a rendition's picture (PNG), drawn
//                                       by the animation's slave (dochost serve)
//                          /page?n=K    the host's page K (PNG; dochost serve)
//   browser ══WebSocket══▶ /ws?a=N     JSON {id, method, params} → {id, result | error};
//                                       events {event: text | scene | state | error}
//                                       go to every view of animation N
//
// Each animation has one asgard-core slave (core/app/editor_rpc.h) and one
// worker thread that talks to it, so all views edit one session.  Safety:
// the listening socket is bound to 127.0.0.1, peers that are not loopback are
// closed at accept, WebSocket upgrades must come from our own origin and Host
// (no cross-site page and no DNS rebinding reaches the editor), requests and
// messages have size limits, and a message that is not JSON is answered with
// an error.  See docs/editor-server.md.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "web/server/slave_link.h"

namespace asgard::serve {

// A rendition's picture for the document view: PNG bytes, the status line
// for its caption, the simulated interval, and whether the picture is live
// (false: the last frame or the poster, the status says why).
struct RenditionFrame {
  std::string png;
  std::string status;
  double t0 = 0, t1 = 0;
  bool live = false;
};

struct Animation {
  std::string title;
  std::string text;  // the scene text when the server starts
  // Saves `text` as this animation's scene (atomically); false with `error`.
  std::function<bool(const std::string& text, std::string* error)> save;
  // The slave the editor talks to; null: the server starts an asgard-core
  // of its own.  Called only from the animation's worker thread.
  std::shared_ptr<SlaveChannel> channel;
  // The animation's rendition at time t (with position handles when asked),
  // drawn by the same slave as `channel`'s, on the same worker thread; null
  // when the animation has none (then GET /frame is 404).
  std::function<RenditionFrame(double t, bool handles)> rendition;
};

struct Options {
  std::string bind = "127.0.0.1";
  int port = 0;                // 0: any free port
  std::string web_root;        // index.html and editor.js (the bundle)
  std::string core_program;    // asgard-core
  std::string render_program;  // the asgard CLI (its `render` makes movies)
  std::string document_title;
  std::string document_html;  // the live document view's body; empty: "/" is the editor
  // GET /page?n=K: the host's page K (PNG), K < page_count (dochost serve).
  size_t page_count = 0;
  std::function<std::string(size_t k)> page_picture;
  size_t max_message = 1 << 20;  // WebSocket message limit in bytes
  std::function<void(int port)> on_listening;
};

// Serves until the process ends; returns an exit status when it cannot start.
int Serve(const Options& options, std::vector<Animation> animations);

// Whether a peer address may talk to the server (loopback only).
bool IsLoopbackPeer(const std::string& address);
// Whether a WebSocket upgrade with these Origin and Host headers (empty when
// absent) may proceed on `port`.
bool IsOwnOrigin(const std::string& origin, const std::string& host, int port);

// Text made safe inside HTML text and attribute values.
std::string HtmlEscape(const std::string& s);

}  // namespace asgard::serve
