// The host's document tree and its embedded subdocuments.
//
// Design: items are found by one walk in document order; paths (child
// indices) locate their elements, recomputed by the same walk after the tree
// changes (a POSTER inserted), so no pointer into a vector is ever kept.  All
// plugin calls go through the C ABI with an asgard_error; a failure becomes
// the item's status line and never an exception or an exit.  Pictures cross
// to and from PNG through Cairo (which premultiplies ARGB in native order, so
// the conversion goes pixel by pixel).
#include "host-shim/host_document.h"

#include <cairo.h>

#include <algorithm>
#include <cstring>

#include "formats/document/file.h"

namespace asgard::host {

namespace {

using document::Node;
using document::NodeKind;

bool IsLeaf(const Node& n) {
  for (const Node& c : n.children)
    if (c.kind == NodeKind::kElement || c.kind == NodeKind::kHeader) return false;
  return true;
}

// Calls f(path, node) for each embedded element: a leaf inside a subdocument.
template <typename F>
void WalkItems(const std::vector<Node>& nodes, std::vector<size_t>& path, bool in_sub, F&& f) {
  for (size_t i = 0; i < nodes.size(); ++i) {
    const Node& n = nodes[i];
    if (n.kind != NodeKind::kElement) continue;
    path.push_back(i);
    if (in_sub && IsLeaf(n) && n.name != "POSTER")
      f(path, n);
    else
      WalkItems(n.children, path, in_sub || n.IsSubdocument(), f);
    path.pop_back();
  }
}

std::string Body(const Node& element) {
  document::Document d;
  d.nodes = element.children;
  return document::Write(d);
}

cairo_status_t AppendPng(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

struct PngSource {
  const std::string* bytes;
  size_t pos = 0;
};

cairo_status_t ReadPng(void* closure, unsigned char* data, unsigned int length) {
  auto* s = static_cast<PngSource*>(closure);
  if (s->pos + length > s->bytes->size()) return CAIRO_STATUS_READ_ERROR;
  std::memcpy(data, s->bytes->data() + s->pos, length);
  s->pos += length;
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

cairo_surface_t* PictureSurface(const Picture& p) {
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, p.width, p.height);
  cairo_surface_flush(s);
  unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  for (int y = 0; y < p.height; ++y) {
    auto* row = reinterpret_cast<uint32_t*>(data + static_cast<size_t>(y) * stride);
    const uint8_t* src = &p.rgba[static_cast<size_t>(y) * p.width * 4];
    for (int x = 0; x < p.width; ++x)
      row[x] = 0xff000000u | (uint32_t(src[4 * x]) << 16) | (uint32_t(src[4 * x + 1]) << 8) |
               src[4 * x + 2];
  }
  cairo_surface_mark_dirty(s);
  return s;
}

std::string EncodePng(const Picture& p) {
  cairo_surface_t* s = PictureSurface(p);
  std::string out;
  cairo_surface_write_to_png_stream(s, AppendPng, &out);
  cairo_surface_destroy(s);
  return out;
}

std::optional<Picture> DecodePng(const std::string& png, std::string* why) {
  // The size is read from the header before anything is decoded: a few
  // bytes of PNG can claim gigapixels.
  const auto* b = reinterpret_cast<const unsigned char*>(png.data());
  if (png.size() < 24 || png.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 ||
      png.compare(12, 4, "IHDR") != 0) {
    if (why) *why = "not a PNG picture";
    return std::nullopt;
  }
  auto u32 = [&](size_t at) {
    return (uint32_t{b[at]} << 24) | (uint32_t{b[at + 1]} << 16) | (uint32_t{b[at + 2]} << 8) |
           b[at + 3];
  };
  const uint32_t w = u32(16), h = u32(20);
  if (w == 0 || h == 0 || w > kMaxPictureSide || h > kMaxPictureSide ||
      uint64_t{w} * h > kMaxPicturePixels) {
    if (why)
      *why = "the picture is " + std::to_string(w) + " × " + std::to_string(h) +
             " pixels, above the limit of " + std::to_string(kMaxPictureSide) + " per side and " +
             std::to_string(kMaxPicturePixels) + " pixels";
    return std::nullopt;
  }
  PngSource src{&png};
  cairo_surface_t* s = cairo_image_surface_create_from_png_stream(ReadPng, &src);
  if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
    if (why)
      *why =
          std::string("cannot decode the PNG: ") + cairo_status_to_string(cairo_surface_status(s));
    cairo_surface_destroy(s);
    return std::nullopt;
  }
  cairo_surface_flush(s);
  Picture p;
  p.width = cairo_image_surface_get_width(s);
  p.height = cairo_image_surface_get_height(s);
  p.rgba.resize(static_cast<size_t>(p.width) * p.height * 4);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  const bool alpha = cairo_image_surface_get_format(s) == CAIRO_FORMAT_ARGB32;
  for (int y = 0; y < p.height; ++y) {
    const auto* row = reinterpret_cast<const uint32_t*>(data + static_cast<size_t>(y) * stride);
    for (int x = 0; x < p.width; ++x) {
      const uint32_t v = row[x];
      const uint32_t a = alpha ? v >> 24 : 255;
      uint8_t* d = &p.rgba[(static_cast<size_t>(y) * p.width + x) * 4];
      for (int c = 0; c < 3; ++c) {
        const uint32_t premul = (v >> (16 - 8 * c)) & 0xff;  // composite on white
        d[c] = static_cast<uint8_t>(std::min<uint32_t>(255, premul + (255 - a)));
      }
      d[3] = 255;
    }
  }
  cairo_surface_destroy(s);
  return p;
}

HostDocument::HostDocument(document::Document doc, MediumRegistry& registry, HostOptions options,
                           std::vector<std::string>* warnings)
    : doc_(std::move(doc)), registry_(registry), options_(std::move(options)) {
  FindItems(warnings);
}

HostDocument::~HostDocument() {
  for (Embedded& item : items_) StopNode(item);
}

void HostDocument::StopNode(Embedded& item) {
  if (!item.medium) return;
  for (auto& [device, r] : item.renditions)
    if (item.medium->rendition()) item.medium->rendition()->destroy(r);
  item.renditions.clear();
  item.rendition_sizes.clear();
  if (!item.node) return;
  item.medium->node()->destroy(item.node);
  item.node = nullptr;
  item.stopped = true;
  item.simulated = false;
}

int HostDocument::running_slaves() const {
  int n = 0;
  for (const Embedded& item : items_) n += item.node != nullptr;
  return n;
}

void HostDocument::MakeRoom(const Embedded& keep) {
  const int most = std::max(1, options_.max_slaves);
  // Room for every item: nothing to stop, and no other item is touched.
  if (static_cast<size_t>(most) >= items_.size()) return;
  while (running_slaves() >= most) {
    Embedded* oldest = nullptr;
    for (Embedded& item : items_)
      if (item.node && &item != &keep && (!oldest || item.last_use < oldest->last_use))
        oldest = &item;
    if (!oldest) return;
    StopNode(*oldest);
    oldest->message = "stopped to keep " + std::to_string(most) +
                      " animations running; it simulates again when drawn";
  }
}

Node* HostDocument::NodeAt(const std::vector<size_t>& path) {
  std::vector<Node>* level = &doc_.nodes;
  Node* n = nullptr;
  for (size_t i : path) {
    n = &(*level)[i];
    level = &n->children;
  }
  return n;
}

const Embedded* HostDocument::ItemAt(const std::vector<size_t>& path) const {
  for (const Embedded& e : items_)
    if (e.path == path) return &e;
  return nullptr;
}

void HostDocument::FindItems(std::vector<std::string>* warnings) {
  std::vector<size_t> path;
  WalkItems(doc_.nodes, path, false, [&](const std::vector<size_t>& p, const Node& n) {
    Embedded item;
    item.index = static_cast<int>(items_.size()) + 1;
    item.path = p;
    item.element = n.name;
    std::string error;
    item.medium = registry_.Find(n.name, &error);
    const std::string where = options_.name + ":" + std::to_string(n.line) + ":" +
                              std::to_string(n.column) + ": <" + n.name + ">: ";
    if (!item.medium) {
      item.message = error;
      if (warnings) warnings->push_back(where + error);
    } else {
      const std::string body = Body(n);
      asgard_bytes text{};
      asgard_error e{};
      if (item.medium->storage()->decode(body.data(), body.size(), &text, &e) != ASGARD_OK) {
        item.message = std::string("cannot read the stored text: ") + e.message;
        if (warnings) warnings->push_back(where + item.message);
        item.medium = nullptr;
      } else {
        item.text = item.medium->Take(text);
        item.message = "not started";
      }
    }
    items_.push_back(std::move(item));
  });
  // Posters stored in the document.
  for (Embedded& item : items_) {
    std::vector<size_t> parent(item.path.begin(), item.path.end() - 1);
    const std::vector<Node>& siblings = parent.empty() ? doc_.nodes : NodeAt(parent)->children;
    for (size_t i = item.path.back() + 1; i < siblings.size(); ++i) {
      if (siblings[i].kind == NodeKind::kSpace) continue;
      if (siblings[i].IsElement("POSTER") && !siblings[i].children.empty()) {
        for (const Node& t : siblings[i].children) {
          if (t.kind != NodeKind::kText) continue;
          std::string why = "its text is not base64";
          std::optional<Picture> pic;
          if (auto png = document::Base64Decode(t.Text())) pic = DecodePng(*png, &why);
          if (pic) {
            item.poster = *pic;
            item.poster_from_document = true;
          } else if (warnings) {
            warnings->push_back(options_.name + ":" + std::to_string(t.line) + ":" +
                                std::to_string(t.column) + ": <POSTER>: ignored: " + why);
          }
        }
      }
      break;
    }
  }
}

void HostDocument::Fail(Embedded& item, const asgard_error& error) {
  RefreshStatus(item);
  if (item.message.empty() || item.status.state < ASGARD_NODE_CRASHED) item.message = error.message;
}

void HostDocument::RefreshStatus(Embedded& item) {
  if (!item.medium || !item.node || !item.medium->node()) return;
  item.status = asgard_node_status{};
  item.status.struct_size = sizeof item.status;
  item.medium->node()->get_status(item.node, &item.status);
  item.message = item.status.message;
  item.simulated = item.status.state == ASGARD_NODE_SIMULATED;
  if (item.simulated) {
    item.t0 = item.status.t0;
    item.t1 = item.status.t1;
    item.frame_rate = item.status.frame_rate;
  }
}

bool HostDocument::EnsureNode(Embedded& item) {
  if (!item.medium) return false;
  item.last_use = ++clock_;
  if (item.node) return true;
  const asgard_node_v1* api = item.medium->node();
  if (!api) {
    item.message = "the medium provides no subdocument nodes";
    return false;
  }
  asgard_node_options o{};
  o.struct_size = sizeof o;
  o.slave_path = options_.slave_path.empty() ? nullptr : options_.slave_path.c_str();
  o.timeout_seconds = options_.timeout_seconds;
  o.slave_memory_mb = options_.slave_memory_mb;
  MakeRoom(item);
  const std::string name = options_.name + ": animation " + std::to_string(item.index);
  o.name = name.c_str();
  asgard_error e{};
  const int32_t s = api->create(item.text.data(), item.text.size(), &o, &item.node, &e);
  if (item.node) RefreshStatus(item);
  if (s != ASGARD_OK) item.message = e.message;
  if (!item.node) item.status = asgard_node_status{};  // nothing of a node stopped before
  if (item.medium->presentation() && item.node) {
    int32_t w = 0, h = 0;
    asgard_error pe{};
    if (item.medium->presentation()->desired_size(item.node, &w, &h, &pe) == ASGARD_OK && w > 0 &&
        h > 0)
      item.width = w, item.height = h;
  }
  return item.node != nullptr && s == ASGARD_OK;
}

namespace {
void Relay(void* user, double fraction, const char*) {
  auto* p = static_cast<std::pair<const HostOptions*, const Embedded*>*>(user);
  if (p->first->progress) p->first->progress(*p->second, fraction);
}
}  // namespace

bool HostDocument::Simulate(Embedded& item) {
  if (SimulateOnce(item)) return true;
  if (item.status.state != ASGARD_NODE_CRASHED || item.restarted) return false;
  item.restarted = true;
  item.restart_reason = item.message;
  return Restart(item);
}

bool HostDocument::SimulateOnce(Embedded& item) {
  if (!EnsureNode(item)) return false;
  std::pair<const HostOptions*, const Embedded*> user(&options_, &item);
  asgard_error e{};
  const int32_t s = item.medium->node()->simulate(item.node, Relay, &user, &e);
  if (s != ASGARD_OK) {
    Fail(item, e);
    return false;
  }
  RefreshStatus(item);
  return true;
}

bool HostDocument::Restart(Embedded& item) {
  if (!item.medium) return false;
  if (!item.node) return Simulate(item);
  asgard_error e{};
  if (item.medium->node()->restart(item.node, &e) != ASGARD_OK) {
    Fail(item, e);
    return false;
  }
  return Simulate(item);
}

bool HostDocument::SetText(Embedded& item, const std::string& text) {
  if (!item.medium) return false;
  asgard_bytes body{};
  asgard_error e{};
  if (item.medium->storage()->encode(text.data(), text.size(), &body, &e) != ASGARD_OK) {
    item.message = e.message;
    return false;
  }
  const std::string stored = item.medium->Take(body);
  auto parsed = document::Parse("DOCUMENT X\n<X>" + stored + "</X>");
  if (!parsed.ok()) {
    item.message = "the medium encoded its text into bytes the document cannot hold";
    return false;
  }
  NodeAt(item.path)->children = parsed.document->Root()->children;
  item.text = text;
  if (!item.node) return Simulate(item);
  std::pair<const HostOptions*, const Embedded*> user(&options_, &item);
  if (item.medium->node()->update(item.node, text.data(), text.size(), Relay, &user, &e) !=
      ASGARD_OK) {
    Fail(item, e);
    return false;
  }
  RefreshStatus(item);
  return true;
}

Picture HostDocument::Frame(Embedded& item, int device, int width, int height, double t,
                            uint32_t flags, bool* live) {
  if (live) *live = false;
  const asgard_rendition_v1* api = item.medium ? item.medium->rendition() : nullptr;
  // A slave stopped to make room for others simulates again.
  if (api && !item.node && item.stopped && !Simulate(item)) return item.poster;
  if (!api || !item.node) return item.poster;
  item.last_use = ++clock_;
  auto it = item.renditions.find(device);
  if (it != item.renditions.end() &&
      item.rendition_sizes[device] != std::make_pair(width, height)) {
    api->destroy(it->second);
    item.renditions.erase(it);
    it = item.renditions.end();
  }
  if (it == item.renditions.end()) {
    asgard_rendition* r = nullptr;
    asgard_error e{};
    const std::string view = "view-" + std::to_string(device);
    if (api->create(item.node, view.c_str(), device, width, height, &r, &e) != ASGARD_OK) {
      item.message = e.message;
      return item.poster;
    }
    it = item.renditions.emplace(device, r).first;
    item.rendition_sizes[device] = {width, height};
  }
  asgard_error e{};
  api->set_flags(it->second, flags, &e);
  asgard_frame f{};
  f.struct_size = sizeof f;
  const int32_t s = api->frame(it->second, t, &f, &e);
  if (s != ASGARD_OK) {
    Fail(item, e);
    // A slave that died is restarted once (and simulates again) before the
    // animation falls back to its poster.
    if (item.status.state == ASGARD_NODE_CRASHED && !item.restarted) {
      item.restarted = true;
      item.restart_reason = item.message;
      if (Restart(item)) return Frame(item, device, width, height, t, flags, live);
    }
  }
  if (!f.pixels) return item.poster;
  Picture p;
  p.width = f.width;
  p.height = f.height;
  p.time = f.time;
  p.rgba.resize(static_cast<size_t>(f.width) * f.height * 4);
  for (int y = 0; y < f.height; ++y)
    std::memcpy(&p.rgba[static_cast<size_t>(y) * f.width * 4],
                f.pixels + static_cast<size_t>(y) * f.stride, static_cast<size_t>(f.width) * 4);
  if (s == ASGARD_OK && live) *live = true;
  return p;
}

void HostDocument::SetPoster(Embedded& item, const Picture& picture) {
  item.poster = picture;
  const std::string text = document::Base64Encode(EncodePng(picture), 76);
  std::vector<size_t> parent(item.path.begin(), item.path.end() - 1);
  std::vector<Node>& siblings = parent.empty() ? doc_.nodes : NodeAt(parent)->children;
  size_t i = item.path.back() + 1;
  while (i < siblings.size() && siblings[i].kind == NodeKind::kSpace) ++i;
  std::vector<Node> content = {Node::Space("\n"), Node::TextNode(text), Node::Space("\n")};
  if (i < siblings.size() && siblings[i].IsElement("POSTER")) {
    siblings[i].children = content;
  } else {
    const size_t at = item.path.back() + 1;
    siblings.insert(siblings.begin() + static_cast<long>(at),
                    {Node::Space("\n"), Node::Element("POSTER", content)});
    // Paths after the insertion point moved: walk again, in the same order.
    std::vector<size_t> path;
    size_t k = 0;
    WalkItems(doc_.nodes, path, false,
              [&](const std::vector<size_t>& p, const Node&) { items_[k++].path = p; });
  }
}

bool HostDocument::Command(Embedded& item, const std::string& line, std::string* reply) {
  if (!EnsureNode(item)) return false;
  asgard_bytes out{};
  asgard_error e{};
  if (item.medium->node()->command(item.node, line.c_str(), &out, &e) != ASGARD_OK) {
    Fail(item, e);
    return false;
  }
  const std::string r = item.medium->Take(out);
  if (reply) *reply = r;
  return true;
}

int32_t HostDocument::Call(Embedded& item, const std::string& method, const std::string& params,
                           std::string* result) {
  if (!item.medium || !item.medium->node_rpc()) {
    item.message = item.medium ? "the medium " + item.medium->path() +
                                     " takes no requests of its own (medium ABI 1.1)"
                               : item.message;
    return ASGARD_ERR_UNSUPPORTED;
  }
  // A scene with errors still has a node: the request may fix its text.
  if (!item.node && !EnsureNode(item) && !item.node) return ASGARD_ERR_SLAVE;
  RefreshStatus(item);
  asgard_error e{};
  if ((item.status.state == ASGARD_NODE_CRASHED || item.status.state == ASGARD_NODE_HUNG) &&
      item.medium->node()->restart(item.node, &e) != ASGARD_OK && e.code != ASGARD_ERR_SCENE) {
    Fail(item, e);
    return e.code;
  }
  item.last_use = ++clock_;
  asgard_bytes out{};
  e = asgard_error{};
  const int32_t s = item.medium->node_rpc()->call(item.node, method.c_str(), params.data(),
                                                  params.size(), &out, &e);
  RefreshStatus(item);
  if (s != ASGARD_OK) {
    item.message = e.message;
    return s;
  }
  const std::string r = item.medium->Take(out);
  if (result) *result = r;
  return ASGARD_OK;
}

}  // namespace asgard::host
