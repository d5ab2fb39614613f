// Source map of a scene script: every command and word with its byte span.
//
// Built once per evaluation, before anything runs, with Tcl_ParseCommand.
// Top-level commands are listed in order; braced words and bracketed command
// substitutions are parsed again as scripts so that commands inside loop
// bodies, proc bodies and `[...]` have spans too.  (Braced data such as
// `{1 2 3}` also parses as a "command"; that is harmless because commands are
// looked up by their exact text and line.)
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/scene/scene.h"

struct Tcl_Token;

namespace asgard::lang {

// Maps byte offsets to 1-based line and column.
class LineIndex {
 public:
  explicit LineIndex(std::string_view text);
  scene::SourceSpan Span(int begin, int end) const;
  int LineOf(int offset) const;
  // Offset of the first byte of `line` (clamped to the text).
  int LineStart(int line) const;
  int line_count() const { return static_cast<int>(starts_.size()); }

 private:
  std::vector<int> starts_;
  int size_ = 0;
};

struct SourceWord {
  scene::SourceSpan span;  // the whole word, including braces or quotes
  bool simple = false;     // no substitution: its value is `text`
  bool expand = false;     // {*}word
  std::string text;        // the value of a simple word (braces/quotes removed)
};

struct SourceCommand {
  scene::SourceSpan span;  // first byte of the first word to end of last word
  std::vector<SourceWord> words;
  int top = -1;      // index (into top_level) of the enclosing top-level command
  int depth = 0;     // 0 for top-level commands
  std::string text;  // exact source text of `span`
};

struct ParseFailure {
  std::string message;
  scene::SourceSpan span;  // where the problem starts (e.g. the open brace)
};

class SourceMap {
 public:
  // Parses `text` (which must outlive the map).
  explicit SourceMap(std::string_view text);

  std::string_view text() const { return text_; }
  const LineIndex& lines() const { return lines_; }
  const std::vector<SourceCommand>& commands() const { return commands_; }
  // Indices into commands() of the top-level commands, in order.
  const std::vector<int>& top_level() const { return top_level_; }
  // Set when the top-level parse stopped early; the commands before it are
  // listed and can be evaluated.
  const std::optional<ParseFailure>& failure() const { return failure_; }

  // Commands whose text equals `text` (after trimming blanks and a trailing
  // semicolon).
  std::vector<int> FindByText(std::string_view text) const;

  // The body word of `proc NAME ARGS BODY` definitions named `name` (leading
  // "::" ignored); empty when there are none.
  std::vector<const SourceWord*> ProcBodies(std::string_view name) const;

  // The best span for an error reported by Tcl: `hint` is the text of the
  // failing command as quoted in errorInfo (a prefix when `truncated`),
  // `line` the absolute line from -errorline inside top-level command `top`.
  // Prefers a command with that text inside `top` (on `line` if several),
  // then a unique one anywhere (a proc body), then the most deeply nested
  // command starting on `line`, then the non-blank part of the line.
  scene::SourceSpan ErrorSpan(int top, int line, std::string_view hint, bool truncated) const;

 private:
  void ParseScript(int begin, int end, int top, int depth, bool top_level);
  void ParseWords(const Tcl_Token* tokens, int num_words, SourceCommand& cmd);

  std::string_view text_;
  LineIndex lines_;
  std::vector<SourceCommand> commands_;
  std::vector<int> top_level_;
  std::optional<ParseFailure> failure_;
  std::unordered_multimap<std::string_view, int> by_text_;
};

// Tcl's parser recurses once per nested `[`; a few tens of thousands of
// levels overflow the C stack.  Returns the offset of the first `[` nested
// deeper than `limit` (backslash-escaped brackets ignored, braces not
// considered, so the count is conservative), or -1.
constexpr int kMaxBracketDepth = 256;
int FindDeepBracket(std::string_view text, int limit = kMaxBracketDepth);

// `text` without leading/trailing blanks and trailing semicolons.
std::string_view TrimCommandText(std::string_view text);

}  // namespace asgard::lang
