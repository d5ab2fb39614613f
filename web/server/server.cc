// The editor server (see server.h): Boost.Beast over Boost.Asio, one I/O
// thread; slave calls happen on one worker thread per animation and their
// results are posted back to the I/O thread, which alone touches sockets.
#include "web/server/server.h"

// Boost 1.74's asio uses std::exchange without including <utility> (C++20).
#include <utility>
// clang-format off
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
// clang-format on
#include <array>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "web/server/movie.h"
#include "web/server/slave_link.h"

namespace asgard::serve {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using nlohmann::json;

bool IsLoopbackPeer(const std::string& address) {
  boost::system::error_code ec;
  const auto a = net::ip::make_address(address, ec);
  if (ec) return false;
  if (a.is_v6() && a.to_v6().is_v4_mapped())
    return net::ip::make_address_v4(net::ip::v4_mapped, a.to_v6()).is_loopback();
  return a.is_loopback();
}

bool IsOwnOrigin(const std::string& origin, const std::string& host, int port) {
  const std::string p = ":" + std::to_string(port);
  const bool host_ok = host == "127.0.0.1" + p || host == "localhost" + p;
  if (!host_ok) return false;
  // Browsers always send Origin on a WebSocket upgrade; tools may not.
  return origin.empty() || origin == "http://127.0.0.1" + p || origin == "http://localhost" + p;
}

std::string HtmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

namespace {

class WsSession;

// One animation: its slave, the last good scene, its views.
class Hub {
 public:
  Hub(net::io_context& io, Animation a, std::string core, std::string render, size_t index)
      : io_(io),
        def_(std::move(a)),
        text_(def_.text),
        slave_(def_.channel ? def_.channel : std::make_shared<SlaveLink>(std::move(core))),
        render_(std::move(render)),
        index_(index) {
    worker_ = std::thread([this] { Work(); });
  }
  ~Hub() {
    {
      std::lock_guard lock(mu_);
      stop_ = true;
    }
    cv_.notify_one();
    worker_.join();
  }
  const Animation& def() const { return def_; }

  // I/O thread only.
  void Join(const std::shared_ptr<WsSession>& s) { views_.insert(s); }
  void Leave(const std::shared_ptr<WsSession>& s) { views_.erase(s); }
  void Request(const std::shared_ptr<WsSession>& from, json request);

  // An export made for download (any thread): its name and bytes.
  struct Download {
    std::string name, type, bytes;
  };
  // The rendition at time t for the document view, drawn on the worker
  // (after this animation's pending requests); `done` runs on the I/O thread.
  void Render(double t, bool handles, std::function<void(RenditionFrame)> done) {
    Post([this, t, handles, done = std::move(done)] {
      RenditionFrame f;
      try {
        f = def_.rendition(t, handles);
      } catch (const std::exception& e) {
        f.status = e.what();
      }
      net::post(io_, [done, f = std::move(f)]() mutable { done(std::move(f)); });
    });
  }

  std::optional<Download> TakeDownload(long id) {
    std::lock_guard lock(downloads_mu_);
    const auto it = downloads_.find(id);
    if (it == downloads_.end()) return std::nullopt;
    return it->second;
  }

 private:
  json Movie(const json& params);

  void Post(std::function<void()> job) {
    {
      std::lock_guard lock(mu_);
      jobs_.push_back(std::move(job));
    }
    cv_.notify_one();
  }
  void Work() {
    for (;;) {
      std::function<void()> job;
      {
        std::unique_lock lock(mu_);
        cv_.wait(lock, [&] { return stop_ || !jobs_.empty(); });
        if (stop_) return;
        job = std::move(jobs_.front());
        jobs_.pop_front();
      }
      job();
    }
  }
  // Worker thread: make sure the slave runs with the current text; false
  // with the failed `load`'s answer.
  bool Ensure(SlaveAnswer* failed);
  // Worker thread: one request, restarting a dead slave once.
  SlaveAnswer Ask(const std::string& method, const json& params);
  json Call(const std::string& method, const json& params);
  // Worker thread: the session's undo history as known here.  A change the
  // session recorded (its text, and the parameter a drag edits: the steps of
  // one drag are one entry, as core/session makes them), and an undo or
  // redo that was done.
  void Record(const std::string& key);
  void Moved(int by);
  // Worker thread: simulate and fetch the motion; updates the last good scene.
  json Resimulate();
  json Open();
  json Handle(const std::string& method, const json& params,
              const std::shared_ptr<WsSession>& from);
  void Broadcast(json event);  // from the worker: posted to the I/O thread
  void Reply(const std::shared_ptr<WsSession>& to, json message);

