#include "web/server/slave_link.h"

#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/protocol/protocol.h"

extern char** environ;

namespace asgard::serve {
namespace {

bool WriteAll(int fd, const char* p, size_t n) {
  while (n > 0) {
    const ssize_t r = ::send(fd, p, n, MSG_NOSIGNAL);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return false;
    p += r, n -= static_cast<size_t>(r);
  }
  return true;
}

bool ReadAll(int fd, char* p, size_t n) {
  while (n > 0) {
    const ssize_t r = ::read(fd, p, n);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return false;
    p += r, n -= static_cast<size_t>(r);
  }
  return true;
}

}  // namespace

SlaveLink::~SlaveLink() { Stop(); }

bool SlaveLink::Start() {
  if (running()) return true;
  int sv[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0) {
    error_ = std::string("socketpair: ") + std::strerror(errno);
    return false;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, sv[1], 3);  // dup2 clears CLOEXEC
  std::string a0 = program_, a1 = "--fd", a2 = "3";
  char* argv[] = {a0.data(), a1.data(), a2.data(), nullptr};
  pid_t pid = -1;
  const int rc = ::posix_spawn(&pid, program_.c_str(), &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(sv[1]);
  if (rc != 0) {
    ::close(sv[0]);
    error_ = "cannot start " + program_ + ": " + std::strerror(rc);
    return false;
  }
  pid_ = pid;
  fd_ = sv[0];
  return true;
}

void SlaveLink::Stop() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
  pid_ = -1;
}

SlaveAnswer SlaveLink::Call(const std::string& method, const nlohmann::json& params) {
  SlaveAnswer a;
  if (!Start()) {
    a.died = true;
    a.error = error_;
    return a;
  }
  const long id = next_id_++;
  const std::string body =
      nlohmann::json{{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", params}}.dump(
          -1, ' ', false, nlohmann::json::error_handler_t::replace);
  const auto head = protocol::EncodeLength(static_cast<uint32_t>(body.size()));
  auto broken = [&](const std::string& why) {
    Stop();
    a.died = true;
    a.error = "the animation's process " + why + "; it restarts on the next action";
    return a;
  };
  if (!WriteAll(fd_, reinterpret_cast<const char*>(head.data()), 4) ||
      !WriteAll(fd_, body.data(), body.size()))
    return broken("ended");
  for (;;) {  // progress notifications come first; the answer carries our id
    unsigned char h[4];
    if (!ReadAll(fd_, reinterpret_cast<char*>(h), 4)) return broken("ended");
    const uint32_t n = protocol::DecodeLength(h);
    if (n > protocol::kMaxMessage) return broken("sent a message that cannot be framed");
    std::string in(n, '\0');
    if (n > 0 && !ReadAll(fd_, in.data(), n)) return broken("ended");
    const auto m = nlohmann::json::parse(in, nullptr, false);
    if (m.is_discarded() || !m.is_object()) return broken("sent a message that is not JSON");
    if (!m.contains("id") || m["id"] != id) continue;
    if (m.contains("result")) {
      a.ok = true;
      a.result = m["result"];
    } else {
      a.error = m.contains("error") && m["error"].is_object()
                    ? m["error"].value("message", std::string("error"))
                    : "malformed answer";
    }
    return a;
  }
}

}  // namespace asgard::serve
