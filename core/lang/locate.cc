// Locating the element command being executed.
//
// Design: an element command is an alias into the master interpreter, so it
// runs while the child's frame stack still describes the call.  We ask the
// child for `info frame` records (through ::tcl::info::frame, so a script
// that redefines `info` does not interfere): the innermost record below our
// own query is the element command (its exact text, its line and whether it
// belongs to a proc body), the ones around it tell whether it runs through
// eval/uplevel or inside a proc.
//
// Lines in the records are relative: to the top-level command being
// evaluated (each top-level command is evaluated on its own, see interp.cc)
// or to the proc body.  We turn them into absolute lines and pick the source
// command with the same text on that line.  When the line cannot be made
// absolute (procs defined by computed text, eval of built strings) a command
// with the same text is accepted only if it is unique.  A command that is not
// found keeps the call site as its location.
//
// The words of a found command are matched to the arguments only when they
// can be proven to correspond: same count, no {*} expansion, and every
// literal source word equal to the argument value.
#include <tcl.h>

#include <cstring>
#include <string>

#include "core/lang/eval_context.h"

namespace asgard::lang {
namespace {

// How many enclosing frames are examined for eval/uplevel/proc.
constexpr int kMaxOuterFrames = 64;

struct FrameInfo {
  bool ok = false;
  std::string type;
  std::string cmd;
  std::string proc;
  int line = 0;
};

std::string DictString(Tcl_Obj* dict, const char* key) {
  Tcl_Obj* k = Tcl_NewStringObj(key, -1);
  Tcl_IncrRefCount(k);
  Tcl_Obj* v = nullptr;
  std::string out;
  if (Tcl_DictObjGet(nullptr, dict, k, &v) == TCL_OK && v != nullptr) {
    int len = 0;
    const char* s = Tcl_GetStringFromObj(v, &len);
    out.assign(s, len);
  }
  Tcl_DecrRefCount(k);
  return out;
}

// Runs `::tcl::info::frame ?level?` in the child.
bool QueryFrame(Tcl_Interp* child, int level, Tcl_Obj** result) {
  Tcl_Obj* words[2];
  words[0] = Tcl_NewStringObj("::tcl::info::frame", -1);
  int n = 1;
  if (level > 0) words[n++] = Tcl_NewIntObj(level);
  for (int i = 0; i < n; ++i) Tcl_IncrRefCount(words[i]);
  int rc = Tcl_EvalObjv(child, n, words, 0);
  for (int i = 0; i < n; ++i) Tcl_DecrRefCount(words[i]);
  if (rc != TCL_OK) return false;
  *result = Tcl_GetObjResult(child);
  Tcl_IncrRefCount(*result);
  Tcl_ResetResult(child);
  return true;
}

FrameInfo GetFrame(Tcl_Interp* child, int level) {
  FrameInfo f;
  Tcl_Obj* dict = nullptr;
  if (!QueryFrame(child, level, &dict)) return f;
  f.ok = true;
  f.type = DictString(dict, "type");
  f.cmd = DictString(dict, "cmd");
  f.proc = DictString(dict, "proc");
  std::string line = DictString(dict, "line");
  f.line = line.empty() ? 0 : std::atoi(line.c_str());
  Tcl_DecrRefCount(dict);
  return f;
}

std::string_view FirstWord(std::string_view cmd) {
  cmd = TrimCommandText(cmd);
  size_t e = 0;
  while (e < cmd.size() && cmd[e] != ' ' && cmd[e] != '\t' && cmd[e] != '\n') ++e;
  std::string_view w = cmd.substr(0, e);
  if (w.substr(0, 2) == "::") w.remove_prefix(2);
  return w;
}

bool IsEvalCommand(std::string_view cmd) {
  std::string_view w = FirstWord(cmd);
  if (w == "eval" || w == "uplevel" || w == "interp" || w == "subst") return true;
  if (w == "namespace") {
    std::string_view rest = TrimCommandText(cmd).substr(w.size());
    while (!rest.empty() && (rest[0] == ' ' || rest[0] == '\t')) rest.remove_prefix(1);
    return rest.substr(0, 4) == "eval" || rest.substr(0, 7) == "inscope";
  }
  return false;
}

bool WordsMatch(const SourceCommand& cmd, int objc, Tcl_Obj* const objv[]) {
  if (static_cast<int>(cmd.words.size()) != objc) return false;
  for (int i = 1; i < objc; ++i) {
    const SourceWord& w = cmd.words[i];
    if (w.expand) return false;
    if (w.simple) {
      int len = 0;
      const char* s = Tcl_GetStringFromObj(objv[i], &len);
      if (w.text != std::string_view(s, len)) return false;
    }
  }
  return true;
}

}  // namespace

CommandSite LocateCommand(EvalContext& ctx, int objc, Tcl_Obj* const objv[]) {
  CommandSite site;
  const SourceCommand& top = ctx.TopCommand();
  site.call_site = top.span;
  site.command = top.span;

  Tcl_Obj* depth_obj = nullptr;
  if (!QueryFrame(ctx.child, 0, &depth_obj)) return site;
  int depth = 0;
  Tcl_GetIntFromObj(nullptr, depth_obj, &depth);
  Tcl_DecrRefCount(depth_obj);

  // Skip our own query if the interpreter recorded a frame for it.
  int level = depth;
  FrameInfo elem;
  while (level >= 1) {
    elem = GetFrame(ctx.child, level);
    if (!elem.ok) return site;
    if (FirstWord(elem.cmd) != "tcl::info::frame") break;
    --level;
  }
  if (level < 1) return site;

  site.in_proc = elem.type == "proc";
  for (int l = level - 1; l >= 1 && l >= level - kMaxOuterFrames; --l) {
    FrameInfo outer = GetFrame(ctx.child, l);
    if (!outer.ok) break;
    if (IsEvalCommand(outer.cmd)) site.in_eval = true;
    if (outer.type == "proc") site.in_proc = true;
  }

  // Absolute line of the element command, when it can be known.
  int abs_line = 0;
  if (elem.type == "eval" && !site.in_eval && elem.line > 0) {
    abs_line = top.span.line + elem.line - 1;
  } else if (elem.type == "proc" && elem.line > 0) {
    auto bodies = ctx.map.ProcBodies(elem.proc);
    if (bodies.size() == 1) abs_line = bodies[0]->span.line + elem.line - 1;
  } else if (elem.type == "eval" && elem.line > 0) {
    // Under eval: literal bodies keep lines relative to the top command.
    abs_line = -(top.span.line + elem.line - 1);  // a hint only
  }

  std::vector<int> candidates = ctx.map.FindByText(elem.cmd);
  const SourceCommand* found = nullptr;
  if (abs_line > 0) {
    for (int c : candidates) {
      if (ctx.map.commands()[c].span.line == abs_line) {
        found = &ctx.map.commands()[c];
        break;
      }
    }
  } else {
    if (abs_line < 0) {
      for (int c : candidates) {
        if (ctx.map.commands()[c].span.line == -abs_line) {
          found = &ctx.map.commands()[c];
          break;
        }
      }
    }
    if (found == nullptr && candidates.size() == 1) found = &ctx.map.commands()[candidates[0]];
  }
  if (found == nullptr) return site;
  site.source = found;
  site.command = found->span;
  site.words_matched = WordsMatch(*found, objc, objv);
  return site;
}

}  // namespace asgard::lang
