// The host's document tree: a parsed document plus one Embedded item per
// subdocument of a plugin medium (seed 6.1: subdocuments, nodes, renditions).
//
//   Document ─ <DOCUMENT> ─ <ANIMATION> ─ <ASGARD>{scene}</ASGARD>   ← embedded item
//                                       └ <POSTER>{base64 PNG}</POSTER> ← its poster frame
//
// An embedded item is a leaf element inside a <DOCUMENT> subdocument (POSTER
// excepted).  Its medium comes from the registry by element name; without one
// the item is a placeholder with the reason.  The poster is the host's own
// generic mechanism for loosely coupled media: a PNG of the last frame kept
// in the document, so it stays viewable without the slave.  Nodes are started
// on demand; a failing node never stops the host — the item keeps a status
// line and its last picture, and the document tree is never changed except by
// SetText and SetPoster.
#pragma once

#include <cairo.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/protocol/protocol.h"
#include "formats/document/document.h"
#include "host-shim/medium.h"

namespace asgard::host {

// An RGBA picture, rows from the top.
struct Picture {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
  double time = 0.0;
  bool empty() const { return rgba.empty(); }
};
std::string EncodePng(const Picture& picture);
// A Cairo RGB24 image surface with the picture's pixels; the caller destroys it.
cairo_surface_t* PictureSurface(const Picture& picture);
// Pictures larger than this are refused before decoding (posters come from
// documents, and a small PNG can claim gigapixels).
inline constexpr uint32_t kMaxPictureSide = 8192;
inline constexpr uint64_t kMaxPicturePixels = uint64_t{4096} * 4096;
// nullopt (and `why`, when given) for anything but a PNG within the limits.
std::optional<Picture> DecodePng(const std::string& png, std::string* why = nullptr);

struct Embedded {
  int index = 0;             // 1-based, document order
  std::vector<size_t> path;  // child indices from Document::nodes to the element
  std::string element;       // tag name
  Medium* medium = nullptr;  // nullptr: placeholder
  std::string text;          // the medium text (storage-decoded)
  asgard_node* node = nullptr;
  asgard_node_status status{};    // after the last call
  std::string message;            // status line for captions
  int width = 360, height = 240;  // presentation's desired size, points
  bool simulated = false;
  bool restarted = false;      // the slave died and was restarted once
  std::string restart_reason;  // how it died then
  bool stopped = false;        // its slave was stopped to make room for another's
  long last_use = 0;           // when its node was last used (HostDocument's clock)
  double t0 = 0, t1 = 0, frame_rate = protocol::kDefaultFrameRate;
  Picture poster;  // from the document or the last frame drawn
  bool poster_from_document = false;
  std::map<int, asgard_rendition*> renditions;  // device → rendition
  std::map<int, std::pair<int, int>> rendition_sizes;
};

// Slaves running at once by default.  Each maps its shared frame memory (a
// largest rendition, 256 MiB) in the host too, so 500 animations must not
// mean 500 slaves at once.
inline constexpr int kDefaultMaxSlaves = 4;

struct HostOptions {
  std::string slave_path;      // empty: the medium's default
  double timeout_seconds = 0;  // 0: the medium's default
  double slave_memory_mb = 0;  // address space of each slave; 0: the medium's default
  // Starting a slave beyond this many stops the one used longest ago; its
  // item simulates again when it is drawn next.
  int max_slaves = kDefaultMaxSlaves;
  std::string name;  // for messages: the file name
  // Simulation progress: (item, fraction).
  std::function<void(const Embedded&, double)> progress;
};

class HostDocument {
 public:
  // Finds the embedded items and their media and decodes their texts; never
  // starts a node.  `warnings` receives one line per placeholder or storage
  // problem.
  HostDocument(document::Document doc, MediumRegistry& registry, HostOptions options,
               std::vector<std::string>* warnings = nullptr);
  ~HostDocument();  // destroys renditions and nodes (slaves are shut down)
  HostDocument(const HostDocument&) = delete;
  HostDocument& operator=(const HostDocument&) = delete;

  const document::Document& document() const { return doc_; }
  std::vector<Embedded>& items() { return items_; }
  const std::vector<Embedded>& items() const { return items_; }
  const Embedded* ItemAt(const std::vector<size_t>& path) const;

  // Starts the node (when needed) and simulates; a slave that dies while
  // loading its text or simulating is started again once.  False with
  // item.message set on any failure; the host goes on.
  bool Simulate(Embedded& item);
  // Slaves running now (at most HostOptions::max_slaves).
  int running_slaves() const;
  // New medium text: stored in the document (storage encode) and the node
  // updated (re-simulated).
  bool SetText(Embedded& item, const std::string& text);
  // Kills nothing itself: restarts a slave that crashed or hung, and simulates.
  bool Restart(Embedded& item);
  // A frame for (device, pixel size) at time t; falls back to the last frame
  // of that rendition, then to the poster.  `flags`: ASGARD_RENDITION_*.
  // Sets `live` when it came from the slave just now.
  Picture Frame(Embedded& item, int device, int width, int height, double t, uint32_t flags,
                bool* live = nullptr);
  // Stores `picture` as the item's poster, in the document too.
  void SetPoster(Embedded& item, const Picture& picture);
  // A text command to the node (e.g. "handles on").
  bool Command(Embedded& item, const std::string& line, std::string* reply);
  // A request in the medium's own protocol to the item's slave (ABI 1.1,
  // asgard_node_rpc_v1): `params` and `*result` are JSON texts.  The node is
  // started when it has none, and a slave that died or hung is started again
  // first (with the node's text, edits included): the next action restarts
  // it.  Returns the status; on failure item.message says why.  Calls for
  // different items may come from different threads when max_slaves covers
  // every item (no slave is then stopped to make room for another's).
  int32_t Call(Embedded& item, const std::string& method, const std::string& params,
               std::string* result);
  void RefreshStatus(Embedded& item);

 private:
  document::Node* NodeAt(const std::vector<size_t>& path);
  void FindItems(std::vector<std::string>* warnings);
  bool EnsureNode(Embedded& item);
  bool SimulateOnce(Embedded& item);
  // Stops the slave of the item used longest ago (not `keep`) while as many
  // as max_slaves run.
  void MakeRoom(const Embedded& keep);
  void StopNode(Embedded& item);
  void Fail(Embedded& item, const asgard_error& error);

  document::Document doc_;
  MediumRegistry& registry_;
  HostOptions options_;
  std::vector<Embedded> items_;
  std::atomic<long> clock_ = 0;  // counts node uses, for Embedded::last_use
};

}  // namespace asgard::host
