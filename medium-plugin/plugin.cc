// The ASGARD medium behind the C ABI (host-shim/include/asgard/medium_abi.h).
//
//   asgard_node ── SlaveProcess (asgard-core) ── state, text, t0..t1
//       └── asgard_rendition × (view, device): size, flags, frame-memory slot,
//           last good frame (a copy, so it outlives the slave)
//
// Design: every exported function is a thin C shell around C++ that catches
// everything (Guard) and turns it into a status + message.  The node keeps
// the scene text; a slave that died or hung leaves the node in a CRASHED or
// HUNG state whose message names what happened, every rendition keeps its last
// frame, and restart() starts a fresh slave with the same text.  Renditions
// are opened lazily in the current slave (generation counter), so a restart
// needs nothing from the host but a new simulate.  Frame-memory slots are
// handed out per slave, page aligned, first come first served.
#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "asgard/medium_abi.h"
#include "core/protocol/protocol.h"
#include "medium-plugin/slave.h"

using asgard::medium::CallResult;
using asgard::medium::CallStatus;
using asgard::medium::SlaveProcess;
using nlohmann::json;

struct asgard_rendition;

struct asgard_node {
  std::string text;
  std::string name;
  std::string slave_path;
  double timeout = 60.0;
  int memory_mib = asgard::protocol::kDefaultSlaveMemoryMiB;
  std::unique_ptr<SlaveProcess> slave;
  bool spawned = false;  // a slave process was started (at least once)
  int generation = 0;
  int32_t state = ASGARD_NODE_LOADED;
  std::string message;
  double t0 = 0, t1 = 0, frame_rate = asgard::protocol::kDefaultFrameRate;
  int bodies = 0;
  size_t next_offset = 0;
  int next_rendition = 1;
  std::vector<asgard_rendition*> renditions;
};

struct asgard_rendition {
  asgard_node* node = nullptr;
  int id = 0;
  std::string view;
  int32_t device = 0;
  int width = 0, height = 0;
  uint32_t flags = 0;
  int generation = -1;  // the slave generation it is open in
  size_t offset = 0;
  std::vector<uint8_t> last;  // the last good frame, RGBA
  double last_time = 0;
};

namespace {

constexpr int kDesiredWidth = 360, kDesiredHeight = 240;  // points

int32_t SetError(asgard_error* error, int32_t code, const std::string& message) {
  if (error) {
    error->code = code;
    std::snprintf(error->message, sizeof error->message, "%s", message.c_str());
  }
  return code;
}

template <typename F>
int32_t Guard(asgard_error* error, F&& f) {
  try {
    return f();
  } catch (const std::exception& e) {
    return SetError(error, ASGARD_ERR_INTERNAL, std::string("internal error: ") + e.what());
  } catch (...) {
    return SetError(error, ASGARD_ERR_INTERNAL, "internal error");
  }
}

int32_t GiveBytes(const std::string& s, asgard_bytes* out) {
  out->data = static_cast<char*>(std::malloc(s.size() + 1));
  if (!out->data) return ASGARD_ERR_INTERNAL;
  std::memcpy(out->data, s.data(), s.size());
  out->data[s.size()] = '\0';
  out->size = s.size();
  return ASGARD_OK;
}

// ---- storage (seed 6.2.1): {…} with \{ \} \\ escaped ----

int32_t Decode(const char* body, size_t size, asgard_bytes* text, asgard_error* error) {
  return Guard(error, [&]() -> int32_t {
    if (!text) return SetError(error, ASGARD_ERR_INVALID, "no output buffer");
    const std::string_view b(body ? body : "", body ? size : 0);
    const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
    size_t i = 0, j = b.size();
    while (i < j && is_space(b[i])) ++i;
    while (j > i && is_space(b[j - 1])) --j;
    if (j - i < 2 || b[i] != '{' || b[j - 1] != '}')
      return SetError(error, ASGARD_ERR_SYNTAX,
                      "an <ASGARD> element must hold one {…} text with the scene");
    std::string out;
    for (size_t k = i + 1; k + 1 < j; ++k) {
      const char c = b[k];
      if (c == '\\' && k + 2 < j && (b[k + 1] == '{' || b[k + 1] == '}' || b[k + 1] == '\\')) {
        out += b[++k];
      } else if (c == '{' || c == '}') {
        return SetError(error, ASGARD_ERR_SYNTAX, "an unescaped brace in the <ASGARD> text");
      } else {
        out += c;
      }
    }
    return GiveBytes(out, text);
  });
}

int32_t Encode(const char* text, size_t size, asgard_bytes* body, asgard_error* error) {
  return Guard(error, [&]() -> int32_t {
    if (!body) return SetError(error, ASGARD_ERR_INVALID, "no output buffer");
    std::string out = "{";
    for (size_t k = 0; text && k < size; ++k) {
      if (text[k] == '{' || text[k] == '}' || text[k] == '\\') out += '\\';
      out += text[k];
    }
    out += '}';
    return GiveBytes(out, body);
  });
}

// ---- the slave program ----

std::string PluginDirectory() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&PluginDirectory), &info) && info.dli_fname) {
    std::string p = info.dli_fname;
    const size_t slash = p.rfind('/');
    if (slash != std::string::npos) return p.substr(0, slash);
  }
  return ".";
}

