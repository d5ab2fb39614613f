// Evaluation driver: interpreters, limits, safety guards, error locations.
//
// Design:
//  * A fresh safe child ("scene") per evaluation runs the script; its
//    master hosts the element commands.  The master is made once per thread
//    and kept: creating it was a third of a small scene's evaluation (each
//    Tcl_CreateInterp builds Tcl's whole command table).  Scripts never run
//    in it; after each evaluation the child is deleted with every alias into
//    the master, the master's "asgard_*" commands (whose client data belonged
//    to that evaluation) are deleted and its result is reset.  After a Tcl
//    panic both are abandoned and the next evaluation starts a new master.
//    The child additionally loses `interp`, `after`, `vwait` and `update`
//    (nested interpreters escape the limits; the others wait on the event
//    loop).
//  * Limits on the child: a command count (relative to what the setup used)
//    and a wall-clock deadline checked at every limit check (granularity 1),
//    which also catches `while 1 {}` -- a compiled empty loop runs no
//    commands at all, so the command limit alone would never fire.
//  * Memory: Tcl aborts the process when an allocation fails or a value
//    passes 2 GB, so values must not get near that.  `string repeat` and
//    `lrepeat` are replaced by versions that refuse results above 16 MB /
//    4M elements; an object trace refuses any command whose argument is a
//    string above 16 MB (stops doubling loops), and every 4096 commands or
//    32 MB of argument text it compares the process heap with its size at the
//    start (EvalLimits::memory_limit_mb).  A single command can still make a
//    big value from small arguments (`string map`, `regsub` on a large
//    input); see docs/language.md.  `format`/`binary format` specs with
//    fields wider than 16 MB are refused.  The trace knows the commands it
//    bounds by their tokens, not by the word that named them.  Where the
//    process allows it (CapProcessMemoryDuringEvaluation), RLIMIT_DATA is
//    lowered for the evaluation, so that an allocation no guard foresaw
//    fails and Tcl's panic ends the scene with a memory error.  The trace
//    also keeps Tcl from inlining commands, which costs some speed; scenes
//    are small.
//  * Each top-level command is evaluated on its own (Tcl_EvalEx on its text),
//    so an error in one does not stop the others and `info frame` lines are
//    relative to a known command.  Errors are located from -errorline and the
//    "while executing" text of errorInfo.
//  * Nothing here throws out of Evaluate; Tcl state never outlives it.
#include <dlfcn.h>
#include <malloc.h>
#include <setjmp.h>
#include <sys/resource.h>
#include <tcl.h>
#include <tclTomMath.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#define ASGARD_ASAN_ALLOCATOR 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ASGARD_ASAN_ALLOCATOR 1
#endif
#endif
#ifdef ASGARD_ASAN_ALLOCATOR
// The sanitizer runtime's count of bytes in live allocations (declared in
// <sanitizer/allocator_interface.h>, which GCC does not ship).
extern "C" size_t __sanitizer_get_current_allocated_bytes();
#endif

#include "core/lang/eval_context.h"
#include "core/lang/lang.h"

