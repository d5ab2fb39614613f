// Shared helpers of the render and export tests.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "core/pipeline/pipeline.h"

namespace asgard::render::testing {

inline std::string SourcePath(const std::string& rel) {
  return std::string(ASGARD_SOURCE_DIR) + "/" + rel;
}

inline std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Simulates a scene file of the repository (relative path).
inline pipeline::Run SimulateFile(const std::string& rel) {
  return pipeline::Simulate(ReadText(SourcePath(rel)));
}

// A fresh scratch directory under the build tree.
inline std::string ScratchDir(const std::string& name) {
  const std::string dir = std::string(ASGARD_BINARY_DIR) + "/render-test-output/" + name;
  [[maybe_unused]] const int rc =
      std::system(("rm -rf '" + dir + "' && mkdir -p '" + dir + "'").c_str());
  return dir;
}

inline bool HaveProgram(const std::string& name) {
  return std::system(("command -v " + name + " > /dev/null 2>&1").c_str()) == 0;
}

inline int Run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace asgard::render::testing
