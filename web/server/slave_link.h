// One asgard-core slave for the editor server: started with a socketpair on
// fd 3, spoken to in the framing of core/protocol (a 4-byte big-endian length,
// then a JSON-RPC 2.0 object).  Calls block; the server makes them from one
// worker thread per animation.  A slave that dies or sends garbage is killed
// and reaped; the next Call() starts a new one (the caller reloads the text).
#pragma once

#include <sys/types.h>

#include <nlohmann/json.hpp>
#include <string>
#include <utility>

namespace asgard::serve {

struct SlaveAnswer {
  bool ok = false;        // a result came back
  bool died = false;      // the slave died or broke the protocol
  nlohmann::json result;  // when ok
  std::string error;      // otherwise
};

// Where an animation's editor requests go: an asgard-core of the server's
// own (SlaveLink), or the slave of the host's medium node that also draws
// the animation's renditions (dochost serve, host-shim/serve_host.h).  Called
// from the animation's worker thread only.
class SlaveChannel {
 public:
  virtual ~SlaveChannel() = default;
  // A slave runs and holds the text last loaded through this channel.
  virtual bool running() const = 0;
  // One request; a slave that is not running is started first.
  virtual SlaveAnswer Call(const std::string& method, const nlohmann::json& params) = 0;
};

class SlaveLink : public SlaveChannel {
 public:
  explicit SlaveLink(std::string program) : program_(std::move(program)) {}
  ~SlaveLink() override;
  SlaveLink(const SlaveLink&) = delete;
  SlaveLink& operator=(const SlaveLink&) = delete;

  bool running() const override { return pid_ > 0; }
  // Starts the slave when none runs; false (with error()) when it cannot.
  bool Start();
  SlaveAnswer Call(const std::string& method, const nlohmann::json& params) override;
  void Stop();
  const std::string& error() const { return error_; }

 private:
  pid_t pid_ = -1;
  int fd_ = -1;
  long next_id_ = 1;
  std::string program_;
  std::string error_;
};

}  // namespace asgard::serve
