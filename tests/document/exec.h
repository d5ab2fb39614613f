// Runs a shell command for the document tests: its exit status (-1 when it
// ended by a signal) and its standard output and error together.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace asgard::testing {

struct Result {
  int status = -1;
  std::string out;
};

inline Result Exec(const std::string& command) {
  Result r;
  FILE* p = popen((command + " 2>&1").c_str(), "r");
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int s = pclose(p);
  r.status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
  return r;
}

// An empty folder `name` of the group's scratch folder in the build tree.
inline std::filesystem::path ScratchFolder(const std::string& group, const std::string& name) {
  const auto dir = std::filesystem::path(ASGARD_BINARY_DIR) / "tests/document" / group / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A whole file's bytes (empty when it cannot be read).
inline std::string FileText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace asgard::testing
