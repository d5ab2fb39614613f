// asgard render / asgard export (being built: see issue "Rendering and exports").
#include <iostream>

#include "core/app/commands.h"

namespace asgard::app {

const char* const kRenderHelp = "Usage: asgard render FILE ...\n\nNot available in this build yet.\n";
const char* const kExportHelp = "Usage: asgard export FILE ...\n\nNot available in this build yet.\n";

int RenderCommand(const std::vector<std::string>&) {
  std::cerr << "asgard render: not available in this build yet\n";
  return 2;
}

int ExportCommand(const std::vector<std::string>&) {
  std::cerr << "asgard export: not available in this build yet\n";
  return 2;
}

}  // namespace asgard::app
