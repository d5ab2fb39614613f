// One asgard-core slave process and its control channel (seed 6.2.2).
//
//   plugin ── socketpair (SOCK_STREAM, CLOEXEC on our end) ──▶ slave fd 3
//          ── memfd "asgard-frames" (sparse, kFrameMemory bytes) ─▶ slave fd 4
//
// Messages are a 4-byte big-endian length and a JSON-RPC 2.0 object.  Call()
// sends one request and waits for its answer, handing progress notifications
// to a callback.  The watchdog is the poll() timeout: silence longer than
// `timeout` seconds (progress notifications reset it) kills the slave, and so
// does a call lasting longer than kOverallTimeoutFactor × `timeout` in all.  A dead
// slave (EOF, EPIPE — writes use MSG_NOSIGNAL so the host never gets SIGPIPE),
// a hung one, or a malformed message all end in a Failure status with a
// message; the process is then reaped and the object stays usable for
// questions (state, last message) but not for calls.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "core/protocol/protocol.h"

namespace asgard::medium {

// One frame of the largest rendition; virtual, pages are touched on use.
inline constexpr size_t kFrameMemory =
    size_t{protocol::kMaxRenditionSide} * protocol::kMaxRenditionSide * 4;
using protocol::kMaxMessage;

// The longest one call may take, in multiples of the watchdog timeout:
// progress notifications reset the watchdog but cannot extend this deadline,
// so a simulation that progresses forever is still stopped.
inline constexpr int kOverallTimeoutFactor = 4;

enum class CallStatus { kOk, kRemoteError, kDied, kTimeout, kProtocol, kNotRunning };

struct CallResult {
  CallStatus status = CallStatus::kOk;
  nlohmann::json result;  // kOk
  int remote_code = 0;    // kRemoteError: the JSON-RPC error code
  std::string message;    // anything but kOk
};

class SlaveProcess {
 public:
  // Starts `program --fd 3 --shm-fd 4 --shm-size N --memory MIB`.  On
  // failure running() is false and error() says why.
  SlaveProcess(const std::string& program, double timeout_seconds,
               int memory_mib = protocol::kDefaultSlaveMemoryMiB);
  ~SlaveProcess();  // asks politely (shutdown), then SIGKILL, then reaps
  SlaveProcess(const SlaveProcess&) = delete;
  SlaveProcess& operator=(const SlaveProcess&) = delete;

  bool running() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }
  const std::string& error() const { return error_; }
  uint8_t* frame_memory() const { return shm_; }

  using Progress = std::function<void(double fraction, double time)>;
  CallResult Call(const std::string& method, const nlohmann::json& params,
                  const Progress& progress = nullptr);

  // Kills and reaps the process (when running) and records why.
  void Kill(const std::string& why);

 private:
  bool Send(const std::string& bytes);
  // Reads exactly n bytes before the deadline; 1 ok, 0 EOF/error, -1 timeout.
  int ReadExact(char* buf, size_t n, int64_t deadline_ms);
  std::string Reap();  // waits for the process; describes how it ended

  pid_t pid_ = -1;
  int fd_ = -1;
  int shm_fd_ = -1;
  uint8_t* shm_ = nullptr;
  double timeout_;
  int64_t next_id_ = 1;
  std::string program_;
  std::string error_;
};

}  // namespace asgard::medium