std::string FindSlave(const asgard_node_options* options) {
  if (options && options->slave_path && *options->slave_path) return options->slave_path;
  if (const char* env = std::getenv("ASGARD_CORE"); env && *env) return env;
  const std::string dir = PluginDirectory();
  for (const char* rel : {"/../core/app/asgard-core", "/asgard-core", "/../bin/asgard-core",
                          "/../../bin/asgard-core"}) {
    const std::string p = dir + rel;
    if (::access(p.c_str(), X_OK) == 0) return p;
  }
  return "asgard-core";  // PATH
}

int32_t StatusOf(const CallResult& r, asgard_node* node, asgard_error* error) {
  switch (r.status) {
    case CallStatus::kOk:
      return ASGARD_OK;
    case CallStatus::kRemoteError:
      return SetError(
          error,
          r.remote_code == asgard::protocol::kSceneError ? ASGARD_ERR_SCENE : ASGARD_ERR_INVALID,
          r.message);
    case CallStatus::kTimeout:
      node->state = ASGARD_NODE_HUNG;
      node->message = r.message;
      return SetError(error, ASGARD_ERR_TIMEOUT, r.message);
    case CallStatus::kProtocol:
      if (!node->slave->running()) node->state = ASGARD_NODE_CRASHED;
      node->message = r.message;
      return SetError(error, ASGARD_ERR_PROTOCOL, r.message);
    case CallStatus::kDied:
    case CallStatus::kNotRunning:
      if (node->state != ASGARD_NODE_HUNG) node->state = ASGARD_NODE_CRASHED;
      node->message = r.message;
      return SetError(error, ASGARD_ERR_SLAVE, r.message);
  }
  return ASGARD_ERR_INTERNAL;
}

// The node's state after its slave answered `load` with `result`.
int32_t Loaded(asgard_node* node, const json& result, asgard_error* error) {
  if (!result.value("ok", false)) {
    std::string message;
    for (const auto& d : result.value("diagnostics", json::array())) {
      if (!message.empty()) message += "; ";
      message += std::to_string(d.value("line", 0)) + ":" + std::to_string(d.value("column", 0)) +
                 ": " + d.value("message", std::string());
    }
    node->state = ASGARD_NODE_SCENE_ERROR;
    node->message = "scene errors: " + message;
    return SetError(error, ASGARD_ERR_SCENE, node->message);
  }
  node->bodies = static_cast<int>(result.value("bodies", json::array()).size());
  node->state = ASGARD_NODE_LOADED;
  node->message = "loaded, not simulated";
  return ASGARD_OK;
}