namespace asgard::lang {
namespace {

// The size limits of this thread's evaluation, from EvalLimits::value_bytes
// (Evaluate sets them): a value, the elements a list may get, all the
// arguments of one command, a command's estimated result (below).
struct SizeLimits {
  size_t value, list_elements, command, result;
  explicit SizeLimits(size_t value_bytes)
      : value(value_bytes),
        list_elements(value_bytes / 4),
        command(4 * value_bytes),
        result(16 * value_bytes) {}
};
thread_local SizeLimits size_limits{EvalLimits{}.value_bytes};
constexpr size_t kCheckEveryBytes = size_t{32} << 20;
constexpr long kCheckEveryCommands = 4096;
constexpr int kRecursionLimit = 400;
// size_limits.command: all the arguments of one command together, and the
// string a pure list argument would become: a command over more than this
// is refused (values past 2 GB abort Tcl, and a command's result is at most
// about the sum of its arguments for everything but the commands bounded
// separately below).  size_limits.result: a bound on a single command's
// output estimated from its arguments (string map, regsub, join), far below
// Tcl's 2 GB value limit.

// Tcl aborts the process on a panic (a value past 2 GB that a check above
// did not foresee, an allocation failure).  While a scene command runs, the
// panic jumps back to the evaluation instead, which reports it and abandons
// (leaks) the interpreters, whose state can no longer be trusted.
thread_local sigjmp_buf* panic_target = nullptr;
thread_local char panic_message[256];

[[noreturn]] void ScenePanic(const char* format, ...) {
  va_list ap;
  va_start(ap, format);
  std::vsnprintf(panic_message, sizeof panic_message, format, ap);
  va_end(ap);
  if (panic_target != nullptr) {
    sigjmp_buf* target = panic_target;
    panic_target = nullptr;
    siglongjmp(*target, 1);
  }
  std::fprintf(stderr, "Tcl panic: %s\n", panic_message);
  std::abort();
}

// Integers.  Tcl's big-integer arithmetic runs inside one `expr` without
// returning to the interpreter, so neither the time limit nor the memory
// check can stop `7**99999999`, `1 << 99999999` or a 10-million-digit
// literal, and turning such a number into text takes time quadratic in its
// digits.  The big-integer primitives that make a number grow are wrapped
// below (Tcl calls them through its procedure linkage table, so the
// executable's definitions take their place); one that would make a number
// of more than kMaxIntegerBits bits during a scene evaluation stops it the
// way a Tcl panic does (the interpreter is abandoned, the error names the
// limit).  Outside a scene evaluation they only forward.
// Tcl makes a big integer into text in time quadratic in its digits (3**100000,
// 47713 digits: 5 s), so the limit keeps that well under a second.
constexpr long kMaxIntegerBits = 1L << 15;  // 32768 bits, 9864 decimal digits

long DigitBits(const mp_int* a) { return static_cast<long>(a->used) * MP_DIGIT_BIT; }

void CheckIntegerBits(long bits) {
  if (bits <= kMaxIntegerBits || panic_target == nullptr) return;
  ScenePanic("an integer would have about %ld bits; the scene limit is %ld bits (%ld digits)", bits,
             kMaxIntegerBits, static_cast<long>(kMaxIntegerBits * 0.30103));
}

// libtcl's own definition of a wrapped primitive.  The executable links
// libtcl dynamically, so the next definition in lookup order is always
// there; if a build ever links Tcl statically the wrappers would be the only
// definitions, and forwarding to null must not be what finds that out.
template <typename Fn>
Fn Real(const char* name) {
  void* const next = dlsym(RTLD_NEXT, name);
  if (next == nullptr) {
    std::fprintf(stderr, "asgard: libtcl's %s was not found (%s); Tcl must be linked dynamically\n",
                 name, dlerror());
    std::abort();
  }
  return reinterpret_cast<Fn>(next);
}

void InitTcl() {
  static std::once_flag once;
  std::call_once(once, [] {
    Tcl_SetPanicProc(ScenePanic);
    Tcl_FindExecutable(nullptr);
  });
}

size_t HeapInUse() {
#ifdef ASGARD_ASAN_ALLOCATOR
  // AddressSanitizer replaces malloc; glibc's mallinfo2 then sees nothing and
  // the memory limit would never trip.
  return __sanitizer_get_current_allocated_bytes();
#else
  struct mallinfo2 mi = mallinfo2();
  return mi.uordblks + mi.hblkhd;
#endif
}

// The commands whose result the trace bounds from their arguments.  They are
// known by their command token, not by the word a script wrote: Tcl looks a
// name up as a C string, so "lrepeat\0\0" runs lrepeat, and `rename` or
// a namespace path reach a command under another word (a guard that compared
// the word let 1.6 GB of list text through).
enum class Guarded {
  kNone,
  kJoin,
  kString,  // the ensemble: `string map ...`
  kStringMap,
  kRegsub,
  kSplit,
  kRegexp,
  kListRepeat,
  kFormat,
  kBinary,  // the ensemble: `binary format ...`
  kBinaryFormat,
};

struct GuardState;

// A guarded command's token, forgotten when the command is deleted (its token
// could then be reused by a command of the script's).
struct GuardedCommand {
  GuardState* guard;
  Tcl_Command token;
};

struct GuardState {
  EvalContext* ctx = nullptr;
  bool memory_exceeded = false;
  std::unordered_map<Tcl_Command, Guarded> guarded;
  std::vector<std::unique_ptr<GuardedCommand>> watches;
  // String sizes of large pure lists already measured: (element count,
  // element array) → bytes, so a loop over a big list is not quadratic.
  struct Measured {
    int count;
    Tcl_Obj** elements;
    size_t bytes;
  };
  std::unordered_map<Tcl_Obj*, Measured> measured;
};

const Tcl_ObjType* ListType() {
  static const Tcl_ObjType* type = Tcl_GetObjType("list");
  return type;
}

// The bytes of the string `o` has or would get (a pure list's string is
// built from its elements'); stops counting past `cap`.  Other values
// without a string (numbers, dicts, ...) count as small.
size_t StringBytes(GuardState& guard, Tcl_Obj* o, size_t cap, int depth = 0) {
  if (o->bytes != nullptr) return static_cast<size_t>(o->length);
  if (o->typePtr != ListType() || depth > 64) return 32;
  int n = 0;
  Tcl_Obj** elements = nullptr;
  if (Tcl_ListObjGetElements(nullptr, o, &n, &elements) != TCL_OK) return 32;
  constexpr int kMemoFrom = 1024;
  if (n >= kMemoFrom) {
    auto it = guard.measured.find(o);
    if (it != guard.measured.end() && it->second.count == n && it->second.elements == elements)
      return it->second.bytes;
  }
  size_t bytes = 0;
  for (int i = 0; i < n && bytes <= cap; ++i)
    bytes += StringBytes(guard, elements[i], cap, depth + 1) + 3;  // braces and a space
  if (n >= kMemoFrom) {
    if (guard.measured.size() > 4096) guard.measured.clear();
    guard.measured[o] = {n, elements, bytes};
  }
  return bytes;
}

// A value's text with its length: Tcl keeps the bytes a script gave it, a
// NUL among them, so the text does not end at the first NUL (a regsub
// spec "\0&&&…" read up to its NUL hid every & from the bound below).
std::string_view Text(Tcl_Obj* o) {
  int len = 0;
  const char* s = Tcl_GetStringFromObj(o, &len);
  return {s, static_cast<size_t>(len)};
}

// Commands whose result can be far larger than their arguments: a bound on
// the result from the arguments, or 0 when there is nothing to fear.
size_t ResultBound(GuardState& guard, Guarded kind, int objc, Tcl_Obj* const objv[]) {
  auto len = [&](int i) { return StringBytes(guard, objv[i], size_limits.result); };
  if (kind == Guarded::kJoin && objc == 3) {
    int n = 0;
    if (Tcl_ListObjLength(nullptr, objv[1], &n) != TCL_OK) return 0;
    return len(1) + static_cast<size_t>(n) * len(2);
  }
  if ((kind == Guarded::kString || kind == Guarded::kStringMap) && objc >= 3) {
    const bool sub = kind == Guarded::kString;
    if (sub && Text(objv[1]) != "map") return 0;
    const int map = objc - 2, input = objc - 1;
    int n = 0;
    Tcl_Obj** pairs = nullptr;
    if (Tcl_ListObjGetElements(nullptr, objv[map], &n, &pairs) != TCL_OK) return 0;
    size_t longest = 1;
    for (int i = 1; i < n; i += 2)
      longest = std::max(longest, StringBytes(guard, pairs[i], size_limits.result));
    // Every input character can become the longest replacement at most.
    return (len(input) + 1) * longest;
  }
  if (kind == Guarded::kRegsub && objc >= 4) {
    // regsub ?switches? exp string subSpec ?varName?: every match (at most
    // one per input character, and one more) becomes subSpec, with each &
    // or \N the whole input at most.
    int i = 1;
    while (i < objc && Tcl_GetString(objv[i])[0] == '-') {
      if (Text(objv[i++]) == "--") break;
    }
    const int input = i + 1;
    if (input + 1 >= objc) return 0;
    const std::string_view spec = Text(objv[input + 1]);
    size_t refs = 0;
    for (size_t k = 0; k < spec.size(); ++k)
      if (spec[k] == '&' ||
          (spec[k] == '\\' && k + 1 < spec.size() && spec[k + 1] >= '0' && spec[k + 1] <= '9'))
        ++refs;
    const size_t in = len(input);
    return in + (in + 1) * (spec.size() + refs * in);
  }
  return 0;
}

// Commands that build a list of far more elements than their arguments
// hold values (each element a Tcl object of about 50 bytes besides its
// text: 16 MB split into single characters takes over 1 GB before the next
// memory check): a bound on the element count, or 0 when it is small.
size_t ElementBound(Guarded kind, int objc, Tcl_Obj* const objv[]) {
  if (kind == Guarded::kSplit && (objc == 2 || objc == 3)) {
    int len = 0;
    const char* s = Tcl_GetStringFromObj(objv[1], &len);
    if (static_cast<size_t>(len) < size_limits.list_elements) return 0;
    // The exact count: one more than the separators (default: white
    // space), or every character with an empty separator list.
    std::vector<Tcl_UniChar> seps;
    const std::string_view chars = objc == 3 ? Text(objv[2]) : std::string_view(" \t\n\r");
    for (const char* p = chars.data(); p < chars.data() + chars.size();) {
      Tcl_UniChar c = 0;
      p += Tcl_UtfToUniChar(p, &c);
      seps.push_back(c);
    }
    size_t count = 1;
    for (const char* p = s; p < s + len;) {
      Tcl_UniChar c = 0;
      p += Tcl_UtfToUniChar(p, &c);
      if (seps.empty() || std::find(seps.begin(), seps.end(), c) != seps.end()) ++count;
    }
    return count;
  }
  if (kind == Guarded::kRegexp && objc >= 3) {
    // regexp ?switches? exp string ...: with -all -inline, every match (at
    // most one per input character, and one more) adds itself and each
    // subexpression (at most one per '(' of exp).
    bool all = false, inline_ = false;
    int i = 1;
    for (; i < objc && Tcl_GetString(objv[i])[0] == '-'; ++i) {
      const std::string_view sw = Text(objv[i]);
      if (sw == "--") {
        ++i;
        break;
      }
      all |= sw == "-all";
      inline_ |= sw == "-inline";
      if (sw == "-start") ++i;
    }
    if (!all || !inline_ || i + 1 >= objc) return 0;
    const std::string_view exp = Text(objv[i]);
    int len = 0;
    Tcl_GetStringFromObj(objv[i + 1], &len);
    const size_t groups = 1 + static_cast<size_t>(std::count(exp.begin(), exp.end(), '('));
    const size_t bound = (static_cast<size_t>(len) + 1) * groups;
    return bound > size_limits.list_elements ? bound : 0;
  }
  return 0;
}

// lrepeat shares its values, so its list is cheap, but the list's text (made
// when it is substituted into a word: `[lrepeat 4000 $big]x`) is count times
// theirs, built inside the substitution where no check runs.  A list whose
// text is over the command limit could not be passed to any command anyway,
// so it is not made.  The text's size, or 0 when it is not lrepeat.
size_t RepeatedListBytes(GuardState& guard, Guarded kind, int objc, Tcl_Obj* const objv[]) {
  if (kind != Guarded::kListRepeat || objc < 3) return 0;
  Tcl_WideInt count = 0;
  if (Tcl_GetWideIntFromObj(nullptr, objv[1], &count) != TCL_OK || count <= 0) return 0;
  // Too many elements: lrepeat itself refuses that, with its own message.
  if (static_cast<size_t>(count) > size_limits.list_elements / static_cast<size_t>(objc - 2))
    return 0;
  size_t per = 0;
  for (int i = 2; i < objc; ++i) per += StringBytes(guard, objv[i], size_limits.command) + 3;
  return static_cast<size_t>(count) * per;
}

void SetError(Tcl_Interp* interp, const std::string& message) {
  Tcl_SetObjResult(interp, Tcl_NewStringObj(message.data(), static_cast<int>(message.size())));
}

std::string MegaBytes(size_t bytes) {
  return bytes >= (size_t{1} << 20) ? std::to_string(bytes >> 20) + " MB"
                                    : std::to_string(bytes >> 10) + " KB";
}

// True if a `format` / `binary format` spec asks for a field wider than the
// value limit (digit runs in the spec, or `*` with a huge argument).
bool HugeFormat(Guarded kind, int objc, Tcl_Obj* const objv[]) {
  int spec = -1;
  if ((kind == Guarded::kFormat || kind == Guarded::kBinaryFormat) && objc >= 2) spec = 1;
  if (kind == Guarded::kBinary && objc >= 3 && Text(objv[1]) == "format") spec = 2;
  if (spec < 0) return false;
  const std::string_view f = Text(objv[spec]);
  size_t run = 0;
  for (char c : f) {
    if (c >= '0' && c <= '9') {
      run = std::min(run * 10 + static_cast<size_t>(c - '0'), size_limits.value + 1);
      if (run > size_limits.value) return true;
    } else {
      run = 0;
    }
  }
  if (f.find('*') == std::string_view::npos) return false;
  for (int i = spec + 1; i < objc; ++i) {
    Tcl_WideInt w = 0;
    if (Tcl_GetWideIntFromObj(nullptr, objv[i], &w) == TCL_OK &&
        (w > static_cast<Tcl_WideInt>(size_limits.value) ||
         w < -static_cast<Tcl_WideInt>(size_limits.value))) {
      return true;
    }
  }
  return false;
}

// The command's name as Tcl looked it up: up to a NUL, at most 40 bytes.
std::string FirstWord(Tcl_Obj* word) {
  std::string_view name = Text(word);
  name = name.substr(0, std::min(name.find('\0'), size_t{40}));
  if (name.substr(0, 2) == "::") name.remove_prefix(2);
  return std::string(name);
}

int GuardTrace(ClientData data, Tcl_Interp* interp, int, const char*, Tcl_Command command, int objc,
               Tcl_Obj* const objv[]) {
  auto* guard = static_cast<GuardState*>(data);
  EvalContext& ctx = *guard->ctx;
  const auto known = guard->guarded.find(command);
  const Guarded kind = known == guard->guarded.end() ? Guarded::kNone : known->second;
  if (guard->memory_exceeded) {
    SetError(interp, "scene exceeded its memory limit (" +
                         std::to_string(ctx.limits.memory_limit_mb) + " MB)");
    return TCL_ERROR;
  }
  size_t bytes = 0, strings = 0;
  for (int i = 0; i < objc; ++i) {
    if (objv[i]->bytes == nullptr) {
      // A pure list: what its string would be, and its element array.
      strings += StringBytes(*guard, objv[i], size_limits.command);
      int n = 0;
      if (objv[i]->typePtr == ListType() && Tcl_ListObjLength(nullptr, objv[i], &n) == TCL_OK)
        bytes += static_cast<size_t>(n) * sizeof(Tcl_Obj*);
      if (strings > size_limits.command) break;
      continue;
    }
    size_t len = static_cast<size_t>(objv[i]->length);
    strings += len;
    if (len > size_limits.value) {
      SetError(interp, "value of " + std::to_string(len) + " bytes is above the scene limit of " +
                           MegaBytes(size_limits.value));
      return TCL_ERROR;
    }
    bytes += len;
    if (len >= static_cast<size_t>(kMaxBracketDepth) &&
        FindDeepBracket(std::string_view(objv[i]->bytes, len)) >= 0) {
      SetError(interp, "brackets nested more than " + std::to_string(kMaxBracketDepth) +
                           " deep are not allowed in scene scripts");
      return TCL_ERROR;
    }
  }
  if (strings > size_limits.command) {
    SetError(interp, "the arguments of \"" + FirstWord(objv[0]) + "\" come to more than " +
                         MegaBytes(size_limits.command) + " in all, above the scene limit");
    return TCL_ERROR;
  }
  if (objc >= 2) {
    if (const size_t bound = ResultBound(*guard, kind, objc, objv); bound > size_limits.result) {
      SetError(interp, "the result of \"" + FirstWord(objv[0]) + "\" could reach " +
                           std::to_string(bound) + " bytes, above the scene limit of " +
                           MegaBytes(size_limits.result));
      return TCL_ERROR;
    }
    if (const size_t text = RepeatedListBytes(*guard, kind, objc, objv);
        text > size_limits.command) {
      SetError(interp, "lrepeat: the result would come to " + std::to_string(text) +
                           " bytes as text, above the scene limit of " +
                           MegaBytes(size_limits.command));
      return TCL_ERROR;
    }
    if (const size_t count = ElementBound(kind, objc, objv); count > size_limits.list_elements) {
      SetError(interp, "the result of \"" + FirstWord(objv[0]) + "\" could have " +
                           std::to_string(count) + " elements, above the scene limit of " +
                           std::to_string(size_limits.list_elements) + " elements");
      return TCL_ERROR;
    }
  }
  ctx.bytes_since_check += bytes;
  if (objc >= 2 && HugeFormat(kind, objc, objv)) {
    SetError(interp,
             "format: field width is above the scene limit of " + MegaBytes(size_limits.value));
    return TCL_ERROR;
  }
  if (++ctx.commands_since_check >= kCheckEveryCommands ||
      ctx.bytes_since_check >= kCheckEveryBytes) {
    ctx.commands_since_check = 0;
    ctx.bytes_since_check = 0;
    size_t now = HeapInUse();
    size_t limit = ctx.limits.memory_limit_mb << 20;
    if (now > ctx.heap_baseline && now - ctx.heap_baseline > limit) {
      guard->memory_exceeded = true;
      SetError(interp, "scene exceeded its memory limit (" +
                           std::to_string(ctx.limits.memory_limit_mb) + " MB)");
      return TCL_ERROR;
    }
  }
  return TCL_OK;
}

int StringRepeat(ClientData, Tcl_Interp* interp, int objc, Tcl_Obj* const objv[]) {
  if (objc != 3) {
    SetError(interp, "wrong # args: should be \"string repeat string count\"");
    return TCL_ERROR;
  }
  int count = 0;
  if (Tcl_GetIntFromObj(interp, objv[2], &count) != TCL_OK) return TCL_ERROR;
  int len = 0;
  const char* s = Tcl_GetStringFromObj(objv[1], &len);
  if (count <= 0 || len == 0) {
    Tcl_ResetResult(interp);
    return TCL_OK;
  }
  size_t total = static_cast<size_t>(len) * static_cast<size_t>(count);
  if (total > size_limits.value) {
    SetError(interp, "string repeat: result of " + std::to_string(total) +
                         " bytes is above the scene limit of " + MegaBytes(size_limits.value));
    return TCL_ERROR;
  }
  // Filled by doubling copies (one byte at a time, 400 MB took seconds).
  Tcl_Obj* out = Tcl_NewObj();
  Tcl_SetObjLength(out, static_cast<int>(total));
  char* bytes = Tcl_GetString(out);
  std::memcpy(bytes, s, static_cast<size_t>(len));
  for (size_t done = static_cast<size_t>(len); done < total;) {
    const size_t n = std::min(done, total - done);
    std::memcpy(bytes + done, bytes, n);
    done += n;
  }
  Tcl_SetObjResult(interp, out);
  return TCL_OK;
}

int ListRepeat(ClientData, Tcl_Interp* interp, int objc, Tcl_Obj* const objv[]) {
  if (objc < 2) {
    SetError(interp, "wrong # args: should be \"lrepeat count ?value ...?\"");
    return TCL_ERROR;
  }
  int count = 0;
  if (Tcl_GetIntFromObj(interp, objv[1], &count) != TCL_OK) return TCL_ERROR;
  if (count < 0) {
    SetError(interp, "bad count \"" + std::to_string(count) + "\": must be integer >= 0");
    return TCL_ERROR;
  }
  size_t per = static_cast<size_t>(objc - 2);
  if (per == 0) {  // nothing to repeat: no loop over the count (2e9 took a minute)
    Tcl_ResetResult(interp);
    return TCL_OK;
  }
  size_t total = per * static_cast<size_t>(count);
  if (total > size_limits.list_elements) {
    SetError(interp, "lrepeat: result of " + std::to_string(total) +
                         " elements is above the scene limit of " +
                         std::to_string(size_limits.list_elements) + " elements");
    return TCL_ERROR;
  }
  std::vector<Tcl_Obj*> elems;
  elems.reserve(total);
  for (int i = 0; i < count; ++i) {
    for (int k = 2; k < objc; ++k) elems.push_back(objv[k]);
  }
  Tcl_SetObjResult(interp, Tcl_NewListObj(static_cast<int>(elems.size()), elems.data()));
  return TCL_OK;
}

void ForgetGuardedCommand(ClientData data, Tcl_Interp*, const char*, const char*, int flags) {
  auto* watch = static_cast<GuardedCommand*>(data);
  if ((flags & TCL_TRACE_DELETE) != 0) watch->guard->guarded.erase(watch->token);
}

void WatchGuardedCommands(Tcl_Interp* child, GuardState& guard) {
  static constexpr std::pair<const char*, Guarded> kCommands[] = {
      {"::join", Guarded::kJoin},
      {"::string", Guarded::kString},
      {"::tcl::string::map", Guarded::kStringMap},
      {"::regsub", Guarded::kRegsub},
      {"::split", Guarded::kSplit},
      {"::regexp", Guarded::kRegexp},
      {"::lrepeat", Guarded::kListRepeat},
      {"::format", Guarded::kFormat},
      {"::binary", Guarded::kBinary},
      {"::tcl::binary::format", Guarded::kBinaryFormat},
  };
  for (const auto& [name, kind] : kCommands) {
    Tcl_Command token = Tcl_FindCommand(child, name, nullptr, TCL_GLOBAL_ONLY);
    if (token == nullptr) continue;
    guard.guarded[token] = kind;
    guard.watches.push_back(std::make_unique<GuardedCommand>(GuardedCommand{&guard, token}));
    Tcl_TraceCommand(child, name, TCL_TRACE_DELETE, ForgetGuardedCommand,
                     guard.watches.back().get());
  }
}

// Makes the child safe enough and installs the guards.  Returns false (with
// a message) if something essential could not be set up.
bool SetUpChild(EvalContext& ctx, GuardState& guard, std::string& error) {
  Tcl_Interp* child = ctx.child;
  for (const char* name : {"interp", "after", "vwait", "update"}) {
    if (Tcl_HideCommand(child, name, name) != TCL_OK) Tcl_ResetResult(child);
  }
  if (Tcl_EvalEx(child, "rename ::tcl::string::repeat {}; rename ::lrepeat {}", -1, 0) != TCL_OK) {
    error = std::string("cannot install guards: ") + Tcl_GetStringResult(child);
    return false;
  }
  Tcl_CreateObjCommand(ctx.master, "asgard_string_repeat", StringRepeat, nullptr, nullptr);
  Tcl_CreateObjCommand(ctx.master, "asgard_lrepeat", ListRepeat, nullptr, nullptr);
  if (Tcl_CreateAlias(child, "::tcl::string::repeat", ctx.master, "asgard_string_repeat", 0,
                      nullptr) != TCL_OK ||
      Tcl_CreateAlias(child, "::lrepeat", ctx.master, "asgard_lrepeat", 0, nullptr) != TCL_OK ||
      Tcl_CreateAlias(child, "index", child, "lindex", 0, nullptr) != TCL_OK) {
    error = std::string("cannot install guards: ") + Tcl_GetStringResult(child);
    return false;
  }
  InstallElementCommands(ctx);
  WatchGuardedCommands(child, guard);
  Tcl_SetRecursionLimit(child, kRecursionLimit);
  Tcl_CreateObjTrace(child, 0, 0, GuardTrace, &guard, nullptr);

  // Limits last, so that the setup does not count against them.
  long used = 0;
  if (Tcl_EvalEx(child, "info cmdcount", -1, 0) == TCL_OK) {
    Tcl_GetLongFromObj(nullptr, Tcl_GetObjResult(child), &used);
  }
  Tcl_ResetResult(child);
  long limit = std::max(1L, ctx.limits.command_limit);
  Tcl_LimitSetCommands(child, static_cast<int>(std::min<long>(used + limit, 2'000'000'000L)));
  Tcl_LimitTypeSet(child, TCL_LIMIT_COMMANDS);
  Tcl_Time deadline;
  Tcl_GetTime(&deadline);
  long ms = std::max(1, ctx.limits.time_limit_ms);
  deadline.sec += ms / 1000;
  deadline.usec += (ms % 1000) * 1000;
  if (deadline.usec >= 1'000'000) {
    deadline.sec += 1;
    deadline.usec -= 1'000'000;
  }
  Tcl_LimitSetTime(child, &deadline);
  Tcl_LimitSetGranularity(child, TCL_LIMIT_TIME, 1);
  Tcl_LimitSetGranularity(child, TCL_LIMIT_COMMANDS, 1);
  Tcl_LimitTypeSet(child, TCL_LIMIT_TIME);
  return true;
}

std::string FormatSeconds(int ms) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g s", ms / 1000.0);
  return buf;
}

std::string FirstLine(std::string s) {
  size_t nl = s.find('\n');
  if (nl != std::string::npos) s = s.substr(0, nl);
  constexpr size_t kMax = 300;
  if (s.size() > kMax) s = s.substr(0, kMax) + "...";
  return s;
}

// The innermost command text quoted in errorInfo ("while executing\n\"...\""),
// and whether Tcl shortened it.
std::string ExecutingHint(Tcl_Interp* child, bool* truncated) {
  *truncated = false;
  const char* info = Tcl_GetVar(child, "errorInfo", TCL_GLOBAL_ONLY);
  if (info == nullptr) return {};
  std::string_view s(info);
  size_t at = s.find("\n    while executing\n\"");
  if (at == std::string_view::npos) at = s.find("\n    invoked from within\n\"");
  if (at == std::string_view::npos) return {};
  s = s.substr(s.find('"', at) + 1);
  size_t end = s.find("\"\n");
  if (end == std::string_view::npos) end = s.rfind('"');
  if (end == std::string_view::npos) return {};
  s = s.substr(0, end);
  if (s.size() >= 3 && s.substr(s.size() - 3) == "...") {
    s.remove_suffix(3);
    *truncated = true;
  }
  return std::string(s.substr(0, std::min<size_t>(s.size(), 150)));
}

// Adds a hint to "invalid command name" errors for commands a safe scene
// interpreter does not offer.
std::string ExplainError(std::string message) {
  static constexpr const char* kUnsafe[] = {
      "exec", "open",   "file",  "socket", "source", "load",       "cd",       "exit",   "glob",
      "pwd",  "interp", "after", "vwait",  "update", "fconfigure", "encoding", "unload", "puts"};
  for (const char* name : kUnsafe) {
    if (message == std::string("invalid command name \"") + name + "\"") {
      return message + " (not available in scene scripts: they run in a safe interpreter)";
    }
  }
  return message;
}

int ErrorLine(Tcl_Interp* child, int rc) {
  Tcl_Obj* opts = Tcl_GetReturnOptions(child, rc);
  Tcl_IncrRefCount(opts);
  Tcl_Obj* key = Tcl_NewStringObj("-errorline", -1);
  Tcl_IncrRefCount(key);
  Tcl_Obj* value = nullptr;
  int line = 0;
  if (Tcl_DictObjGet(nullptr, opts, key, &value) == TCL_OK && value != nullptr) {
    Tcl_GetIntFromObj(nullptr, value, &line);
  }
  Tcl_DecrRefCount(key);
  Tcl_DecrRefCount(opts);
  return line;
}

bool PastDeadline(const std::chrono::steady_clock::time_point& deadline) {
  return std::chrono::steady_clock::now() >= deadline;
}

// The master interpreter kept by this thread between evaluations (Tcl
// interpreters belong to the thread that made them); deleted when the thread
// ends.
struct KeptMaster {
  Tcl_Interp* interp = nullptr;
  KeptMaster() = default;
  KeptMaster(const KeptMaster&) = delete;
  KeptMaster& operator=(const KeptMaster&) = delete;
  ~KeptMaster() {
    if (interp != nullptr) Tcl_DeleteInterp(interp);
  }
};
thread_local KeptMaster kept_master;

// Owns the child interpreter of one evaluation, and returns the master to
// this thread's keeping afterwards.
class Interps {
 public:
  explicit Interps(EvalContext& ctx) : ctx_(ctx) {
    if (kept_master.interp == nullptr) kept_master.interp = Tcl_CreateInterp();
    ctx.master = kept_master.interp;
    if (ctx.master != nullptr) ctx.child = Tcl_CreateSlave(ctx.master, "scene", 1);
  }
  ~Interps() {
    if (abandoned) {
      kept_master.interp = nullptr;  // leaked with the child, never touched again
    } else if (ctx_.master != nullptr) {
      if (ctx_.child != nullptr) Tcl_DeleteInterp(ctx_.child);
      if (Tcl_EvalEx(ctx_.master, "foreach c [info commands ::asgard_*] {rename $c {}}", -1,
                     TCL_EVAL_GLOBAL) != TCL_OK) {
        // Cannot happen with a sound master; start afresh rather than keep one
        // holding commands of a finished evaluation.
        Tcl_DeleteInterp(ctx_.master);
        kept_master.interp = nullptr;
      } else {
        Tcl_ResetResult(ctx_.master);
      }
    }
    ctx_.master = nullptr;
    ctx_.child = nullptr;
  }
  Interps(const Interps&) = delete;
  Interps& operator=(const Interps&) = delete;
  bool abandoned = false;  // after a Tcl panic: leaked, never touched again

 private:
  EvalContext& ctx_;
};

constexpr int kPanicked = -1000;

std::atomic<bool> cap_process_memory{false};

#ifndef ASGARD_ASAN_ALLOCATOR
// Kilobytes of the process's data segment (what RLIMIT_DATA counts), or -1.
long DataSegmentKb() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (f == nullptr) return -1;
  char line[256];
  long kb = -1;
  while (std::fgets(line, sizeof line, f) != nullptr) {
    if (std::strncmp(line, "VmData:", 7) == 0) {
      kb = std::strtol(line + 7, nullptr, 10);
      break;
    }
  }
  std::fclose(f);
  return kb;
}
#endif

// Lowers RLIMIT_DATA for the evaluation (see CapProcessMemoryDuringEvaluation)
// and puts it back.  The slack covers what the interpreters' setup and the
// element commands take besides the scene's own growth.
class ProcessMemoryCap {
 public:
  explicit ProcessMemoryCap(size_t limit_mb) {
#ifndef ASGARD_ASAN_ALLOCATOR
    if (!cap_process_memory.load()) return;
    const long kb = DataSegmentKb();
    if (kb < 0 || ::getrlimit(RLIMIT_DATA, &saved_) != 0) return;
    constexpr rlim_t kSlack = rlim_t{64} << 20;
    const rlim_t cap =
        static_cast<rlim_t>(kb) * 1024 + (static_cast<rlim_t>(limit_mb) << 20) + kSlack;
    if (saved_.rlim_cur != RLIM_INFINITY && saved_.rlim_cur <= cap) return;
    rlimit lowered = saved_;
    lowered.rlim_cur = cap;
    active_ = ::setrlimit(RLIMIT_DATA, &lowered) == 0;
#else
    (void)limit_mb;
#endif
  }
  ~ProcessMemoryCap() {
    if (active_) ::setrlimit(RLIMIT_DATA, &saved_);
  }
  ProcessMemoryCap(const ProcessMemoryCap&) = delete;
  ProcessMemoryCap& operator=(const ProcessMemoryCap&) = delete;

 private:
  rlimit saved_{};
  bool active_ = false;
};

// A panic because an allocation failed: the data limit above, or the
// machine's memory.
bool AllocationFailed(const char* message) {
  return std::strncmp(message, "unable to alloc", 15) == 0 ||
         std::strncmp(message, "unable to realloc", 17) == 0;
}

// Tcl_EvalEx, or kPanicked when Tcl panicked during it.  Kept apart from
// Run so that no C++ object lives between the setjmp and the longjmp.
int EvalGuarded(Tcl_Interp* interp, const char* script, int length) {
  static thread_local sigjmp_buf target;
  if (sigsetjmp(target, 0) != 0) return kPanicked;
  panic_target = &target;
  const int rc = Tcl_EvalEx(interp, script, length, 0);
  panic_target = nullptr;
  return rc;
}

void Run(EvalContext& ctx) {
  GuardState guard;
  guard.ctx = &ctx;  // outlives the interpreters that call it
  ProcessMemoryCap cap(ctx.limits.memory_limit_mb);
  Interps interps(ctx);
  scene::SourceSpan whole = ctx.map.lines().Span(0, 0);
  if (ctx.child == nullptr) {
    ctx.AddError("cannot create the scene interpreter", whole);
    return;
  }
  std::string setup_error;
  ctx.heap_baseline = HeapInUse();
  auto deadline = std::chrono::steady_clock::now() +
                  std::chrono::milliseconds(std::max(1, ctx.limits.time_limit_ms));
  if (!SetUpChild(ctx, guard, setup_error)) {
    ctx.AddError(setup_error, whole);
    return;
  }
  const auto& top = ctx.map.top_level();
  std::string_view text = ctx.map.text();
  for (size_t i = 0; i < top.size(); ++i) {
    ctx.current_top = static_cast<int>(i);
    const SourceCommand& cmd = ctx.map.commands()[top[i]];
    int rc = EvalGuarded(ctx.child, text.data() + cmd.span.begin, cmd.span.end - cmd.span.begin);
    if (rc == kPanicked) {
      interps.abandoned = true;
      const std::string what = AllocationFailed(panic_message)
                                   ? "scene exceeded its memory limit (" +
                                         std::to_string(ctx.limits.memory_limit_mb) +
                                         " MB: " + FirstLine(panic_message) + ")"
                                   : "scene exceeded the limits of the Tcl interpreter (" +
                                         FirstLine(panic_message) + ")";
      ctx.AddError(what + "; evaluation stopped",
                   ctx.map.ErrorSpan(static_cast<int>(i), cmd.span.line, "", false));
      ctx.master = nullptr;
      ctx.child = nullptr;
      break;
    }
    if (rc == TCL_OK) continue;
    if (rc == TCL_RETURN) break;  // `return` at top level ends the scene, as in a sourced file
    int rel = rc == TCL_ERROR ? ErrorLine(ctx.child, rc) : 1;
    int last_line = ctx.map.lines().LineOf(cmd.span.end);
    int line = std::clamp(cmd.span.line + std::max(rel, 1) - 1, cmd.span.line, last_line);
    bool truncated = false;
    std::string hint = rc == TCL_ERROR ? ExecutingHint(ctx.child, &truncated) : std::string();
    scene::SourceSpan span = ctx.map.ErrorSpan(static_cast<int>(i), line, hint, truncated);
    bool limit_hit = Tcl_LimitExceeded(ctx.child) != 0;
    if (guard.memory_exceeded) {
      ctx.AddError(
          "scene exceeded its memory limit (" + std::to_string(ctx.limits.memory_limit_mb) + " MB)",
          span);
      break;
    }
    if (limit_hit) {
      if (Tcl_LimitTypeExceeded(ctx.child, TCL_LIMIT_TIME) || PastDeadline(deadline)) {
        ctx.AddError(
            "scene exceeded its time limit (" + FormatSeconds(ctx.limits.time_limit_ms) + ")",
            span);
      } else {
        ctx.AddError("scene exceeded its command limit (" +
                         std::to_string(ctx.limits.command_limit) + " commands)",
                     span);
      }
      break;
    }
    if (rc == TCL_BREAK || rc == TCL_CONTINUE) {
      ctx.AddError(std::string("invoked \"") + (rc == TCL_BREAK ? "break" : "continue") +
                       "\" outside of a loop",
                   span);
      continue;
    }
    ctx.AddError(ExplainError(FirstLine(Tcl_GetStringResult(ctx.child))), span);
    Tcl_ResetResult(ctx.child);
  }
  if (const auto& failure = ctx.map.failure()) {
    std::string message = failure->message;
    if (message == "missing close-brace" || message == "missing close-bracket" ||
        message == "missing close-quote") {
      message += " (the one opened here is never closed)";
    }
    ctx.AddError(message, failure->span);
  }
  FinishScene(ctx);
}

}  // namespace

void CapProcessMemoryDuringEvaluation(bool on) { cap_process_memory.store(on); }

scene::Scene Evaluate(std::string_view text, const EvalLimits& limits) {
  try {
    InitTcl();
    // At least 1 KB per value, at most 64 MB (4× that is a command's
    // arguments, 16× a result bound: below Tcl's 2 GB).
    size_limits = SizeLimits(std::clamp(limits.value_bytes, size_t{1} << 10, size_t{64} << 20));
    if (text.size() > size_limits.command) {
      scene::Scene s;
      s.diagnostics.push_back({scene::Severity::kError, "scene text is too large", {0, 0, 1, 1}});
      return s;
    }
    if (int at = FindDeepBracket(text); at >= 0) {
      scene::Scene s;
      s.diagnostics.push_back({scene::Severity::kError,
                               "brackets nested more than " + std::to_string(kMaxBracketDepth) +
                                   " deep are not allowed in scene scripts",
                               LineIndex(text).Span(at, at + 1)});
      return s;
    }
    // Tcl may look at the byte after a command's text (fuzz_scene saw it
    // read past a scene that ended the buffer holding it): evaluate a copy
    // that ends with a NUL.
    const std::string owned(text);
    EvalContext ctx(owned, limits);
    Run(ctx);
    return std::move(ctx.scene);
  } catch (const std::exception& e) {
    scene::Scene s;
    s.diagnostics.push_back(
        {scene::Severity::kError, std::string("internal error: ") + e.what(), {0, 0, 1, 1}});
    return s;
  } catch (...) {
    scene::Scene s;
    s.diagnostics.push_back({scene::Severity::kError, "internal error", {0, 0, 1, 1}});
    return s;
  }
}

std::string FormatDiagnostic(std::string_view filename, const scene::Diagnostic& d) {
  std::string out(filename);
  if (d.span.known()) {
    out += ":" + std::to_string(d.span.line) + ":" + std::to_string(d.span.column);
  }
  out += d.severity == scene::Severity::kError ? ": error: " : ": warning: ";
  out += d.message;
  return out;
}

}  // namespace asgard::lang

// The wrapped big-integer primitives (see kMaxIntegerBits).
using asgard::lang::CheckIntegerBits;
using asgard::lang::DigitBits;
using asgard::lang::Real;

extern "C" {

mp_err TclBN_mp_mul(const mp_int* a, const mp_int* b, mp_int* c) {
  static const auto real = Real<mp_err (*)(const mp_int*, const mp_int*, mp_int*)>("TclBN_mp_mul");
  CheckIntegerBits(DigitBits(a) + DigitBits(b));
  return real(a, b, c);
}

mp_err TclBN_mp_sqr(const mp_int* a, mp_int* b) {
  static const auto real = Real<mp_err (*)(const mp_int*, mp_int*)>("TclBN_mp_sqr");
  CheckIntegerBits(2 * DigitBits(a));
  return real(a, b);
}

mp_err TclBN_mp_mul_d(const mp_int* a, mp_digit b, mp_int* c) {
  static const auto real = Real<mp_err (*)(const mp_int*, mp_digit, mp_int*)>("TclBN_mp_mul_d");
  CheckIntegerBits(DigitBits(a) + MP_DIGIT_BIT);
  return real(a, b, c);
}

mp_err TclBN_mp_mul_2d(const mp_int* a, int d, mp_int* c) {
  static const auto real = Real<mp_err (*)(const mp_int*, int, mp_int*)>("TclBN_mp_mul_2d");
  CheckIntegerBits(DigitBits(a) + d);
  return real(a, d, c);
}

mp_err TclBN_mp_lshd(mp_int* a, int shift) {
  static const auto real = Real<mp_err (*)(mp_int*, int)>("TclBN_mp_lshd");
  CheckIntegerBits(DigitBits(a) + static_cast<long>(shift) * MP_DIGIT_BIT);
  return real(a, shift);
}

mp_err TclBN_mp_expt_d(const mp_int* a, unsigned int b, mp_int* c) {
  static const auto real =
      Real<mp_err (*)(const mp_int*, unsigned int, mp_int*)>("TclBN_mp_expt_d");
  // |a| ≤ 1 stays small whatever the exponent.
  if (a->used > 1 || (a->used == 1 && a->dp[0] > 1))
    CheckIntegerBits(static_cast<long>(
        std::min<double>(static_cast<double>(TclBN_mp_count_bits(a) - 1) * b, 1e15)));
  return real(a, b, c);
}

}  // extern "C"
