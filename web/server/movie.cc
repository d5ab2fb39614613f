#include "web/server/movie.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "formats/document/file.h"

extern char** environ;

namespace asgard::serve {
namespace fs = std::filesystem;

namespace {

std::string Slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string Joined(const std::array<double, 3>& v) {
  std::ostringstream s;
  s.precision(10);
  s << v[0] << ',' << v[1] << ',' << v[2];
  return s.str();
}

}  // namespace

bool RenderMovie(const std::string& asgard, const std::string& text, const MovieRequest& r,
                 std::string* bytes, std::string* error) {
  if (r.format != "mp4" && r.format != "webm" && r.format != "gif") {
    *error = "a movie is mp4, webm or gif, not '" + r.format + "'";
    return false;
  }
  std::string dir_pattern = (fs::temp_directory_path() / "asgard-movie-XXXXXX").string();
  if (!::mkdtemp(dir_pattern.data())) {
    *error = std::string("cannot make a temporary folder: ") + std::strerror(errno);
    return false;
  }
  const fs::path dir(dir_pattern);
  struct Cleanup {
    fs::path dir;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  } cleanup{dir};
  const fs::path scene = dir / "scene.al", out = dir / ("movie." + r.format),
                 log = dir / "render.log";
  if (!document::WriteFileAtomic(scene.string(), text, error)) return false;
  std::vector<std::string> args = {asgard,
                                   "render",
                                   scene.string(),
                                   "--size",
                                   std::to_string(r.width) + "x" + std::to_string(r.height),
                                   "--quiet"};
  if (!r.view.empty()) args.insert(args.end(), {"--view", r.view});
  if (r.rot_degrees) args.insert(args.end(), {"--rot", Joined(*r.rot_degrees)});
  if (r.center) args.insert(args.end(), {"--center", Joined(*r.center)});
  if (r.pan) args.insert(args.end(), {"--pan", Joined(*r.pan)});
  if (r.scale) {
    std::ostringstream s;
    s.precision(10);
    s << *r.scale;
    args.insert(args.end(), {"--scale", s.str()});
  }
  args.insert(args.end(), {"-o", out.string()});
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = -1;
  const int rc = ::posix_spawn(&pid, asgard.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    *error = "cannot run " + asgard + ": " + std::strerror(rc);
    return false;
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::string said = Slurp(log);
    while (!said.empty() && (said.back() == '\n' || said.back() == ' ')) said.pop_back();
    *error = "asgard render failed" + (said.empty() ? std::string() : ": " + said);
    return false;
  }
  *bytes = Slurp(out);
  if (bytes->empty()) {
    *error = "asgard render wrote no movie";
    return false;
  }
  return true;
}

}  // namespace asgard::serve
