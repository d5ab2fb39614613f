// Command-line conventions (see cli.h).
#include "formats/cli/cli.h"

#include <cmath>
#include <cstdlib>
#include <iostream>

namespace asgard::cli {

int Usage(std::string_view program, const std::string& message, std::string_view help) {
  std::cerr << program << ": " << message << "\n\n" << help;
  return kUsageError;
}

bool ParseNumber(const std::string& s, double& out) {
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return !s.empty() && end && *end == '\0' && std::isfinite(out);
}

}  // namespace asgard::cli
