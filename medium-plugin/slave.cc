// The slave process: spawning, framing, the watchdog, and how it ends.
//
// Design: posix_spawn with two dup2 actions (the socket to fd 3, the frame
// memory to fd 4); every descriptor of ours is close-on-exec, so a slave never
// inherits another slave's channel (which would hide that slave's death from
// us).  Reads poll against an absolute deadline that progress notifications
// push forward; any failure reaps the child so no zombie is left, and the
// exit status becomes the message ("killed by signal 9").
#include "medium-plugin/slave.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

extern char** environ;

namespace asgard::medium {

using nlohmann::json;

namespace {

int64_t NowMs() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1000 + ts.tv_nsec / 1000000;
}

// Moves a descriptor above the range the slave's dup2 targets use.
int HighCloexec(int fd) {
  if (fd < 0) return fd;
  const int high = fcntl(fd, F_DUPFD_CLOEXEC, 10);
  ::close(fd);
  return high;
}

std::string Seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", s);
  return buf;
}

}  // namespace

SlaveProcess::SlaveProcess(const std::string& program, double timeout_seconds, int memory_mib)
    : timeout_(timeout_seconds), program_(program) {
  int sv[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0) {
    error_ = std::string("cannot create the control channel: ") + std::strerror(errno);
    return;
  }
  fd_ = HighCloexec(sv[0]);
  const int child_fd = HighCloexec(sv[1]);
  shm_fd_ = HighCloexec(memfd_create("asgard-frames", MFD_CLOEXEC));
  void* map = MAP_FAILED;
  if (shm_fd_ >= 0 && ::ftruncate(shm_fd_, static_cast<off_t>(kFrameMemory)) == 0)
    map = ::mmap(nullptr, kFrameMemory, PROT_READ | PROT_WRITE, MAP_SHARED, shm_fd_, 0);
  if (map == MAP_FAILED) {
    error_ = std::string("cannot create shared frame memory: ") + std::strerror(errno);
    ::close(child_fd);
    return;
  }
  shm_ = static_cast<uint8_t*>(map);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, child_fd, 3);
  posix_spawn_file_actions_adddup2(&actions, shm_fd_, 4);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  const std::string size = std::to_string(kFrameMemory);
  std::vector<std::string> args = {program_,   "--fd",     "3",
                                   "--shm-fd", "4",        "--shm-size",
                                   size,       "--memory", std::to_string(memory_mib)};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int rc = program_.find('/') == std::string::npos
                     ? posix_spawnp(&pid, program_.c_str(), &actions, nullptr, argv.data(), environ)
                     : posix_spawn(&pid, program_.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(child_fd);
  if (rc != 0) {
    error_ = "cannot start '" + program_ + "': " + std::strerror(rc);
    return;
  }
  pid_ = pid;
}

SlaveProcess::~SlaveProcess() {
  if (running()) {
    // A polite shutdown with a short deadline, then the hard way.
    const double saved = timeout_;
    timeout_ = 0.5;
    Call("shutdown", json::object());
    timeout_ = saved;
    if (running()) Kill("stopped");
  }
  if (fd_ >= 0) ::close(fd_);
  if (shm_) ::munmap(shm_, kFrameMemory);
  if (shm_fd_ >= 0) ::close(shm_fd_);
}

std::string SlaveProcess::Reap() {
  if (pid_ <= 0) return "not running";
  int status = 0;
  pid_t r;
  do r = ::waitpid(pid_, &status, 0);
  while (r < 0 && errno == EINTR);
  pid_ = -1;
  if (r < 0) return "lost";
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* name = sigabbrev_np(sig);
    return "killed by signal " + std::to_string(sig) +
           (name ? std::string(" (SIG") + name + ")" : "");
  }
  return "exited with status " + std::to_string(WEXITSTATUS(status));
}

void SlaveProcess::Kill(const std::string& why) {
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    Reap();
  }
  error_ = why;
}

bool SlaveProcess::Send(const std::string& bytes) {
  const auto head = protocol::EncodeLength(static_cast<uint32_t>(bytes.size()));
  std::string framed(head.begin(), head.end());
  framed += bytes;
  size_t done = 0;
  while (done < framed.size()) {
    const ssize_t w = ::send(fd_, framed.data() + done, framed.size() - done, MSG_NOSIGNAL);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    done += static_cast<size_t>(w);
  }
  return true;
}

