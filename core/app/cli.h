// Helpers shared by the asgard subcommands (main.cc, render_cmd.cc): usage
// errors, numbers, the FILE argument and reading it.
#pragma once

#include <string>

#include "formats/cli/cli.h"

namespace asgard::app {

using cli::ParseNumber;

// Prints "asgard: MESSAGE", a blank line and the command's help to standard
// error (formats/cli); returns 2, the exit status of a usage error.
int Usage(const std::string& message, const char* help);

// The command's one FILE argument: `arg` is an unknown option when it starts
// with '-', a usage error when FILE was already given.  Returns -1 when `arg`
// was taken as FILE, else the exit status of the usage error.
int TakeFile(const std::string& command, const std::string& arg, std::string& file,
             const char* help);

// Reads FILE whole.  On failure prints "asgard: cannot read 'FILE'" and
// returns false.
bool ReadFile(const std::string& file, std::string& text);

}  // namespace asgard::app
