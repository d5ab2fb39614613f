// One asgard-core slave for the editor server: started with a socketpair on
// fd 3, spoken to in the framing of core/protocol (a 4-byte big-endian length,
// then a JSON-RPC 2.0 object).  Calls block; the server makes them from one
// worker thread per animation.  A slave that dies or sends garbage is killed
// and reaped; the next Call() starts a new one (the caller reloads the text).
#pragma once

#include <sys/types.h>

#include <nlohmann/json.hpp>
#include <string>

namespace asgard::serve {

struct SlaveAnswer {
  bool ok = false;        // a result came back
  bool died = false;      // the slave died or broke the protocol
  nlohmann::json result;  // when ok
  std::string error;      // otherwise
};

class SlaveLink {
 public:
  explicit SlaveLink(std::string program) : program_(std::move(program)) {}
  ~SlaveLink();
  SlaveLink(const SlaveLink&) = delete;
  SlaveLink& operator=(const SlaveLink&) = delete;

  bool running() const { return pid_ > 0; }
  // Starts the slave when none runs; false (with error()) when it cannot.
  bool Start();
  SlaveAnswer Call(const std::string& method, const nlohmann::json& params);
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
