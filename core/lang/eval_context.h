// Internal state of one evaluation, shared by the interpreter driver, the
// command locator and the element commands.  Not part of the public API.
#pragma once

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/lang/lang.h"
#include "core/lang/source_map.h"
#include "core/scene/scene.h"

struct Tcl_Interp;
struct Tcl_Obj;

namespace asgard::lang {

// Where the element command being executed comes from.
struct CommandSite {
  scene::SourceSpan command;              // the element command, or the call site if not found
  scene::SourceSpan call_site;            // the top-level command being evaluated
  const SourceCommand* source = nullptr;  // the element command in the source map
  bool words_matched = false;             // source->words[i] is objv[i] for every argument
  bool in_proc = false;
  bool in_eval = false;
};

// An element command call: objv[0] is the command, objv[1..] its arguments.
struct Invocation {
  std::string kind;  // "body", "force", ... (for messages)
  int objc = 0;
  Tcl_Obj* const* objv = nullptr;
  CommandSite site;

  // Span of argument `i` when it was located, else the command span.
  scene::SourceSpan ArgSpan(int i) const;
  const SourceWord* ArgWord(int i) const;
  std::string Arg(int i) const;
};

// Thrown by option parsing inside an element command; never leaves it.
struct ElementError {
  std::string message;
  int arg = -1;  // offending argument index, -1 for the whole command
};

struct EvalContext {
  EvalContext(std::string_view text, const EvalLimits& l) : map(text), limits(l) {}

  SourceMap map;
  EvalLimits limits;
  Tcl_Interp* master = nullptr;
  Tcl_Interp* child = nullptr;
  scene::Scene scene;
  int current_top = -1;           // index into map.top_level()
  std::map<int, int> run_counts;  // command span begin -> runs
  // Names of elements that were defined but failed, by kind.
  std::map<scene::ElementKind, std::set<std::string>> failed;

  std::vector<std::shared_ptr<void>> keep_alive;  // command client data

  // Memory guard state (see interp.cc).
  size_t heap_baseline = 0;
  size_t bytes_since_check = 0;
  long commands_since_check = 0;

  void AddError(std::string message, const scene::SourceSpan& span);
  void AddWarning(std::string message, const scene::SourceSpan& span);
  const SourceCommand& TopCommand() const { return map.commands()[map.top_level()[current_top]]; }
};

// Asks the child interpreter (via `info frame`) which command is running and
// finds it in the source map.  `objc/objv` are the element command's words.
CommandSite LocateCommand(EvalContext& ctx, int objc, Tcl_Obj* const objv[]);

// Registers the element commands (aliases in the child, implemented in the
// master).
void InstallElementCommands(EvalContext& ctx);

// After the script ran: run counts, loop reasons, cross-references.
void FinishScene(EvalContext& ctx);

}  // namespace asgard::lang
