// Helpers shared by the asgard subcommands (see cli.h).
#include "core/app/cli.h"

#include <iostream>

#include "formats/document/file.h"

namespace asgard::app {

int Usage(const std::string& message, const char* help) {
  return cli::Usage("asgard", message, help);
}

int TakeFile(const std::string& command, const std::string& arg, std::string& file,
             const char* help) {
  if (!arg.empty() && arg[0] == '-') return Usage(command + ": unknown option '" + arg + "'", help);
  if (!file.empty()) return Usage(command + ": only one FILE is accepted", help);
  file = arg;
  return -1;
}

bool ReadFile(const std::string& file, std::string& text) {
  if (document::ReadFile(file, text, nullptr)) return true;
  std::cerr << "asgard: cannot read '" << file << "'\n";
  return false;
}

}  // namespace asgard::app