// The node's state after its slave answered `simulate` with `result`.
void Simulated(asgard_node* node, const json& result) {
  node->t0 = result.value("t0", 0.0);
  node->t1 = result.value("t1", 0.0);
  node->frame_rate = result.value("frame_rate", asgard::protocol::kDefaultFrameRate);
  node->bodies = result.value("bodies", 0);
  node->state = ASGARD_NODE_SIMULATED;
  char msg[160];
  std::snprintf(msg, sizeof msg, "%d %s, t = %g .. %g s", node->bodies,
                node->bodies == 1 ? "body" : "bodies", node->t0, node->t1);
  node->message = msg;
}

// Loads the node's text into its slave.
int32_t Load(asgard_node* node, asgard_error* error) {
  const CallResult r = node->slave->Call("load", {{"text", node->text}});
  if (const int32_t s = StatusOf(r, node, error); s != ASGARD_OK) return s;
  return Loaded(node, r.result, error);
}

int32_t Start(asgard_node* node, asgard_error* error) {
  node->slave.reset();
  node->slave = std::make_unique<SlaveProcess>(node->slave_path, node->timeout, node->memory_mib);
  ++node->generation;
  node->next_offset = 0;
  if (!node->slave->running()) {
    node->state = ASGARD_NODE_CRASHED;
    node->message = node->slave->error();
    return SetError(error, ASGARD_ERR_SLAVE, node->message);
  }
  node->spawned = true;
  return Load(node, error);
}

struct ProgressRelay {
  asgard_progress_fn fn;
  void* user;
};

int32_t RunSimulation(asgard_node* node, const char* method, const json& params,
                      asgard_progress_fn progress, void* user, asgard_error* error) {
  if (!node->slave || !node->slave->running())
    return SetError(error, ASGARD_ERR_SLAVE,
                    node->message.empty() ? "asgard-core is not running" : node->message);
  const CallResult r = node->slave->Call(method, params, [&](double f, double t) {
    if (progress) {
      char msg[64];
      std::snprintf(msg, sizeof msg, "t = %.3g", t);
      progress(user, f, msg);
    }
  });
  if (r.status == CallStatus::kRemoteError && r.remote_code == asgard::protocol::kSceneError) {
    node->state = ASGARD_NODE_SCENE_ERROR;
    node->message = r.message;
  }
  if (const int32_t s = StatusOf(r, node, error); s != ASGARD_OK) return s;
  Simulated(node, r.result);
  return ASGARD_OK;
}

// ---- node ----

int32_t NodeCreate(const char* text, size_t size, const asgard_node_options* options,
                   asgard_node** out, asgard_error* error) {
  return Guard(error, [&]() -> int32_t {
    if (!out) return SetError(error, ASGARD_ERR_INVALID, "no output node");
    *out = nullptr;
    auto node = std::make_unique<asgard_node>();
    node->text.assign(text ? text : "", text ? size : 0);
    node->slave_path = FindSlave(options);
    if (options && options->timeout_seconds > 0) node->timeout = options->timeout_seconds;
    if (options && options->name) node->name = options->name;
    // A host built before slave_memory_mb passes a shorter struct.
    if (options &&
        options->struct_size >=
            offsetof(asgard_node_options, slave_memory_mb) + sizeof options->slave_memory_mb &&
        options->slave_memory_mb > 0)
      node->memory_mib = static_cast<int>(std::clamp(options->slave_memory_mb, 16.0, 1e6));
    const int32_t s = Start(node.get(), error);
    // A node whose text has errors still exists (it can be updated), and so
    // does one whose slave started but died or hung loading the text: it is
    // CRASHED or HUNG like any other, and restart() starts it again.  Only a
    // slave that could not be started at all leaves no node.
    if (s != ASGARD_OK && s != ASGARD_ERR_SCENE && !node->spawned) return s;
    *out = node.release();
    return s;
  });
}

void RenditionDestroy(asgard_rendition* r);

void NodeDestroy(asgard_node* node) {
  try {
    if (!node) return;
    while (!node->renditions.empty()) RenditionDestroy(node->renditions.back());
    delete node;
  } catch (...) {
  }
}

