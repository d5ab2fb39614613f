// Runs a shell command for the document tests: its exit status (-1 when it
// ended by a signal) and its standard output and error together.
#pragma once

#include <sys/wait.h>

#include <cstdio>
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

}  // namespace asgard::testing