  net::io_context& io_;
  Animation def_;
  std::string text_;  // the session's text as last known here (survives a slave crash)
  // The session's undo history as texts, history_[history_at_] == text_,
  // and the parameter of the drag whose step is open (docs/editor-server.md,
  // "Restarts"): a restarted slave is loaded with each text in turn and
  // undone back to history_at_, so undo and redo survive it.
  std::vector<std::string> history_;
  size_t history_at_ = 0;
  std::string open_key_;
  std::shared_ptr<SlaveChannel> slave_;
  bool loaded_ = false;
  json meshes_, poses_;  // the last good scene
  std::string sim_error_;
  // Graphical edits changed the text since the views last got a `state`
  // (their parameters' spans and values are stale until the drag ends).
  bool state_stale_ = false;
  std::set<std::shared_ptr<WsSession>> views_;
  std::string render_;  // the asgard CLI
  size_t index_;        // this animation's number (?a=N)
  std::mutex downloads_mu_;
  std::map<long, Download> downloads_;  // the newest few exports
  long next_download_ = 1;
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::function<void()>> jobs_;
  bool stop_ = false;
  std::thread worker_;
};

class WsSession : public std::enable_shared_from_this<WsSession> {
 public:
  WsSession(tcp::socket socket, Hub& hub, size_t max_message) : ws_(std::move(socket)), hub_(hub) {
    ws_.read_message_max(max_message);
  }
  void Run(http::request<http::string_body> req) {
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.async_accept(req, [self = shared_from_this()](beast::error_code ec) {
      if (ec) return;
      self->hub_.Join(self);
      self->Read();
    });
  }
  void Send(std::shared_ptr<const std::string> text) {
    queue_.push_back(std::move(text));
    if (queue_.size() == 1) Write();
  }

 private:
  void Read() {
    ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code ec, size_t) {
      if (ec) {  // closed, or a message beyond the limit (closed with 1009)
        self->hub_.Leave(self);
        return;
      }
      std::string text = beast::buffers_to_string(self->buffer_.data());
      self->buffer_.consume(self->buffer_.size());
      json request = json::parse(text, nullptr, false);
      if (request.is_discarded() || !request.is_object() || !request.contains("method") ||
          !request["method"].is_string() ||
          (request.contains("params") && !request["params"].is_object())) {
        const json id = !request.is_discarded() && request.is_object() && request.contains("id")
                            ? request["id"]
                            : json();
        self->Send(std::make_shared<const std::string>(
            json{{"id", id},
                 {"error",
                  {{"code", request.is_discarded() ? -32700 : -32600},
                   {"message", request.is_discarded()
                                   ? "parse error: the message is not JSON"
                                   : "invalid request: expected {id, method, params}"}}}}
                .dump(-1, ' ', false, json::error_handler_t::replace)));
      } else {
        self->hub_.Request(self, std::move(request));
      }
      self->Read();
    });
  }
  void Write() {
    ws_.text(true);
    ws_.async_write(net::buffer(*queue_.front()),
                    [self = shared_from_this()](beast::error_code ec, size_t) {
                      if (ec) {
                        self->queue_.clear();
                        return;
                      }
                      self->queue_.pop_front();
                      if (!self->queue_.empty()) self->Write();
                    });
  }

  websocket::stream<beast::tcp_stream> ws_;
  beast::flat_buffer buffer_;
  Hub& hub_;
  std::deque<std::shared_ptr<const std::string>> queue_;
};

void Hub::Request(const std::shared_ptr<WsSession>& from, json request) {
  Post([this, from, request = std::move(request)] {
    const json id = request.value("id", json());
    const std::string method = request["method"];
    const json params = request.value("params", json::object());
    json answer;
    try {
      answer = {{"id", id}, {"result", Handle(method, params, from)}};
    } catch (const std::exception& e) {
      answer = {{"id", id}, {"error", {{"code", -32602}, {"message", e.what()}}}};
    }
    Reply(from, std::move(answer));
  });
}

void Hub::Reply(const std::shared_ptr<WsSession>& to, json message) {
  auto s = std::make_shared<const std::string>(
      message.dump(-1, ' ', false, json::error_handler_t::replace));
  net::post(io_, [to, s] { to->Send(s); });
}