int32_t NodeSimulate(asgard_node* node, asgard_progress_fn progress, void* user,
                     asgard_error* error) {
  return Guard(error, [&]() -> int32_t {
    if (!node) return SetError(error, ASGARD_ERR_INVALID, "no node");
    if (node->state == ASGARD_NODE_SCENE_ERROR)
      return SetError(error, ASGARD_ERR_SCENE, node->message);
    return RunSimulation(node, "simulate", json::object(), progress, user, error);
  });
}

int32_t NodeUpdate(asgard_node* node, const char* text, size_t size, asgard_progress_fn progress,
                   void* user, asgard_error* error) {
  return Guard(error, [&]() -> int32_t {
    if (!node) return SetError(error, ASGARD_ERR_INVALID, "no node");
    node->text.assign(text ? text : "", text ? size : 0);
    if (!node->slave || !node->slave->running()) {
      if (const int32_t s = Start(node, error); s != ASGARD_OK) return s;
      return RunSimulation(node, "simulate", json::object(), progress, user, error);
    }
    if (const int32_t s = Load(node, error); s != ASGARD_OK) return s;
    return RunSimulation(node, "simulate", json::object(), progress, user, error);
  });
}

int32_t NodeCommand(asgard_node* node, const char* line, asgard_bytes* reply, asgard_error* error) {
  return Guard(error, [&]() -> int32_t {
    if (!node || !line || !reply) return SetError(error, ASGARD_ERR_INVALID, "bad arguments");
    if (!node->slave || !node->slave->running())
      return SetError(error, ASGARD_ERR_SLAVE, node->message);
    const CallResult r = node->slave->Call("command", {{"line", line}});
    if (const int32_t s = StatusOf(r, node, error); s != ASGARD_OK) return s;
    return GiveBytes(r.result.value("reply", std::string()), reply);
  });
}

int32_t NodeGetText(asgard_node* node, asgard_bytes* text, asgard_error* error) {
  return Guard(error, [&]() -> int32_t {
    if (!node || !text) return SetError(error, ASGARD_ERR_INVALID, "bad arguments");
    return GiveBytes(node->text, text);
  });
}

void NodeGetStatus(asgard_node* node, asgard_node_status* status) {
  if (!node || !status || status->struct_size < sizeof(asgard_node_status)) return;
  status->state = node->state;
  status->pid = node->slave && node->slave->running() ? node->slave->pid() : 0;
  status->bodies = node->bodies;
  status->t0 = node->t0;
  status->t1 = node->t1;
  status->frame_rate = node->frame_rate;
  std::snprintf(status->message, sizeof status->message, "%s", node->message.c_str());
}

int32_t NodeRestart(asgard_node* node, asgard_error* error) {
  return Guard(error, [&]() -> int32_t {
    if (!node) return SetError(error, ASGARD_ERR_INVALID, "no node");
    return Start(node, error);
  });
}

// ---- the medium's own requests (ABI 1.1): the host's editor on this slave ----

