// Source map construction.
//
// Design: Tcl_ParseCommand is run over the whole text; each command's words
// become SourceWords (span, simple-ness, value).  Script-like sub-ranges --
// the inside of braced words and of `[...]` substitutions -- are parsed again
// recursively (bounded depth and command count), after the enclosing command
// has been stored, so that every command the interpreter may later report
// through `info frame` can be found by its text.  Only the top-level parse
// can fail the map; a nested range that does not parse (braced data, say) is
// simply not descended into.
#include "core/lang/source_map.h"

#include <tcl.h>

#include <algorithm>
#include <cstring>
#include <utility>

namespace asgard::lang {
namespace {

constexpr int kMaxDepth = 48;
constexpr size_t kMaxCommands = 400000;

std::string ParseErrorMessage(int error_type) {
  switch (error_type) {
    case TCL_PARSE_MISSING_BRACE:
      return "missing close-brace";
    case TCL_PARSE_MISSING_BRACKET:
      return "missing close-bracket";
    case TCL_PARSE_MISSING_PAREN:
      return "missing close-parenthesis";
    case TCL_PARSE_MISSING_QUOTE:
      return "missing close-quote";
    case TCL_PARSE_MISSING_VAR_BRACE:
      return "missing close-brace for variable name";
    case TCL_PARSE_BRACE_EXTRA:
      return "extra characters after close-brace";
    case TCL_PARSE_QUOTE_EXTRA:
      return "extra characters after close-quote";
    case TCL_PARSE_SYNTAX:
      return "syntax error";
    case TCL_PARSE_BAD_NUMBER:
      return "bad number";
    default:
      return "parse error";
  }
}

bool IsBlank(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

}  // namespace

std::string_view TrimCommandText(std::string_view text) {
  size_t b = 0;
  while (b < text.size() && IsBlank(text[b])) ++b;
  size_t e = text.size();
  while (e > b && (IsBlank(text[e - 1]) || text[e - 1] == ';')) --e;
  return text.substr(b, e - b);
}

int FindDeepBracket(std::string_view text, int limit) {
  if (text.size() < static_cast<size_t>(limit)) return -1;
  size_t opens = 0;
  for (const char* p = text.data();
       (p = static_cast<const char*>(std::memchr(p, '[', text.data() + text.size() - p))) !=
       nullptr;
       ++p) {
    if (++opens > static_cast<size_t>(limit)) break;
  }
  if (opens <= static_cast<size_t>(limit)) return -1;
  int depth = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    char c = text[i];
    if (c == '\\') {
      ++i;
    } else if (c == '[') {
      if (++depth > limit) return static_cast<int>(i);
    } else if (c == ']' && depth > 0) {
      --depth;
    }
  }
  return -1;
}

LineIndex::LineIndex(std::string_view text) : size_(static_cast<int>(text.size())) {
  starts_.push_back(0);
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\n') starts_.push_back(static_cast<int>(i + 1));
  }
}

int LineIndex::LineOf(int offset) const {
  offset = std::clamp(offset, 0, size_);
  auto it = std::upper_bound(starts_.begin(), starts_.end(), offset);
  return static_cast<int>(it - starts_.begin());
}

int LineIndex::LineStart(int line) const {
  if (line < 1) return 0;
  if (line > line_count()) return size_;
  return starts_[line - 1];
}

scene::SourceSpan LineIndex::Span(int begin, int end) const {
  scene::SourceSpan s;
  s.begin = begin;
  s.end = end;
  s.line = LineOf(begin);
  s.column = begin - starts_[s.line - 1] + 1;
  return s;
}

SourceMap::SourceMap(std::string_view text) : text_(text), lines_(text) {
  ParseScript(0, static_cast<int>(text.size()), -1, 0, true);
  for (size_t i = 0; i < commands_.size(); ++i) {
    const auto& span = commands_[i].span;
    by_text_.emplace(text_.substr(span.begin, span.end - span.begin), static_cast<int>(i));
  }
}