void Hub::Broadcast(json event) {
  auto s = std::make_shared<const std::string>(
      event.dump(-1, ' ', false, json::error_handler_t::replace));
  net::post(io_, [this, s] {
    for (const auto& v : views_) v->Send(s);
  });
}

// At most this many texts of the history are kept for a restart (the
// oldest steps are dropped first).
constexpr size_t kMaxHistory = 100;

bool Hub::Ensure(SlaveAnswer* failed) {
  if (slave_->running() && loaded_) return true;
  loaded_ = false;
  // A new slave's session gets the history known here: each text loaded in
  // turn (every load is one step), then undone back to the current one.
  // Without a history that ends in the current text (none yet, or it went
  // out of step with the slave's), the current text alone.
  if (history_.empty() || history_at_ >= history_.size() || history_[history_at_] != text_) {
    history_.assign(1, text_);
    history_at_ = 0;
  }
  open_key_.clear();
  for (const std::string& text : history_) {
    SlaveAnswer a = slave_->Call("load", {{"text", text}});
    if (!a.ok) {
      *failed = std::move(a);
      return false;
    }
  }
  for (size_t k = history_.size() - 1; k > history_at_; --k) {
    SlaveAnswer a = slave_->Call("undo", json::object());
    if (!a.ok) {
      *failed = std::move(a);
      return false;
    }
  }
  loaded_ = true;
  return true;
}

void Hub::Record(const std::string& key) {
  const bool same_drag =
      !key.empty() && key == open_key_ && history_at_ > 0 && history_at_ + 1 == history_.size();
  if (same_drag) {
    history_[history_at_] = text_;
  } else {
    history_.resize(std::min(history_at_ + 1, history_.size()));
    history_.push_back(text_);
    history_at_ = history_.size() - 1;
    if (history_.size() > kMaxHistory) {
      history_.erase(history_.begin());
      --history_at_;
    }
  }
  open_key_ = key;
}

void Hub::Moved(int by) {
  open_key_.clear();
  const long at = static_cast<long>(history_at_) + by;
  if (at >= 0 && at < static_cast<long>(history_.size()) && history_[at] == text_) {
    history_at_ = static_cast<size_t>(at);
    return;
  }
  // Out of step (the oldest steps were dropped, or the slave changed
  // without this server): from here on, the current text.
  history_.assign(1, text_);
  history_at_ = 0;
}

SlaveAnswer Hub::Ask(const std::string& method, const json& params) {
  SlaveAnswer a;
  // A slave found dead is restarted once, loaded with the last text known
  // here (edits not yet simulated included), and asked again; only when
  // that fails too do the views hear why.
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (Ensure(&a)) a = slave_->Call(method, params);
    if (!a.died) return a;
    loaded_ = false;
  }
  Broadcast({{"event", "error"}, {"message", a.error}});
  return a;
}

json Hub::Call(const std::string& method, const json& params) {
  const SlaveAnswer a = Ask(method, params);
  if (!a.ok) throw std::runtime_error(a.error);
  return a.result;
}

json Hub::Resimulate() {
  open_key_.clear();  // a simulation ends a drag's step
  const SlaveAnswer sim = Ask("simulate", json::object());
  if (!sim.ok) {
    sim_error_ = sim.error;
    return {{"ok", false}, {"error", sim.error}};
  }
  sim_error_.clear();
  meshes_ = Call("meshes", json::object());
  poses_ = Call("poses", json::object());
  return {{"ok", true}, {"stats", sim.result}};
}

json Hub::Open() {
  if (meshes_.is_null() || !loaded_) Resimulate();
  json state = Call("scene_state", json::object());
  return {{"title", def_.title},
          {"state", state},
          {"meshes", meshes_},
          {"poses", poses_},
          {"sim_error", sim_error_}};
}