// A request to the node's slave on behalf of the host (its editor server).
// The node follows what the request did: the text after an edit (so a
// restart loads the edited scene), loaded or simulated after load and
// simulate, so renditions draw what the editor shows.
int32_t NodeCall(asgard_node* node, const char* method, const char* params, size_t params_size,
                 asgard_bytes* result, asgard_error* error) {
  return Guard(error, [&]() -> int32_t {
    if (!node || !method || !result) return SetError(error, ASGARD_ERR_INVALID, "bad arguments");
    const std::string m = method;
    for (const char* own : {"shutdown", "open_rendition", "close_rendition", "frame"})
      if (m == own)
        return SetError(error, ASGARD_ERR_INVALID,
                        "'" + m + "' is the node's own request (use the node and rendition calls)");
    const json p = params && params_size
                       ? json::parse(std::string_view(params, params_size), nullptr, false)
                       : json::object();
    if (p.is_discarded() || !p.is_object())
      return SetError(error, ASGARD_ERR_INVALID, "the params of '" + m + "' are not a JSON object");
    if (!node->slave || !node->slave->running())
      return SetError(error, ASGARD_ERR_SLAVE,
                      node->message.empty() ? "asgard-core is not running" : node->message);
    const CallResult r = node->slave->Call(m, p);
    const bool simulates = m == "simulate" || m == "update";
    if (simulates && r.status == CallStatus::kRemoteError &&
        r.remote_code == asgard::protocol::kSceneError) {
      node->state = ASGARD_NODE_SCENE_ERROR;
      node->message = r.message;
    }
    if (const int32_t s = StatusOf(r, node, error); s != ASGARD_OK) return s;
    const bool edits = m == "edit" || m == "create" || m == "delete" || m == "undo" || m == "redo";
    if ((m == "load" || m == "update") && p.contains("text") && p["text"].is_string())
      node->text = p["text"].get<std::string>();
    else if (edits && r.result.is_object() && r.result.contains("text") &&
             r.result["text"].is_string())
      node->text = r.result["text"].get<std::string>();
    if (m == "load") {
      asgard_error ignored{};
      Loaded(node, r.result, &ignored);  // scene errors are the editor's to show
    } else if (simulates) {
      Simulated(node, r.result);
    } else if (edits) {
      // The slave dropped its motion with the old text: simulate to draw again.
      node->state = ASGARD_NODE_LOADED;
      node->message = "edited, not simulated";
    }
    return GiveBytes(r.result.dump(-1, ' ', false, json::error_handler_t::replace), result);
  });
}

// ---- presentation (seed 6.2.3: "arbitrarily selects a size") ----

int32_t DesiredSize(asgard_node* node, int32_t* width, int32_t* height, asgard_error* error) {
  if (!node || !width || !height) return SetError(error, ASGARD_ERR_INVALID, "bad arguments");
  *width = kDesiredWidth;
  *height = kDesiredHeight;
  return ASGARD_OK;
}

// ---- renditions ----

int32_t RenditionCreate(asgard_node* node, const char* view, int32_t device, int32_t width,
                        int32_t height, asgard_rendition** out, asgard_error* error) {
  return Guard(error, [&]() -> int32_t {
    if (!node || !out) return SetError(error, ASGARD_ERR_INVALID, "bad arguments");
    constexpr int kMax = asgard::protocol::kMaxRenditionSide;
    if (width < 1 || height < 1 || width > kMax || height > kMax)
      return SetError(error, ASGARD_ERR_INVALID,
                      "a rendition is 1.." + std::to_string(kMax) + " pixels each way");
    auto r = std::make_unique<asgard_rendition>();
    r->node = node;
    r->id = node->next_rendition++;
    r->view = view ? view : "";
    r->device = device;
    r->width = width;
    r->height = height;
    *out = r.get();
    node->renditions.push_back(r.release());
    return ASGARD_OK;
  });
}

void RenditionDestroy(asgard_rendition* r) {
  if (!r) return;
  asgard_node* node = r->node;
  auto& list = node->renditions;
  list.erase(std::remove(list.begin(), list.end(), r), list.end());
  if (node->slave && node->slave->running() && r->generation == node->generation)
    node->slave->Call("close_rendition", {{"rendition", r->id}});
  delete r;
}

int32_t RenditionSetFlags(asgard_rendition* r, uint32_t flags, asgard_error* error) {
  if (!r) return SetError(error, ASGARD_ERR_INVALID, "no rendition");
  r->flags = flags;
  return ASGARD_OK;
}

void LastFrame(asgard_rendition* r, asgard_frame* frame) {
  frame->width = r->width;
  frame->height = r->height;
  frame->stride = r->width * 4;
  frame->pixels = r->last.empty() ? nullptr : r->last.data();
  frame->time = r->last_time;
}