void SourceMap::ParseScript(int begin, int end, int top, int depth, bool is_top) {
  const char* base = text_.data();
  const char* p = base + begin;
  int remaining = end - begin;
  while (remaining > 0 && commands_.size() < kMaxCommands) {
    Tcl_Parse parse;
    if (Tcl_ParseCommand(nullptr, p, remaining, 0, &parse) != TCL_OK) {
      if (is_top) {
        int at = static_cast<int>(parse.term - base);
        at = std::clamp(at, 0, static_cast<int>(text_.size()));
        failure_ = ParseFailure{ParseErrorMessage(parse.errorType), lines_.Span(at, at + 1)};
        if (failure_->span.end > static_cast<int>(text_.size())) failure_->span.end = at;
      }
      Tcl_FreeParse(&parse);
      return;
    }
    const char* next = parse.commandStart + parse.commandSize;
    if (parse.numWords > 0) {
      SourceCommand cmd;
      cmd.depth = depth;
      std::vector<std::pair<int, int>> nested;
      const Tcl_Token* tok = parse.tokenPtr;
      int last_end = static_cast<int>(parse.commandStart - base);
      for (int w = 0; w < parse.numWords; ++w) {
        SourceWord word;
        int wb = static_cast<int>(tok->start - base);
        int we = wb + tok->size;
        word.span = lines_.Span(wb, we);
        word.expand = tok->type == TCL_TOKEN_EXPAND_WORD;
        word.simple = tok->type == TCL_TOKEN_SIMPLE_WORD;
        if (word.simple) word.text.assign(tok[1].start, tok[1].size);
        if (!word.expand && tok->size >= 2 && tok->start[0] == '{') {
          nested.emplace_back(wb + 1, we - 1);
        } else {
          for (int c = 1; c <= tok->numComponents; ++c) {
            if (tok[c].type == TCL_TOKEN_COMMAND && tok[c].size >= 2) {
              int cb = static_cast<int>(tok[c].start - base);
              nested.emplace_back(cb + 1, cb + tok[c].size - 1);
            }
          }
        }
        last_end = we;
        cmd.words.push_back(std::move(word));
        tok += tok->numComponents + 1;
      }
      int cb = static_cast<int>(parse.commandStart - base);
      cmd.span = lines_.Span(cb, last_end);
      cmd.text.assign(text_.substr(cb, last_end - cb));
      int index = static_cast<int>(commands_.size());
      if (is_top) {
        top = static_cast<int>(top_level_.size());
        top_level_.push_back(index);
      }
      cmd.top = top;
      commands_.push_back(std::move(cmd));
      Tcl_FreeParse(&parse);
      if (depth < kMaxDepth) {
        for (auto [nb, ne] : nested) ParseScript(nb, ne, top, depth + 1, false);
      }
    } else {
      Tcl_FreeParse(&parse);
    }
    remaining -= static_cast<int>(next - p);
    p = next;
  }
}

std::vector<int> SourceMap::FindByText(std::string_view text) const {
  std::vector<int> out;
  auto [b, e] = by_text_.equal_range(TrimCommandText(text));
  for (auto it = b; it != e; ++it) out.push_back(it->second);
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<const SourceWord*> SourceMap::ProcBodies(std::string_view name) const {
  if (name.substr(0, 2) == "::") name.remove_prefix(2);
  std::vector<const SourceWord*> out;
  for (const auto& cmd : commands_) {
    if (cmd.words.size() != 4 || !cmd.words[0].simple || cmd.words[0].text != "proc") continue;
    if (!cmd.words[1].simple) continue;
    std::string_view n = cmd.words[1].text;
    if (n.substr(0, 2) == "::") n.remove_prefix(2);
    if (n == name) out.push_back(&cmd.words[3]);
  }
  return out;
}

scene::SourceSpan SourceMap::ErrorSpan(int top, int line, std::string_view hint,
                                       bool truncated) const {
  hint = TrimCommandText(hint);
  if (!hint.empty()) {
    std::vector<const SourceCommand*> inside, anywhere;
    for (const auto& cmd : commands_) {
      bool match = truncated ? cmd.text.compare(0, hint.size(), hint) == 0 : cmd.text == hint;
      if (!match) continue;
      (cmd.top == top ? inside : anywhere).push_back(&cmd);
    }
    for (const auto* c : inside) {
      if (c->span.line == line) return c->span;
    }
    if (!inside.empty()) return inside.front()->span;
    if (anywhere.size() == 1) return anywhere.front()->span;
  }
  const SourceCommand* deepest = nullptr;
  for (const auto& cmd : commands_) {
    if (cmd.top != top || cmd.span.line != line) continue;
    if (deepest == nullptr || cmd.depth > deepest->depth) deepest = &cmd;
  }
  if (deepest != nullptr) return deepest->span;
  int start = lines_.LineStart(line);
  int end = start;
  while (end < static_cast<int>(text_.size()) && text_[end] != '\n') ++end;
  int b = start;
  while (b < end && (text_[b] == ' ' || text_[b] == '\t')) ++b;
  return lines_.Span(b, end);
}

}  // namespace asgard::lang