json Hub::Handle(const std::string& method, const json& params,
                 const std::shared_ptr<WsSession>& from) {
  const auto after_text_change = [&](const json& changes) {
    json state = Call("scene_state", json::object());
    state_stale_ = false;
    text_ = state.value("text", text_);
    bool errors = false;
    for (const auto& d : state["diagnostics"]) errors |= d.value("severity", "") == "error";
    json sim = errors ? json{{"ok", false}, {"error", "the scene has errors"}} : Resimulate();
    Broadcast({{"event", "state"}, {"state", state}, {"changes", changes}});
    if (sim.value("ok", false))
      Broadcast({{"event", "scene"}, {"meshes", meshes_}, {"poses", poses_}});
    return json{{"state", state}, {"simulated", sim}};
  };
  if (method == "open") return Open();
  // Members a request must have are looked up (and a missing one thrown)
  // before any braced list is built: an exception from inside one, while
  // its elements were being made, read them after their scope under GCC 12
  // (AddressSanitizer's stack-use-after-scope on a create without a command).
  if (method == "set_parameter") {
    // Numbers, or a braced word's whole text (the shape editor's -desc).
    const json& element = params.at("element");
    const json& param = params.at("param");
    const bool word = params.contains("text");
    const json values = word ? json() : params.at("values");
    json r =
        Call("edit", word ? json{{"element", element}, {"param", param}, {"text", params["text"]}}
                          : json{{"element", element}, {"param", param}, {"values", values}});
    text_ = r.value("text", text_);
    state_stale_ = true;
    Record(element.dump() + '\0' + param.dump());
    Broadcast({{"event", "text"},
               {"text", text_},
               {"edits", r["edits"]},
               {"element", element},
               {"param", param},
               {"values", values},
               {"word", word ? params["text"] : json()},
               {"view", params.value("view", "")}});
    return r;
  }
  if (method == "create" || method == "delete") {
    // A new element's command (or one removed) through the session, so
    // that undo covers it; then as an update.
    const std::string key = method == "create" ? "command" : "element";
    const json& arg = params.at(key);
    json r = Call(method, {{key, arg}});
    json out = after_text_change(json::array());
    Record("");
    out["edits"] = r["edits"];
    if (method == "delete") out["removed"] = r.value("removed", json::array());
    return out;
  }
  if (method == "update") {
    if (!params.contains("text") || !params["text"].is_string())
      throw std::runtime_error("update needs a text");
    json loaded = Call("load", {{"text", params["text"]}});
    json out = after_text_change(loaded.value("changes", json::array()));
    Record("");
    return out;
  }
  if (method == "simulate") {
    json sim = Resimulate();
    // The new motion first (a drag's end waits for it; the views already
    // have the dragged values from its `text` events), then, after graphical
    // edits, fresh parameters for every view.
    if (sim.value("ok", false))
      Broadcast({{"event", "scene"}, {"meshes", meshes_}, {"poses", poses_}});
    if (state_stale_) {
      state_stale_ = false;
      Broadcast({{"event", "state"},
                 {"state", Call("scene_state", json::object())},
                 {"changes", json::array()}});
    }
    return sim;
  }
  if (method == "undo" || method == "redo") {
    json r = Call(method, json::object());
    json out = after_text_change(json::array());
    out["done"] = r.value("ok", false);
    if (out["done"].get<bool>()) Moved(method == "undo" ? -1 : 1);
    return out;
  }
  if (method == "movie") return Movie(params);
  if (method == "save") {
    std::string error;
    if (!def_.save) throw std::runtime_error("this animation cannot be saved");
    if (!def_.save(text_, &error)) throw std::runtime_error(error);
    Broadcast({{"event", "saved"}});
    return {{"ok", true}};
  }
  (void)from;
  throw std::runtime_error("unknown method '" + method + "'");
}

