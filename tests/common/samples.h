// Shared helper of the tests that read the scene and document samples.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace asgard {

// The bytes of samples/<name> in the source tree (a path relative to
// samples/, such as "pendulum.al" or "../tests/solver/data/x.al"); fails the
// calling test if the file cannot be opened.
inline std::string ReadSample(const std::string& name) {
  std::ifstream in(std::string(ASGARD_SOURCE_DIR) + "/samples/" + name, std::ios::binary);
  EXPECT_TRUE(in.is_open()) << "cannot open samples/" << name;
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace asgard
