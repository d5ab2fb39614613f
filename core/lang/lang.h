// The scene language: Tcl 8.6 with Asgard's element commands.
//
//   scene text ──Evaluate──▶ scene::Scene (elements + diagnostics)
//
// Each evaluation creates a fresh *safe* child interpreter
// (Tcl_CreateSlave(..., isSafe=1)) of a parent interpreter that each thread
// makes once and keeps (scripts never run in it).  The script runs in the child, with
// a command-count limit and a time limit (Tcl_LimitSetCommands /
// Tcl_LimitSetTime), so an endless loop ends with a clear error.  The element
// commands (simulator shape_set body link force torque trajectory lightsource
// view, and `instance` as an alias of `body`, `index` as the old name of
// lindex) are aliases into the parent, implemented in C++.
//
// Source tracking: before evaluation the text is split into top-level
// commands with Tcl_ParseCommand, recording each command's and each word's
// byte span.  While running, an element command asks `info frame` for the
// line of the command being executed (and whether it runs in a proc or
// through eval), then finds its own command span; it counts how many times the
// command at that span ran.  Option words are matched to their source words
// so that literal numbers and vectors can be rewritten in place later.
//
// Errors never throw: every problem becomes a scene::Diagnostic with a line
// and column, the element that failed is skipped, and the rest of the script
// still runs where Tcl allows (an error in an element command is caught and
// recorded; evaluation continues with the next top-level command).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "core/scene/scene.h"

namespace asgard::lang {

struct EvalLimits {
  long command_limit = 1'000'000;  // Tcl commands per evaluation
  int time_limit_ms = 5000;        // wall-clock time per evaluation
  size_t memory_limit_mb = 512;    // heap growth allowed during an evaluation
  // One Tcl value's size; all the arguments of one command together may be
  // 4× it, a command's estimated result 16×, a list value_bytes/4 elements.
  size_t value_bytes = size_t{16} << 20;
};

// Evaluates `text` and returns the scene.  Never throws.
//
// Spans: SourceSpan offsets are bytes into `text`.  A Word's span covers the
// whole source word including its braces or quotes (`{-5 0 0}`); its text is
// the value without them.  Diagnostics are in the order they were found; a
// parse error (unbalanced brace, ...) is reported at the opening delimiter
// and the commands before it are still evaluated.
scene::Scene Evaluate(std::string_view text, const EvalLimits& limits = {});

// Lets Evaluate lower the process's data limit (RLIMIT_DATA) while a scene
// runs, to what the process uses plus the memory limit: then every
// allocation a scene causes fails past the limit, also one no guard foresaw
// (a list of shared values whose text is made inside a word's substitution),
// and the evaluation stops with an error instead of taking the machine's
// memory.  Only for a process that evaluates on one thread while no other
// thread allocates (the asgard tool, asgard-core); no effect under
// AddressSanitizer, whose shadow memory is past any such limit.
void CapProcessMemoryDuringEvaluation(bool on);

// Formats a diagnostic as "FILE:LINE:COL: error: message" ("warning" for
// warnings; "FILE: error: message" when the location is unknown).
std::string FormatDiagnostic(std::string_view filename, const scene::Diagnostic& d);

}  // namespace asgard::lang