// The movie export (control panel): the current text through `asgard
// render`, kept for one download.  Runs on the worker, so this animation's
// other requests wait for it (about a second for the pendulum).
json Hub::Movie(const json& params) {
  MovieRequest r;
  r.format = params.value("format", "mp4");
  const auto integer = [&](const char* key, int fallback) {
    if (!params.contains(key)) return fallback;
    const json& v = params[key];
    if (!v.is_number_integer() || v.get<int>() < 16 || v.get<int>() > 4096)
      throw std::runtime_error(std::string("movie: ") + key +
                               " must be a whole number of pixels from 16 to 4096");
    return v.get<int>();
  };
  r.width = integer("width", 640) / 2 * 2;  // H.264 wants even sizes
  r.height = integer("height", 480) / 2 * 2;
  const auto triple = [&](const char* key) -> std::optional<std::array<double, 3>> {
    if (!params.contains(key)) return std::nullopt;
    const json& v = params[key];
    if (!v.is_array() || v.size() != 3)
      throw std::runtime_error(std::string("movie: ") + key + " must be three numbers");
    std::array<double, 3> a{};
    for (size_t k = 0; k < 3; ++k) {
      if (!v[k].is_number() || !std::isfinite(v[k].get<double>()))
        throw std::runtime_error(std::string("movie: ") + key + " must be three numbers");
      a[k] = v[k].get<double>();
    }
    return a;
  };
  r.rot_degrees = triple("rot");
  r.center = triple("center");
  r.pan = triple("pan");
  if (params.contains("scale")) {
    const json& v = params["scale"];
    if (!v.is_number() || !(v.get<double>() > 0) || !std::isfinite(v.get<double>()))
      throw std::runtime_error("movie: scale must be a positive number");
    r.scale = v.get<double>();
  }
  r.view = params.value("view", "");
  if (!r.view.empty() && (r.view[0] == '-' || r.view.find('\0') != std::string::npos))
    throw std::runtime_error("movie: bad view name");
  std::string bytes, error;
  if (!RenderMovie(render_, text_, r, &bytes, &error)) throw std::runtime_error(error);
  const size_t size = bytes.size();
  long id = 0;
  {
    std::lock_guard lock(downloads_mu_);
    id = next_download_++;
    const std::string type = r.format == "gif" ? "image/gif" : "video/" + r.format;
    downloads_[id] = {"scene." + r.format, type, std::move(bytes)};
    while (downloads_.size() > 3) downloads_.erase(downloads_.begin());
  }
  return {{"url", "/download?a=" + std::to_string(index_) + "&id=" + std::to_string(id)},
          {"name", "scene." + r.format},
          {"bytes", size}};
}

std::string ReadFile(const std::string& path, bool* ok) {
  std::ifstream in(path, std::ios::binary);
  *ok = static_cast<bool>(in);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class Server;

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket socket, Server& server) : stream_(std::move(socket)), server_(server) {}
  void Run() { Read(); }

 private:
  void Read();
  void OnRequest();
  void Respond(http::status status, const std::string& type, std::string body,
               const std::string& attachment = "",
               const std::vector<std::pair<std::string, std::string>>& headers = {});

  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  Server& server_;
};

class Server {
 public:
  Server(const Options& o, std::vector<Animation> animations) : options_(o), acceptor_(io_) {
    for (auto& a : animations)
      hubs_.push_back(
          std::make_unique<Hub>(io_, std::move(a), o.core_program, o.render_program, hubs_.size()));
  }
  int Run() {
    beast::error_code ec;
    const auto address = net::ip::make_address(options_.bind, ec);
    if (ec) {
      std::cerr << "serve: bad address " << options_.bind << "\n";
      return 2;
    }
    tcp::endpoint ep(address, static_cast<unsigned short>(options_.port));
    acceptor_.open(ep.protocol(), ec);
    if (!ec) acceptor_.set_option(net::socket_base::reuse_address(true), ec);
    if (!ec) acceptor_.bind(ep, ec);
    if (!ec) acceptor_.listen(net::socket_base::max_listen_connections, ec);
    if (ec) {
      std::cerr << "serve: cannot listen on " << options_.bind << ":" << options_.port << ": "
                << ec.message() << "\n";
      return 1;
    }
    port_ = acceptor_.local_endpoint().port();
    if (options_.on_listening) options_.on_listening(port_);
    Accept();
    io_.run();
    return 0;
  }

  const Options& options() const { return options_; }
  int port() const { return port_; }
  Hub* hub(size_t i) { return i < hubs_.size() ? hubs_[i].get() : nullptr; }
  size_t hubs() const { return hubs_.size(); }

 private:
  void Accept() {
    acceptor_.async_accept(net::make_strand(io_), [this](beast::error_code ec, tcp::socket s) {
      if (!ec) {
        beast::error_code pe;
        const auto peer = s.remote_endpoint(pe);
        if (!pe && IsLoopbackPeer(peer.address().to_string())) {
          // Small messages leave at once: without this, an event and the
          // answer written after it wait for the peer's delayed ACK (Nagle),
          // about 40 ms a drag step.
          s.set_option(tcp::no_delay(true), pe);
          std::make_shared<HttpSession>(std::move(s), *this)->Run();
        } else {
          std::cerr << "serve: refused a connection from "
                    << (pe ? std::string("an unknown peer") : peer.address().to_string()) << "\n";
          s.close(pe);
        }
      }
      Accept();
    });
  }

  Options options_;
  net::io_context io_{1};
  tcp::acceptor acceptor_;
  std::vector<std::unique_ptr<Hub>> hubs_;
  int port_ = 0;
};