int SlaveProcess::ReadExact(char* buf, size_t n, int64_t deadline_ms) {
  while (n > 0) {
    const int64_t left = deadline_ms - NowMs();
    if (left <= 0) return -1;
    pollfd p{fd_, POLLIN, 0};
    const int pr = ::poll(&p, 1, static_cast<int>(std::min<int64_t>(left, 1 << 30)));
    if (pr < 0 && errno == EINTR) continue;
    if (pr < 0) return 0;
    if (pr == 0) return -1;
    const ssize_t r = ::read(fd_, buf, n);
    if (r < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (r <= 0) return 0;
    buf += r, n -= static_cast<size_t>(r);
  }
  return 1;
}

CallResult SlaveProcess::Call(const std::string& method, const json& params,
                              const Progress& progress) {
  CallResult out;
  if (!running()) {
    out.status = CallStatus::kNotRunning;
    out.message = error_.empty() ? "asgard-core is not running" : error_;
    return out;
  }
  const int64_t id = next_id_++;
  const json request = {{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", params}};
  auto died = [&](const std::string& when) {
    out.status = CallStatus::kDied;
    out.message = "asgard-core " + Reap() + " " + when;
    error_ = out.message;
    return out;
  };
  auto fail = [&](CallStatus status, const std::string& message) {
    Kill(message);
    out.status = status;
    out.message = message;
    return out;
  };
  if (!Send(request.dump(-1, ' ', false, json::error_handler_t::replace)))
    return died("(the request '" + method + "' could not be sent)");
  const int64_t silence = static_cast<int64_t>(timeout_ * 1000);
  // Progress notifications extend the silence deadline, never this one.
  const int64_t hard_deadline = NowMs() + silence * kOverallTimeoutFactor;
  int64_t deadline = NowMs() + silence;
  for (;;) {
    unsigned char head[4];
    int r = ReadExact(reinterpret_cast<char*>(head), 4, deadline);
    if (r < 0 && NowMs() >= hard_deadline)
      return fail(CallStatus::kTimeout,
                  "asgard-core did not finish '" + method + "' within " +
                      Seconds(timeout_ * kOverallTimeoutFactor) + " s (" +
                      std::to_string(kOverallTimeoutFactor) +
                      " times the watchdog timeout, whatever its progress) and was stopped");
    if (r < 0)
      return fail(CallStatus::kTimeout, "asgard-core did not answer '" + method + "' within " +
                                            Seconds(timeout_) + " s and was stopped");
    if (r == 0) return died("while answering '" + method + "'");
    const uint32_t n = protocol::DecodeLength(head);
    if (n > kMaxMessage)
      return fail(CallStatus::kProtocol, "protocol error: asgard-core sent a message of " +
                                             std::to_string(n) + " bytes; it was stopped");
    std::string body(n, '\0');
    r = n ? ReadExact(body.data(), n, deadline) : 1;
    if (r < 0)
      return fail(CallStatus::kTimeout,
                  "asgard-core stopped in the middle of a message and was stopped");
    if (r == 0) return died("in the middle of a message");
    if (protocol::JsonNestingDepth(body) > protocol::kMaxJsonDepth)
      return fail(CallStatus::kProtocol,
                  "protocol error: asgard-core sent a message nested more than " +
                      std::to_string(protocol::kMaxJsonDepth) + " deep; it was stopped");
    const json message = json::parse(body, nullptr, false);
    if (message.is_discarded() || !message.is_object())
      return fail(CallStatus::kProtocol,
                  "protocol error: asgard-core sent a message that is not a JSON object; it was "
                  "stopped");
    if (message.contains("method")) {  // a notification
      if (message["method"] == "progress" && message.contains("params") &&
          message["params"].is_object()) {
        const json& p = message["params"];
        if (progress && p.value("fraction", json()).is_number())
          progress(p["fraction"].get<double>(), p.value("time", 0.0));
      }
      deadline = std::min(NowMs() + silence, hard_deadline);
      continue;
    }
    if (!message.contains("id") || message["id"] != id) {
      if (message.contains("error") && message["id"].is_null()) {
        // An error about a request it could not read at all.
        out.status = CallStatus::kProtocol;
        out.message = "asgard-core could not read the request: " +
                      message["error"].value("message", std::string("?"));
        return out;
      }
      return fail(CallStatus::kProtocol, "protocol error: an answer to another request");
    }
    if (message.contains("result")) {
      out.result = message["result"];
      return out;
    }
    if (message.contains("error") && message["error"].is_object()) {
      out.status = CallStatus::kRemoteError;
      out.remote_code = message["error"].value("code", 0);
      out.message = message["error"].value("message", std::string("unknown error"));
      return out;
    }
    return fail(CallStatus::kProtocol, "protocol error: an answer without result or error");
  }
}

}  // namespace asgard::medium
