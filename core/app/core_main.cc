// asgard-core: the slave process of the document medium (seed 6.2.2).
//
//   medium plugin (in dochost)                 asgard-core
//        │ ── [u32 length][JSON-RPC request] ──▶ │  load · update · simulate · open_rendition
//        │ ◀── progress notifications ────────── │  close_rendition · frame · command · shutdown
//        │ ◀── [u32 length][JSON-RPC response] ─ │
//        └──────── frames: RGBA in a shared memfd (inherited), at offsets the host assigns
//
// Design: one process per animation subdocument holds the scene text, the
// simulated run and one renderer per rendition (seed: "multiple renditions
// of this animation are managed by this process").  Requests are handled one
// at a time; `simulate` streams progress notifications, which double as the
// heartbeat the host's watchdog waits for.  Every request is answered — a
// malformed one with a JSON-RPC error (protocol::ErrorCode, core/protocol:
// the header the plugin reads the same codes from) — and no exception leaves
// a handler.  Only a frame header that cannot be trusted (a length above
// protocol::kMaxMessage) ends the process, after an error reply, since the
// stream can no longer be resynchronised.  The scene lives in a core/session
// Session, which evaluates each text once: `load` and `update` adopt the new
// text through it (change analysis, one undo history) and check the scene it
// evaluated, `simulate` re-simulates incrementally; `edit` applies a
// graphical edit and answers with the text patches.
//
// Test hooks (environment ASGARD_CORE_FAULT): "hang-on-simulate" stops
// answering when asked to simulate; "endless-progress-on-simulate" reports
// progress every 50 ms and never finishes; "exit-on-frame" exits when asked for a
// frame; "garbage-on-frame" answers a frame request
// with bytes that are not JSON; "exit-on-load" exits at the first load.
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "core/app/editor_rpc.h"
#include "core/lang/lang.h"
#include "core/pipeline/pipeline.h"
#include "core/protocol/protocol.h"
#include "core/render/sampler.h"
#include "core/render/shaded.h"
#include "core/render/wire.h"
#include "core/session/session.h"

namespace {

using nlohmann::json;
using namespace asgard;
using protocol::kMaxMessage;
using enum protocol::ErrorCode;

const char* const kHelp =
    R"(Usage: asgard-core [--fd N] [--shm-fd N --shm-size BYTES] [--memory MIB]

The slave process of the Asgard document medium: it is started by the medium
plugin (dochost) for one animation subdocument and answers length-prefixed
JSON-RPC 2.0 requests (a 4-byte big-endian length, then the JSON text) on the
socket N (default: requests on standard input, answers on standard output).
Frames are written as RGBA into the shared memory object inherited as --shm-fd.
--memory limits the process's data segment (RLIMIT_DATA) to MIB mebibytes: an
allocation past it fails and the slave ends (exit status 3) instead of
starving the host.  Builds with AddressSanitizer ignore it (the sanitizer's
shadow memory alone is larger).

Methods: load {text}, update {text}, simulate {}, edit {element, param,
values}, undo {}, redo {}, scene_state {}, meshes {}, poses {} (the
browser editor's, core/app/editor_rpc.h), open_rendition {rendition, width, height, offset,
device}, close_rendition {rendition}, frame {rendition, t, handles?, wire?},
command {line}, shutdown {}.

Exit status 0 after shutdown or end of input, 2 on bad usage or a broken
stream, 3 when it ran out of memory.
)";

// Moves all n bytes with `io` (read or write), retrying on EINTR; false at
// the end of the stream or on an error.
template <typename Char, typename Io>
bool TransferAll(Char* p, size_t n, Io io) {
  while (n > 0) {
    const ssize_t r = io(p, n);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return false;
    p += r, n -= static_cast<size_t>(r);
  }
  return true;
}

bool ReadAll(int fd, void* buf, size_t n) {
  return TransferAll(static_cast<char*>(buf), n,
                     [fd](char* p, size_t k) { return ::read(fd, p, k); });
}