void HttpSession::Read() {
  parser_.emplace();
  parser_->header_limit(16 * 1024);
  parser_->body_limit(64 * 1024);
  stream_.expires_after(std::chrono::seconds(60));
  http::async_read(stream_, buffer_, *parser_,
                   [self = shared_from_this()](beast::error_code ec, size_t) {
                     if (ec == http::error::end_of_stream || ec == beast::error::timeout) {
                       beast::error_code e;
                       self->stream_.socket().shutdown(tcp::socket::shutdown_both, e);
                       return;
                     }
                     if (ec) {  // malformed or oversized: answer 400 and close
                       self->Respond(http::status::bad_request, "text/plain",
                                     "bad request: " + ec.message() + "\n");
                       return;
                     }
                     self->OnRequest();
                   });
}

// The animation index in "?a=N" (0 when absent); -1 when malformed.
long AnimationIndex(const std::string& target) {
  const auto q = target.find("a=");
  if (q == std::string::npos) return 0;
  try {
    size_t used = 0;
    const long n = std::stol(target.substr(q + 2), &used);
    return n < 0 ? -1 : n;
  } catch (...) {
    return -1;
  }
}

// The value of `key` in the target's query ("" when absent).
std::string QueryValue(const std::string& target, const std::string& key) {
  const size_t q = target.find('?');
  if (q == std::string::npos) return "";
  size_t at = q + 1;
  while (at < target.size()) {
    const size_t amp = std::min(target.find('&', at), target.size());
    const std::string pair = target.substr(at, amp - at);
    if (pair.compare(0, key.size() + 1, key + "=") == 0) return pair.substr(key.size() + 1);
    at = amp + 1;
  }
  return "";
}

