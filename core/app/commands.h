// Subcommands of the asgard CLI implemented outside main.cc.
#pragma once

#include <string>
#include <vector>

namespace asgard::app {

// asgard render FILE ...   (core/app/render_cmd.cc)
int RenderCommand(const std::vector<std::string>& args);
// asgard export FILE ...   (core/app/render_cmd.cc)
int ExportCommand(const std::vector<std::string>& args);

extern const char* const kRenderHelp;
extern const char* const kExportHelp;

}  // namespace asgard::app