bool WriteAll(int fd, const void* buf, size_t n) {
  return TransferAll(static_cast<const char*>(buf), n,
                     [fd](const char* p, size_t k) { return ::write(fd, p, k); });
}

// A session's run options: every core of the machine steps components
// (results do not depend on it; simulation.h, "Threads").
pipeline::RunOptions SessionOptions() {
  pipeline::RunOptions o;
  o.solver.threads = solver::MachineThreads();
  return o;
}

struct RpcError {
  int code;
  std::string message;
};

// The members of a request's params, checked: an error names the member
// (its place in the request) and what it must be.
[[noreturn]] void BadParam(const char* name, const std::string& what) {
  throw RpcError{static_cast<int>(kInvalidParams),
                 std::string("invalid params: '") + name + "' " + what};
}

const json& Param(const json& params, const char* name) {
  if (!params.contains(name)) BadParam(name, "is missing");
  return params[name];
}

long long Integer(const json& params, const char* name, long long lo, long long hi) {
  const json& v = Param(params, name);
  const std::string range =
      "must be an integer from " + std::to_string(lo) + " to " + std::to_string(hi);
  if (v.is_number_unsigned()) {
    const auto u = v.get<unsigned long long>();
    if (u > static_cast<unsigned long long>(hi)) BadParam(name, range);
    return static_cast<long long>(u);
  }
  if (v.is_number_integer()) {
    const auto i = v.get<long long>();
    if (i < lo || i > hi) BadParam(name, range);
    return i;
  }
  if (v.is_number_float()) {
    // 640.0 is an integer; 1e300 and 0.5 are not (and converting them would
    // be undefined).
    const double d = v.get<double>();
    // (double)hi may round up to 2^63, which no long long holds.
    if (!(d >= static_cast<double>(lo) && d <= static_cast<double>(hi) && d < 0x1p63) ||
        d != std::floor(d))
      BadParam(name, range);
    return static_cast<long long>(d);
  }
  BadParam(name, range);
}