void HttpSession::OnRequest() {
  auto req = parser_->release();
  const std::string target(req.target());
  const std::string path = target.substr(0, target.find('?'));
  const Options& o = server_.options();
  if (websocket::is_upgrade(req)) {
    const std::string origin(req[http::field::origin]);
    const std::string host(req[http::field::host]);
    if (path != "/ws") return Respond(http::status::not_found, "text/plain", "not found\n");
    if (!IsOwnOrigin(origin, host, server_.port())) {
      std::cerr << "serve: refused a WebSocket upgrade from origin '" << origin << "'\n";
      return Respond(http::status::forbidden, "text/plain", "forbidden: foreign origin\n");
    }
    const long i = AnimationIndex(target);
    Hub* hub = i < 0 ? nullptr : server_.hub(static_cast<size_t>(i));
    if (!hub) return Respond(http::status::not_found, "text/plain", "no such animation\n");
    std::make_shared<WsSession>(stream_.release_socket(), *hub, o.max_message)->Run(std::move(req));
    return;
  }
  const std::string host(req[http::field::host]);
  if (!IsOwnOrigin("", host, server_.port()))
    return Respond(http::status::forbidden, "text/plain", "forbidden: unknown host\n");
  if (req.method() != http::verb::get && req.method() != http::verb::head)
    return Respond(http::status::method_not_allowed, "text/plain", "only GET\n");
  bool ok = false;
  if (path == "/editor.js" || path == "/document.js" || path == "/handles.js") {
    std::string js = ReadFile(o.web_root + path, &ok);
    if (!ok)
      return Respond(http::status::not_found, "text/plain",
                     "the browser bundle was not built (web/, needs node)\n");
    return Respond(http::status::ok, "text/javascript; charset=utf-8", std::move(js));
  }
  if (path == "/editor.css") {
    std::string css = ReadFile(o.web_root + "/editor.css", &ok);
    return Respond(ok ? http::status::ok : http::status::not_found, "text/css", std::move(css));
  }
  if (path == "/download") {
    const long i = AnimationIndex(target);
    Hub* hub = i < 0 ? nullptr : server_.hub(static_cast<size_t>(i));
    const auto q = target.find("id=");
    const long id = q == std::string::npos ? -1 : std::strtol(target.c_str() + q + 3, nullptr, 10);
    const auto d = hub ? hub->TakeDownload(id) : std::nullopt;
    if (!d) return Respond(http::status::not_found, "text/plain", "no such download\n");
    return Respond(http::status::ok, d->type, d->bytes, d->name);
  }
  if (path == "/page") {
    const std::string n = QueryValue(target, "n");
    char* end = nullptr;
    const long k = std::strtol(n.c_str(), &end, 10);
    if (n.empty() || *end != '\0' || k < 0 || static_cast<size_t>(k) >= o.page_count ||
        !o.page_picture)
      return Respond(http::status::not_found, "text/plain", "no such page\n");
    std::string png = o.page_picture(static_cast<size_t>(k));
    if (png.empty())
      return Respond(http::status::internal_server_error, "text/plain",
                     "the page cannot be drawn\n");
    return Respond(http::status::ok, "image/png", std::move(png));
  }
  if (path == "/frame") {
    const long i = AnimationIndex(target);
    Hub* hub = i < 0 ? nullptr : server_.hub(static_cast<size_t>(i));
    if (!hub || !hub->def().rendition)
      return Respond(http::status::not_found, "text/plain", "no rendition of that animation\n");
    const std::string t = QueryValue(target, "t");
    char* end = nullptr;
    const double time = std::strtod(t.c_str(), &end);
    if (t.empty() || *end != '\0' || !std::isfinite(time))
      return Respond(http::status::bad_request, "text/plain", "frame: t must be a number\n");
    hub->Render(time, QueryValue(target, "handles") == "1",
                [self = shared_from_this()](RenditionFrame f) {
                  char interval[64];
                  std::snprintf(interval, sizeof interval, "%.17g %.17g", f.t0, f.t1);
                  const std::vector<std::pair<std::string, std::string>> headers = {
                      {"X-Asgard-Status", f.status},
                      {"X-Asgard-Interval", interval},
                      {"X-Asgard-Live", f.live ? "1" : "0"}};
                  if (f.png.empty())
                    return self->Respond(http::status::service_unavailable, "text/plain",
                                         "no picture: " + f.status + "\n", "", headers);
                  self->Respond(http::status::ok, "image/png", std::move(f.png), "", headers);
                });
    return;
  }
  if (path == "/edit" || (path == "/" && o.document_html.empty())) {
    const long i = AnimationIndex(target);
    if (i < 0 || !server_.hub(static_cast<size_t>(i)))
      return Respond(http::status::not_found, "text/plain", "no such animation\n");
    std::string page = ReadFile(o.web_root + "/index.html", &ok);
    if (!ok) return Respond(http::status::not_found, "text/plain", "index.html is missing\n");
    return Respond(http::status::ok, "text/html; charset=utf-8", std::move(page));
  }
  if (path == "/") {
    std::string page = "<!doctype html><html><head><meta charset=utf-8><title>" +
                       HtmlEscape(o.document_title) + "</title></head><body>\n" + o.document_html;
    page += "<h2>Animations</h2><ul>";
    for (size_t i = 0; i < server_.hubs(); ++i)
      page += "<li><a href=\"/edit?a=" + std::to_string(i) + "\">" +
              HtmlEscape(server_.hub(i)->def().title) + "</a></li>";
    page += "</ul></body></html>\n";
    return Respond(http::status::ok, "text/html; charset=utf-8", std::move(page));
  }
  Respond(http::status::not_found, "text/plain", "not found\n");
}

void HttpSession::Respond(http::status status, const std::string& type, std::string body,
                          const std::string& attachment,
                          const std::vector<std::pair<std::string, std::string>>& headers) {
  auto res = std::make_shared<http::response<http::string_body>>(status, 11);
  for (const auto& [name, value] : headers) {
    std::string v = value;  // one line: a slave's message may hold anything
    for (char& c : v)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
    res->set(name, v);
  }
  if (!attachment.empty())
    res->set(http::field::content_disposition, "attachment; filename=\"" + attachment + "\"");
  res->set(http::field::server, "asgard");
  res->set(http::field::content_type, type);
  res->set(http::field::cache_control, "no-store");
  res->set("X-Content-Type-Options", "nosniff");
  res->keep_alive(status == http::status::ok);
  res->body() = std::move(body);
  res->prepare_payload();
  http::async_write(stream_, *res, [self = shared_from_this(), res](beast::error_code ec, size_t) {
    if (ec || !res->keep_alive()) {
      beast::error_code e;
      self->stream_.socket().shutdown(tcp::socket::shutdown_both, e);
      return;
    }
    self->Read();
  });
}

}  // namespace

int Serve(const Options& options, std::vector<Animation> animations) {
  if (animations.empty()) {
    std::cerr << "serve: the document has no animation to edit\n";
    return 1;
  }
  Server server(options, std::move(animations));
  return server.Run();
}

}  // namespace asgard::serve