int32_t RenditionFrame(asgard_rendition* r, double time, asgard_frame* frame, asgard_error* error) {
  return Guard(error, [&]() -> int32_t {
    if (!r || !frame) return SetError(error, ASGARD_ERR_INVALID, "bad arguments");
    asgard_node* node = r->node;
    LastFrame(r, frame);
    if (!node->slave || !node->slave->running())
      return SetError(error, ASGARD_ERR_SLAVE, node->message);
    if (node->state != ASGARD_NODE_SIMULATED)
      return SetError(error, ASGARD_ERR_INVALID, "the animation has not been simulated");
    if (r->generation != node->generation) {
      const size_t bytes = (static_cast<size_t>(r->width) * r->height * 4 + 4095) & ~size_t{4095};
      if (node->next_offset + bytes > asgard::medium::kFrameMemory)
        return SetError(error, ASGARD_ERR_INVALID, "out of shared frame memory");
      const CallResult o = node->slave->Call("open_rendition", {{"rendition", r->id},
                                                                {"width", r->width},
                                                                {"height", r->height},
                                                                {"offset", node->next_offset},
                                                                {"device", r->device}});
      if (const int32_t s = StatusOf(o, node, error); s != ASGARD_OK) return s;
      r->offset = node->next_offset;
      node->next_offset += bytes;
      r->generation = node->generation;
    }
    const CallResult f =
        node->slave->Call("frame", {{"rendition", r->id},
                                    {"t", time},
                                    {"handles", (r->flags & ASGARD_RENDITION_HANDLES) != 0},
                                    {"wire", (r->flags & ASGARD_RENDITION_WIRE) != 0}});
    if (const int32_t s = StatusOf(f, node, error); s != ASGARD_OK) return s;
    if (f.result.value("width", 0) != r->width || f.result.value("height", 0) != r->height ||
        f.result.value("offset", size_t{0}) != r->offset) {
      node->slave->Kill("protocol error: a frame of the wrong size or place");
      node->state = ASGARD_NODE_CRASHED;
      node->message = node->slave->error();
      return SetError(error, ASGARD_ERR_PROTOCOL, node->message);
    }
    const uint8_t* src = node->slave->frame_memory() + r->offset;
    r->last.assign(src, src + static_cast<size_t>(r->width) * r->height * 4);
    r->last_time = f.result.value("time", time);
    LastFrame(r, frame);
    return ASGARD_OK;
  });
}

void FreeBytes(asgard_bytes* b) {
  if (!b) return;
  std::free(b->data);
  b->data = nullptr;
  b->size = 0;
}

const asgard_storage_v1 kStorage = {sizeof(asgard_storage_v1), Decode, Encode};
const asgard_node_v1 kNode = {sizeof(asgard_node_v1),
                              NodeCreate,
                              NodeDestroy,
                              NodeUpdate,
                              NodeSimulate,
                              NodeCommand,
                              NodeGetText,
                              NodeGetStatus,
                              NodeRestart};
const asgard_node_rpc_v1 kNodeRpc = {sizeof(asgard_node_rpc_v1), NodeCall};
const asgard_presentation_v1 kPresentation = {sizeof(asgard_presentation_v1), DesiredSize};
const asgard_rendition_v1 kRendition = {sizeof(asgard_rendition_v1), RenditionCreate,
                                        RenditionDestroy, RenditionSetFlags, RenditionFrame};

const void* GetInterface(uint32_t id) {
  switch (id) {
    case ASGARD_IFACE_STORAGE:
      return &kStorage;
    case ASGARD_IFACE_NODE:
      return &kNode;
    case ASGARD_IFACE_PRESENTATION:
      return &kPresentation;
    case ASGARD_IFACE_RENDITION:
      return &kRendition;
    case ASGARD_IFACE_NODE_RPC:
      return &kNodeRpc;
  }
  return nullptr;
}

const asgard_medium_entry kEntry = {
    sizeof(asgard_medium_entry),
    ASGARD_MEDIUM_ABI_MAJOR,
    ASGARD_MEDIUM_ABI_MINOR,
    "ASGARD",
    "Animation",
    "Physically-based 3D animation: the scene text is simulated by an asgard-core slave",
    GetInterface,
    FreeBytes};

}  // namespace

extern "C" __attribute__((visibility("default"))) const asgard_medium_entry*
asgard_medium_get_entry() {
  return &kEntry;
}