double Number(const json& params, const char* name) {
  const json& v = Param(params, name);
  if (!v.is_number()) BadParam(name, "must be a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) BadParam(name, "must be finite");
  return d;
}

bool Flag(const json& params, const char* name, bool fallback) {
  if (!params.contains(name)) return fallback;
  if (!params[name].is_boolean()) BadParam(name, "must be true or false");
  return params[name].get<bool>();
}

std::string String(const json& params, const char* name) {
  const json& v = Param(params, name);
  if (!v.is_string()) BadParam(name, "must be a string");
  return v.get<std::string>();
}

constexpr long long kIntMax = std::numeric_limits<int>::max();

// nlohmann's message without its "[json.exception.out_of_range.406] " tag.
std::string WithoutPrefix(const char* what) {
  std::string s = what;
  if (const size_t end = s.find("] "); !s.empty() && s[0] == '[' && end != std::string::npos)
    s.erase(0, end + 2);
  return s;
}

struct Rendition {
  int width = 0, height = 0;
  size_t offset = 0;
  bool handles = false;
  bool wire = false;
  std::unique_ptr<render::ShadedRenderer> renderer;
};

class Slave {
 public:
  Slave(int in, int out, uint8_t* shm, size_t shm_size)
      : in_(in), out_(out), shm_(shm), shm_size_(shm_size) {
    if (const char* f = std::getenv("ASGARD_CORE_FAULT")) fault_ = f;
    // With ASGARD_CORE_FAULT_ONCE=FILE only the first slave misbehaves: the
    // one that creates FILE.
    if (const char* once = std::getenv("ASGARD_CORE_FAULT_ONCE"); once && !fault_.empty()) {
      const int fd = ::open(once, O_CREAT | O_EXCL | O_WRONLY, 0600);
      if (fd < 0)
        fault_.clear();
      else
        ::close(fd);
    }
  }

  int Loop() {
    for (;;) {
      unsigned char head[4];
      if (!ReadAll(in_, head, 4)) return 0;  // the host closed the channel
      const uint32_t n = protocol::DecodeLength(head);
      if (n > kMaxMessage) {
        SendError(nullptr, kInvalidRequest,
                  "message length " + std::to_string(n) + " exceeds the limit of " +
                      std::to_string(kMaxMessage) + " bytes; the stream cannot be resynchronised");
        return 2;
      }
      std::string body(n, '\0');
      if (n > 0 && !ReadAll(in_, body.data(), n)) return 0;
      if (!Handle(body)) return 0;
    }
  }

 private:
  void Send(const json& message) {
    const std::string s = message.dump(-1, ' ', false, json::error_handler_t::replace);
    const auto head = protocol::EncodeLength(static_cast<uint32_t>(s.size()));
    if (!WriteAll(out_, head.data(), head.size()) || !WriteAll(out_, s.data(), s.size()))
      std::_Exit(0);
  }
  void SendError(const json* id, int code, const std::string& message) {
    Send({{"jsonrpc", "2.0"},
          {"id", id ? *id : json(nullptr)},
          {"error", {{"code", code}, {"message", message}}}});
  }

 public:
  // Answers one message body; false when the process should end (shutdown).
  // Public for the protocol fuzz target (tests/fuzz/fuzz_protocol.cc).
  bool Handle(const std::string& body) {
    if (protocol::JsonNestingDepth(body) > protocol::kMaxJsonDepth) {
      SendError(nullptr, kInvalidRequest,
                "invalid request: arrays and objects nested more than " +
                    std::to_string(protocol::kMaxJsonDepth) + " deep");
      return true;
    }
    json request;
    try {
      request = json::parse(body);
    } catch (const json::parse_error& e) {
      // e.byte: the 1-based position of the offending byte (one past the
      // end when the text ends too soon).
      SendError(nullptr, kParseError,
                "parse error at byte " + std::to_string(e.byte) + ": the message is not JSON");
      return true;
    } catch (const json::exception& e) {
      // Well-formed but unreadable: a number past the range of a double.
      SendError(nullptr, kParseError,
                std::string("parse error: the message cannot be read: ") + WithoutPrefix(e.what()));
      return true;
    }
    if (!request.is_object() || !request.contains("method") || !request["method"].is_string() ||
        (request.contains("params") && !request["params"].is_object())) {
      const json id = request.is_object() && request.contains("id") ? request["id"] : json();
      SendError(&id, kInvalidRequest, "invalid request: expected an object with a string 'method'");
      return true;
    }
    const json id = request.value("id", json());
    const std::string method = request["method"];
    const json params = request.value("params", json::object());
    try {
      if (method == "shutdown") {
        Send({{"jsonrpc", "2.0"}, {"id", id}, {"result", {{"ok", true}}}});
        return false;
      }
      json result = Dispatch(method, params, id);
      if (!result.is_null()) Send({{"jsonrpc", "2.0"}, {"id", id}, {"result", result}});
    } catch (const RpcError& e) {
      SendError(&id, e.code, e.message);
    } catch (const json::exception& e) {
      SendError(&id, kInvalidParams, std::string("invalid params: ") + e.what());
    } catch (const std::exception& e) {
      SendError(&id, kInternalError, std::string("internal error: ") + e.what());
    }
    return true;
  }

 private:
  static std::string Text(const json& params) { return String(params, "text"); }

  json Dispatch(const std::string& method, const json& params, const json& id) {
    if (method == "load") return Load(Text(params));
    if (method == "update") {
      json loaded = Load(Text(params));
      if (!loaded["ok"]) return loaded;
      return Simulate(id);
    }
    if (method == "simulate") return Simulate(id);
    if (method == "open_rendition") return OpenRendition(params);
    if (method == "close_rendition") {
      renditions_.erase(static_cast<int>(Integer(params, "rendition", 0, kIntMax)));
      return {{"ok", true}};
    }
    if (method == "frame") return Frame(params);
    if (method == "edit") return Edit(params);
    if (method == "create") return Create(params);
    if (method == "delete") return Delete(params);
    if (method == "undo" || method == "redo") {
      if (!session_) throw RpcError{kSceneError, "no scene is loaded"};
      const bool done = method == "undo" ? session_->Undo() : session_->Redo();
      return {{"ok", done}, {"text", session_->text()}};
    }
    if (method == "command") return Command(String(params, "line"));
    if (auto r = editor_rpc::Dispatch(method, params, session_.get(), sampler_.get())) return *r;
    throw RpcError{kMethodNotFound, "unknown method '" + method + "'"};
  }

  // The session keeps one history and simulates incrementally: after an
  // update only what the edit affected is computed again.
  json Load(const std::string& text) {
    if (fault_ == "exit-on-load") std::_Exit(3);
    text_ = text;
    motion_.reset();
    sampler_.reset();
    for (auto& [k, r] : renditions_) r.renderer.reset();
    json changes = json::array();
    if (!session_) {
      session_ = std::make_unique<session::Session>(text_, SessionOptions());
    } else {
      for (const auto& c : session_->UpdateText(text_))
        if (c.change != session::Change::kUnchanged)
          changes.push_back({{"kind", scene::ElementKindName(c.kind)},
                             {"name", c.name},
                             {"change", session::ChangeName(c.change)}});
    }
    // The scene the session evaluated: the text is not evaluated again.
    const pipeline::Run check = pipeline::Check(session_->scene());
    json diagnostics = json::array();
    for (const auto& d : check.diagnostics)
      diagnostics.push_back(
          {{"line", d.span.line}, {"column", d.span.column}, {"message", d.message}});
    json bodies = json::array();
    for (const auto& b : check.scene.bodies) bodies.push_back(b.name);
    return {
        {"ok", check.ok}, {"diagnostics", diagnostics}, {"bodies", bodies}, {"changes", changes}};
  }

  // A graphical edit: {element, param, values} → the text patches (byte
  // offsets into the previous text, end exclusive, with 1-based lines and
  // columns counted in bytes) and the new text.
  json Edit(const json& params) {
    if (!session_) throw RpcError{kSceneError, "no scene is loaded"};
    if (params.contains("element") && params["element"].is_string() && params.contains("param") &&
        params["param"].is_string() && params.contains("text") && params["text"].is_string())
      return Edited(session_->SetWord(params["element"], params["param"], params["text"]));
    if (!params.contains("element") || !params["element"].is_string() ||
        !params.contains("param") || !params["param"].is_string() || !params.contains("values") ||
        !params["values"].is_array())
      throw RpcError{kInvalidParams,
                     "invalid params: edit needs element, param and values (or text)"};
    std::vector<double> values;
    for (const auto& v : params["values"]) {
      if (!v.is_number()) throw RpcError{kInvalidParams, "invalid params: values must be numbers"};
      values.push_back(v.get<double>());
    }
    return Edited(session_->SetParameter(params["element"], params["param"], values));
  }

  // A new element: {command} (one well-formatted command, inserted after the
  // last command of its kind) → the text patches and the new text, as edit.
  json Create(const json& params) {
    if (!session_) throw RpcError{kSceneError, "no scene is loaded"};
    if (!params.contains("command") || !params["command"].is_string())
      throw RpcError{kInvalidParams, "invalid params: create needs a command"};
    const std::string command = params["command"];
    if (command.find_first_not_of(" \t") == std::string::npos ||
        command.find('\n') != std::string::npos)
      throw RpcError{kInvalidParams, "invalid params: create takes one command on one line"};
    return Edited(session_->CreateElement(command));
  }

  // An element's command removed: {element} (a name or kind#index).
  json Delete(const json& params) {
    if (!session_) throw RpcError{kSceneError, "no scene is loaded"};
    if (!params.contains("element") || !params["element"].is_string())
      throw RpcError{kInvalidParams, "invalid params: delete needs an element"};
    return Edited(session_->DeleteElement(params["element"]));
  }

  // The answer to a graphical edit, creation or deletion.
  json Edited(const session::EditResult& r) {
    if (!r.ok) throw RpcError{kSceneError, r.error};
    json edits = json::array();
    for (const auto& e : r.edits)
      edits.push_back({{"begin", e.begin},
                       {"end", e.end},
                       {"text", e.text},
                       {"line", e.line},
                       {"column", e.column},
                       {"end_line", e.end_line},
                       {"end_column", e.end_column}});
    text_ = session_->text();
    motion_.reset();
    sampler_.reset();
    for (auto& [k, r2] : renditions_) r2.renderer.reset();
    return {{"ok", true},
            {"edits", edits},
            {"text", text_},
            {"units", "bytes"},
            {"removed", r.removed}};
  }

  json Simulate(const json& id) {
    if (fault_ == "hang-on-simulate")
      for (;;) std::this_thread::sleep_for(std::chrono::hours(1));
    if (fault_ == "endless-progress-on-simulate") {
      for (double f = 0;; f = std::min(f + 1e-6, 0.99)) {
        Send({{"jsonrpc", "2.0"},
              {"method", "progress"},
              {"params", {{"id", id}, {"time", f}, {"fraction", f}}}});
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
    }
    motion_.reset();
    sampler_.reset();
    if (!session_) session_ = std::make_unique<session::Session>(text_, SessionOptions());
    auto last = std::chrono::steady_clock::now() - std::chrono::seconds(1);
    // The interval for the progress fraction, from the session's scene.
    const scene::Simulator simulator = session_->scene().simulator.value_or(scene::Simulator{});
    const double t0 = simulator.start, t1 = simulator.finish;
    auto progress = [&](double t) {
      const auto now = std::chrono::steady_clock::now();
      if (now - last < std::chrono::milliseconds(50)) return;
      last = now;
      const double f = t1 > t0 ? std::clamp((t - t0) / (t1 - t0), 0.0, 1.0) : 1.0;
      Send({{"jsonrpc", "2.0"},
            {"method", "progress"},
            {"params", {{"id", id}, {"time", t}, {"fraction", f}}}});
    };
    // A scene with errors is refused (the document shows its poster frame
    // and the errors) rather than animated in part.
    std::string message;
    for (const auto& d : session_->scene().diagnostics) {
      if (d.severity != scene::Severity::kError) continue;
      if (!message.empty()) message += "; ";
      message +=
          std::to_string(d.span.line) + ":" + std::to_string(d.span.column) + ": " + d.message;
    }
    const bool ok = message.empty() && session_->Simulate(progress);
    run_ = session_->run();
    if (!ok || !run_ || !run_->ok) {
      if (run_ && !run_->solver_error.empty())
        message += (message.empty() ? "" : "; ") + run_->solver_error;
      run_ = nullptr;
      throw RpcError{kSceneError, message.empty() ? "the scene could not be simulated" : message};
    }
    motion_.reset();  // it refers to the old sampler
    sampler_ =
        std::make_unique<render::SceneSampler>(run_->scene, *run_->equations, *run_->simulation);
    view_ = *sampler_->SceneView();
    motion_.emplace(*sampler_, sampler_->FindView());
    return {{"t0", sampler_->t0()},
            {"t1", sampler_->t1()},
            {"frame_rate", sampler_->frame_rate()},
            {"bodies", sampler_->bodies().size()},
            {"seconds", session_->last_stats().seconds},
            {"incremental", !session_->last_stats().rebuilt},
            {"components_reset", session_->last_stats().components_reset}};
  }

  json OpenRendition(const json& params) {
    Rendition r;
    const int id = static_cast<int>(Integer(params, "rendition", 0, kIntMax));
    constexpr int kMax = protocol::kMaxRenditionSide;
    r.width = static_cast<int>(Integer(params, "width", 1, kMax));
    r.height = static_cast<int>(Integer(params, "height", 1, kMax));
    r.offset =
        static_cast<size_t>(Integer(params, "offset", 0, std::numeric_limits<long long>::max()));
    const size_t bytes = static_cast<size_t>(r.width) * r.height * 4;
    if (!shm_ || r.offset > shm_size_ || bytes > shm_size_ - r.offset)
      throw RpcError{kInvalidParams, "invalid params: the rendition does not fit in shared memory"};
    renditions_[id] = std::move(r);
    return {{"ok", true}};
  }

  json Frame(const json& params) {
    const int id = static_cast<int>(Integer(params, "rendition", 0, kIntMax));
    auto it = renditions_.find(id);
    if (it == renditions_.end())
      throw RpcError{kInvalidParams, "invalid params: no rendition " + std::to_string(id)};
    if (!sampler_) throw RpcError{kNotSimulated, "the scene has not been simulated"};
    Rendition& r = it->second;
    if (fault_ == "exit-on-frame") std::_Exit(9);
    if (fault_ == "garbage-on-frame") {
      const char junk[] = "\x00\x00\x00\x05{{{{{";
      WriteAll(out_, junk, sizeof junk - 1);
      return nullptr;
    }
    const double t = std::clamp(Number(params, "t"), sampler_->t0(), sampler_->t1());
    const bool handles = Flag(params, "handles", r.handles);
    const bool wire = Flag(params, "wire", r.wire);
    render::FrameInput f;
    f.sampler = sampler_.get();
    f.t = t;
    f.poses = sampler_->Poses(t);
    // The scene's view as it is at t (-follow, -trajectory, expressions).
    const render::ViewState view = motion_ ? motion_->At(t) : view_;
    f.camera = render::MakeCamera(view, r.width, r.height);
    f.view_radius = view.radius / view.scale;
    render::Overlays overlays;
    overlays.handles = handles;
    render::Image image;
    if (wire) {
      image = render::RenderWire(f, overlays);
    } else {
      if (!r.renderer) r.renderer = std::make_unique<render::ShadedRenderer>(r.width, r.height);
      if (!r.renderer->ok())
        throw RpcError{kRenderError, "shaded rendering: " + r.renderer->error()};
      image = r.renderer->Render(*sampler_, f.poses, f.camera, sampler_->SceneLights());
      if (handles) render::OverlayImage(image, f, overlays);
    }
    uint8_t* dst = shm_ + r.offset;
    const size_t pixels = static_cast<size_t>(r.width) * r.height;
    for (size_t i = 0; i < pixels; ++i) {
      dst[4 * i] = image.rgb[3 * i];
      dst[4 * i + 1] = image.rgb[3 * i + 1];
      dst[4 * i + 2] = image.rgb[3 * i + 2];
      dst[4 * i + 3] = 255;
    }
    return {{"width", r.width},
            {"height", r.height},
            {"stride", r.width * 4},
            {"offset", r.offset},
            {"time", t}};
  }

  json Command(const std::string& line) {
    if (line == "handles on" || line == "handles off") {
      for (auto& [k, r] : renditions_) r.handles = line == "handles on";
      return {{"reply", "handles " + std::string(line == "handles on" ? "shown" : "hidden")}};
    }
    if (line == "info") {
      if (!sampler_) return {{"reply", "not simulated"}};
      std::string s;
      for (const auto& b : sampler_->bodies()) s += (s.empty() ? "" : " ") + b.name;
      return {{"reply", "bodies: " + s + "; t = " + std::to_string(sampler_->t0()) + " .. " +
                            std::to_string(sampler_->t1())}};
    }
    if (line == "ping") return {{"reply", "pong"}};
    // "player [RATE]": the meshes, poses and camera a page plays in WebGL.
    if (line == "player" || line.rfind("player ", 0) == 0) {
      if (!sampler_) throw RpcError{kSceneError, "not simulated"};
      double rate = 0;
      if (line.size() > 7) {
        char* end = nullptr;
        rate = std::strtod(line.c_str() + 7, &end);
        if (!end || *end != '\0' || !(rate > 0) || rate > 1000)
          throw RpcError{kInvalidParams, "player: the rate must be a number in (0, 1000]"};
      }
      return {
          {"reply",
           editor_rpc::PlayerData(*sampler_, view_, rate, motion_ ? &*motion_ : nullptr).dump()}};
    }
    throw RpcError{kInvalidParams, "unknown command '" + line +
                                       "' (known: handles on|off, info, ping, player [RATE])"};
  }

  int in_, out_;
  uint8_t* shm_;
  size_t shm_size_;
  std::string fault_;
  std::string text_;
  std::unique_ptr<session::Session> session_;
  const pipeline::Run* run_ = nullptr;  // the session's last run
  std::unique_ptr<render::SceneSampler> sampler_;
  render::ViewState view_;
  std::optional<render::ViewMotion> motion_;  // the scene's view over time (refers to sampler_)
  std::map<int, Rendition> renditions_;
};

bool ParseSize(const char* s, long long& out) {
  char* end = nullptr;
  out = std::strtoll(s, &end, 10);
  return end && *end == '\0' && out >= 0;
}

// False (errno set) when the limit cannot be set.
bool LimitMemory(long long mib) {
#ifdef ASGARD_SANITIZERS
  return true;  // the sanitizer's shadow memory alone is past any limit
#endif
  if (mib <= 0) return true;
  const rlim_t bytes = static_cast<rlim_t>(mib) << 20;
  struct rlimit r {};
  if (::getrlimit(RLIMIT_DATA, &r) != 0) return false;
  // Never above a hard limit the process already has.
  r.rlim_cur = r.rlim_max == RLIM_INFINITY ? bytes : std::min<rlim_t>(bytes, r.rlim_max);
  return ::setrlimit(RLIMIT_DATA, &r) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Scenes are evaluated on this thread, with nothing else running.
  asgard::lang::CapProcessMemoryDuringEvaluation(true);
  int in = STDIN_FILENO, out = STDOUT_FILENO;
  long long shm_fd = -1, shm_size = 0, memory_mib = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    long long v = 0;
    if (a == "-h" || a == "--help") {
      std::cout << kHelp;
      return 0;
    }
    if ((a == "--fd" || a == "--shm-fd" || a == "--shm-size" || a == "--memory") && i + 1 < argc &&
        ParseSize(argv[i + 1], v)) {
      ++i;
      if (a == "--fd")
        in = out = static_cast<int>(v);
      else if (a == "--shm-fd")
        shm_fd = v;
      else if (a == "--memory")
        memory_mib = v;
      else
        shm_size = v;
      continue;
    }
    std::cerr << "asgard-core: bad argument '" << a << "'\n\n" << kHelp;
    return 2;
  }
  if (!LimitMemory(memory_mib)) {
    std::cerr << "asgard-core: cannot limit memory to " << memory_mib
              << " MiB: " << std::strerror(errno) << "\n";
    return 2;
  }
  uint8_t* shm = nullptr;
  if (shm_fd >= 0 && shm_size > 0) {
    // Mapping past the end of the object would raise SIGBUS at the first
    // frame written there.
    struct stat st {};
    if (::fstat(static_cast<int>(shm_fd), &st) != 0) {
      std::cerr << "asgard-core: cannot use the shared frame memory (--shm-fd " << shm_fd
                << "): " << std::strerror(errno) << "\n";
      return 2;
    }
    if (st.st_size < shm_size) {
      std::cerr << "asgard-core: --shm-size " << shm_size
                << " is larger than the shared frame memory (" << st.st_size << " bytes)\n";
      return 2;
    }
    void* p = ::mmap(nullptr, static_cast<size_t>(shm_size), PROT_READ | PROT_WRITE, MAP_SHARED,
                     static_cast<int>(shm_fd), 0);
    if (p == MAP_FAILED) {
      std::cerr << "asgard-core: cannot map the shared frame memory: " << std::strerror(errno)
                << "\n";
      return 2;
    }
    shm = static_cast<uint8_t*>(p);
  }
  try {
    Slave slave(in, out, shm, static_cast<size_t>(shm_size));
    return slave.Loop();
  } catch (const std::bad_alloc&) {
    std::cerr << "asgard-core: out of memory\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "asgard-core: internal error: " << e.what() << "\n";
    return 3;
  }
}
