// The command-line conventions every Asgard program follows (asgard, dochost):
// a usage error prints "PROGRAM: MESSAGE", a blank line and the help on
// standard error and exits 2; numbers in arguments are whole words.
#pragma once

#include <string>
#include <string_view>

namespace asgard::cli {

// The exit status of a usage error.
inline constexpr int kUsageError = 2;

// Prints the usage error; returns kUsageError.
int Usage(std::string_view program, const std::string& message, std::string_view help);

// A whole argument as a finite number.
bool ParseNumber(const std::string& s, double& out);

}  // namespace asgard::cli
