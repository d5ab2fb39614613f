// Graphical edits as text patches (seed 4.2.2): a parameter is editable iff
// its element's command ran once and its word is a literal number or vector;
// an edit rewrites only the characters of that literal that change.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <unordered_map>

#include "core/session/elements.h"
#include "core/session/session.h"

namespace asgard::session {
namespace {

// Shortest text that reads back as exactly `v`.
std::string FormatNumber(double v) {
  if (v == 0) return "0";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string ReadOnlyReason(const scene::ElementBase& e, const scene::Word* w) {
  if (e.run_count > 1) return "made in a loop";
  if (e.in_proc) return "made in a proc";
  if (e.in_eval) return "built by eval";
  if (!e.command.known()) return "its command could not be located in the text";
  if (w && !w->literal) return w->reason.empty() ? "not a literal number" : w->reason;
  if (w && !w->span.known()) return "its word could not be located in the text";
  return "";
}

// The minimal edit turning text[begin, end) into `replacement`.
TextEdit Minimal(const std::string& text, int begin, int end, const std::string& replacement) {
  const std::string old = text.substr(begin, end - begin);
  size_t p = 0;
  while (p < old.size() && p < replacement.size() && old[p] == replacement[p]) ++p;
  size_t s = 0;
  while (s < old.size() - p && s < replacement.size() - p &&
         old[old.size() - 1 - s] == replacement[replacement.size() - 1 - s])
    ++s;
  TextEdit e;
  e.begin = begin + static_cast<int>(p);
  e.end = end - static_cast<int>(s);
  e.text = replacement.substr(p, replacement.size() - p - s);
  return e;
}

// The option words a parameter spans: one word, or -x -y -z for a force's
// "vector".
std::vector<std::string> Words(scene::ElementKind kind, const std::string& param) {
  const bool vector_of_words = kind == scene::ElementKind::kForce ||
                               kind == scene::ElementKind::kTorque ||
                               kind == scene::ElementKind::kLink;
  if (vector_of_words && param == "vector") return {"x", "y", "z"};
  return {param};
}

// The element addressed as `element`, or null with the error in `result`.
const ElementRef* FindOrReport(const std::vector<ElementRef>& elements, const std::string& element,
                               EditResult& result) {
  const ElementRef* e = Find(elements, element);
  if (!e) result.error = "no element '" + element + "'";
  return e;
}

// Who names what: the elements naming each body (a force, torque, link,
// trajectory or view on it) and each trajectory (a link or view along it).
struct NamedBy {
  std::unordered_map<std::string, std::vector<const ElementRef*>> body, trajectory;
};

NamedBy IndexNames(const std::vector<ElementRef>& elements) {
  using K = scene::ElementKind;
  NamedBy by;
  auto add = [](auto& map, const std::string& name, const ElementRef* x) {
    if (!name.empty()) map[name].push_back(x);
  };
  for (const ElementRef& x : elements) {
    switch (x.kind) {
      case K::kForce:
        add(by.body, static_cast<const scene::Force*>(x.base)->body, &x);
        break;
      case K::kTorque:
        add(by.body, static_cast<const scene::Torque*>(x.base)->body, &x);
        break;
      case K::kTrajectory:
        add(by.body, static_cast<const scene::Trajectory*>(x.base)->body, &x);
        break;
      case K::kLink: {
        const auto* link = static_cast<const scene::Link*>(x.base);
        add(by.body, link->body1, &x);
        if (link->body2 != link->body1) add(by.body, link->body2, &x);
        add(by.trajectory, link->trajectory, &x);
        break;
      }
      case K::kView: {
        const auto* view = static_cast<const scene::View*>(x.base);
        add(by.body, view->follow, &x);
        add(by.trajectory, view->trajectory, &x);
        break;
      }
      default:
        break;
    }
  }
  return by;
}

// `e` and, transitively, every element that names a body or trajectory
// among them: what deleting `e` removes so that nothing is left dangling.
std::vector<const ElementRef*> WithDependents(const ElementRef& e, const NamedBy& by) {
  using K = scene::ElementKind;
  std::vector<const ElementRef*> doomed = {&e};
  for (size_t i = 0; i < doomed.size(); ++i) {
    const ElementRef& d = *doomed[i];
    if (d.base->name.empty() || (d.kind != K::kBody && d.kind != K::kTrajectory)) continue;
    const auto& map = d.kind == K::kBody ? by.body : by.trajectory;
    const auto it = map.find(d.base->name);
    if (it == map.end()) continue;
    for (const ElementRef* x : it->second)
      if (std::find(doomed.begin(), doomed.end(), x) == doomed.end()) doomed.push_back(x);
  }
  return doomed;
}

// The edit removing a command and, when it stands alone on its lines,
// those lines.
TextEdit CommandSpan(const std::string& text, const scene::SourceSpan& command) {
  int begin = command.begin, end = command.end;
  int line_start = begin;
  while (line_start > 0 && text[line_start - 1] != '\n') --line_start;
  const size_t line_end = text.find('\n', end);
  const bool alone =
      text.find_first_not_of(" \t", line_start) == static_cast<size_t>(begin) &&
      (line_end == std::string::npos || text.find_first_not_of(" \t;", end) >= line_end);
  if (alone) {
    begin = line_start;
    end = line_end == std::string::npos ? static_cast<int>(text.size())
                                        : static_cast<int>(line_end) + 1;
  } else {
    // One of several commands on its line: with the ';' that separates it
    // from the next one (or, the last, from the one before) and the blanks.
    const size_t after = text.find_first_not_of(" \t", end);
    if (after != std::string::npos && text[after] == ';') {
      end = static_cast<int>(std::min(text.find_first_not_of(" \t", after + 1), text.size()));
    } else {
      size_t before = static_cast<size_t>(begin);
      while (before > 0 && (text[before - 1] == ' ' || text[before - 1] == '\t')) --before;
      if (before > 0 && text[before - 1] == ';') begin = static_cast<int>(before - 1);
    }
  }
  TextEdit edit;
  edit.begin = begin;
  edit.end = end;
  return edit;
}

}  // namespace

void Locate(TextEdit& edit, const std::string& text) {
  auto at = [&](int offset, int& line, int& column) {
    line = 1;
    column = 1;
    for (int i = 0; i < offset && i < static_cast<int>(text.size()); ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
  };
  at(edit.begin, edit.line, edit.column);
  at(edit.end, edit.end_line, edit.end_column);
}

std::vector<Parameter> Session::Parameters() const {
  std::vector<Parameter> out;
  for (const ElementRef& e : Elements(scene_)) {
    for (const auto& [key, word] : e.base->options) {
      Parameter p;
      p.kind = e.kind;
      p.element = e.key;
      p.param = key;
      p.value = word.text;
      p.span = word.span;
      p.reason = ReadOnlyReason(*e.base, &word);
      p.editable = p.reason.empty();
      out.push_back(std::move(p));
    }
  }
  return out;
}

std::vector<ElementInfo> Session::ElementInfos() const {
  std::vector<ElementInfo> out;
  const auto elements = Elements(scene_);
  const NamedBy by = IndexNames(elements);
  for (const ElementRef& e : elements) {
    ElementInfo info;
    info.kind = e.kind;
    info.element = e.key;
    info.reason = ReadOnlyReason(*e.base, nullptr);
    info.editable = info.reason.empty();
    const auto doomed = WithDependents(e, by);
    for (size_t i = 1; i < doomed.size(); ++i) info.deleted_with.push_back(doomed[i]->key);
    out.push_back(std::move(info));
  }
  return out;
}

std::vector<PrescribedInitial> Session::PrescribedInitials() const {
  using State = scene::Trajectory::State;
  // What each kind of trajectory sets (core/physics/equations.cc).
  static constexpr struct {
    State state;
    const char* param;
    const char* what;
  } kSets[] = {{State::kPos, "init_pos", "position"},
               {State::kPos, "init_dpos", "velocity"},
               {State::kDpos, "init_dpos", "velocity"},
               {State::kRot, "init_rot", "rotation"},
               {State::kRot, "init_drot", "angular velocity"},
               {State::kDrot, "init_drot", "angular velocity"}};
  std::vector<PrescribedInitial> out;
  const double start = scene_.simulator ? scene_.simulator->start : 0.0;
  auto number = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return std::string(buf);
  };
  for (const scene::Trajectory& t : scene_.trajectories) {
    if (t.body.empty() || t.knots.empty() || t.state == State::kNone) continue;
    const double from = t.from.value_or(t.knots.front().t);
    const double to = t.to.value_or(t.knots.back().t);
    if (!(from <= start && start < to)) continue;  // the override's interval
    for (const auto& set : kSets) {
      if (set.state != t.state) continue;
      const bool known = std::any_of(out.begin(), out.end(), [&](const PrescribedInitial& p) {
        return p.body == t.body && p.param == set.param;
      });
      if (!known)
        out.push_back({t.body, set.param,
                       "trajectory " + t.name + " prescribes its " + set.what +
                           " from t = " + number(from) + " to " + number(to)});
    }
  }
  return out;
}

EditResult Session::SetParameter(const std::string& element, const std::string& param,
                                 const std::vector<double>& values) {
  EditResult result;
  const auto elements = Elements(scene_);
  const ElementRef* e = FindOrReport(elements, element, result);
  if (!e) return result;
  for (double v : values)
    if (!std::isfinite(v)) {
      result.error = "values must be finite numbers";
      return result;
    }
  const auto words = Words(e->kind, param);
  std::vector<TextEdit> edits;
  if (words.size() > 1 && values.size() != words.size()) {
    result.error = param + " takes " + std::to_string(words.size()) + " numbers";
    return result;
  }
  for (size_t i = 0; i < words.size(); ++i) {
    const scene::Word* w = e->base->option(words[i]);
    const std::string reason = ReadOnlyReason(*e->base, w);
    if (!reason.empty()) {
      result.error = element + "." + param + " is read-only: " + reason;
      return result;
    }
    std::string body;
    const size_t first = words.size() > 1 ? i : 0, count = words.size() > 1 ? 1 : values.size();
    if (param == "points") {
      // Trajectory knots: {{t x y z} {t x y z} ...}
      if (values.size() % 4 != 0) {
        result.error = "points takes groups of four numbers: t x y z";
        return result;
      }
      for (size_t k = 0; k < values.size(); k += 4)
        body += std::string(k ? " " : "") + "{" + FormatNumber(values[k]) + " " +
                FormatNumber(values[k + 1]) + " " + FormatNumber(values[k + 2]) + " " +
                FormatNumber(values[k + 3]) + "}";
    } else {
      for (size_t k = first; k < first + count; ++k)
        body += (k > first ? " " : "") + FormatNumber(values[k]);
    }
    if (!w) {
      // Not written yet: append the option to the command.
      const std::string word = count > 1 ? "{" + body + "}" : body;
      TextEdit add;
      add.begin = add.end = e->base->command.end;
      add.text = " -" + words[i] + " " + word;
      edits.push_back(add);
      continue;
    }
    const std::string source = text_.substr(w->span.begin, w->span.end - w->span.begin);
    std::string replacement;
    if (!source.empty() && (source[0] == '{' || source[0] == '"'))
      replacement = source.substr(0, 1) + body + (source[0] == '{' ? "}" : "\"");
    else if (count > 1)
      replacement = "{" + body + "}";
    else
      replacement = body;
    edits.push_back(Minimal(text_, w->span.begin, w->span.end, replacement));
  }
  pending_key_ = element + '\0' + param;
  return ApplyEdits(std::move(edits));
}

EditResult Session::SetWord(const std::string& element, const std::string& param,
                            const std::string& text) {
  EditResult result;
  const auto elements = Elements(scene_);
  const ElementRef* e = FindOrReport(elements, element, result);
  if (!e) return result;
  const scene::Word* w = e->base->option(param);
  std::string reason = ReadOnlyReason(*e->base, nullptr);
  if (reason.empty() && !w) reason = "it has no -" + param;
  if (reason.empty() && !w->span.known()) reason = "its word could not be located in the text";
  if (reason.empty() && text_[w->span.begin] != '{') reason = "its word is not a braced literal";
  if (!reason.empty()) {
    result.error = element + "." + param + " is read-only: " + reason;
    return result;
  }
  // The new word must stay one braced word: balanced, unescaped braces.
  int depth = 0;
  for (size_t i = 0; i < text.size() && depth >= 0; ++i) {
    if (text[i] == '\\')
      ++i;
    else if (text[i] == '{')
      ++depth;
    else if (text[i] == '}')
      --depth;
  }
  if (depth != 0 || (!text.empty() && text.back() == '\\')) {
    result.error = "the new -" + param + " of " + element + " has unbalanced braces";
    return result;
  }
  const TextEdit edit = Minimal(text_, w->span.begin, w->span.end, "{" + text + "}");
  if (edit.begin == edit.end && edit.text.empty()) {  // the same word: no undo step
    result.ok = true;
    return result;
  }
  pending_key_ = element + '\0' + param;
  return ApplyEdits({edit});
}

EditResult Session::CreateElement(const std::string& command) {
  EditResult result;
  std::string cmd = command;
  while (!cmd.empty() && (cmd.back() == '\n' || cmd.back() == ' ')) cmd.pop_back();
  const std::string kind = cmd.substr(0, cmd.find(' '));
  // After the last command of the same kind, else at the end.
  int at = static_cast<int>(text_.size());
  bool found = false;
  for (const ElementRef& e : Elements(scene_)) {
    if (scene::ElementKindName(e.kind) != kind || e.base->run_count != 1 ||
        !e.base->command.known())
      continue;
    if (!found || e.base->command.end > at) at = e.base->command.end;
    found = true;
  }
  TextEdit edit;
  if (found) {
    // After the end of that command's line.
    const size_t eol = text_.find('\n', at);
    at = eol == std::string::npos ? static_cast<int>(text_.size()) : static_cast<int>(eol) + 1;
    edit.begin = edit.end = at;
    edit.text = cmd + "\n";
    if (eol == std::string::npos) edit.text = "\n" + edit.text;
  } else {
    edit.begin = edit.end = static_cast<int>(text_.size());
    edit.text = (text_.empty() || text_.back() == '\n' ? "" : "\n") + cmd + "\n";
  }
  return ApplyEdits({edit});
}

EditResult Session::DeleteElement(const std::string& element) {
  EditResult result;
  const auto elements = Elements(scene_);
  const ElementRef* e = FindOrReport(elements, element, result);
  if (!e) return result;
  const std::vector<const ElementRef*> doomed = WithDependents(*e, IndexNames(elements));
  std::vector<TextEdit> edits;
  for (const ElementRef* d : doomed) {
    const std::string reason = ReadOnlyReason(*d->base, nullptr);
    if (!reason.empty()) {
      result.error = d == e ? element + " cannot be deleted here: " + reason
                            : element + " cannot be deleted here: " + d->key +
                                  ", which names it, is " + reason + " (edit the text)";
      return result;
    }
    edits.push_back(CommandSpan(text_, d->base->command));
    if (d != e) result.removed.push_back(d->key);
  }
  // Spans of commands on one line may touch; never overlap them.
  std::sort(edits.begin(), edits.end(),
            [](const TextEdit& a, const TextEdit& b) { return a.begin < b.begin; });
  std::vector<TextEdit> merged;
  for (const TextEdit& x : edits) {
    if (!merged.empty() && x.begin < merged.back().end)
      merged.back().end = std::max(merged.back().end, x.end);
    else
      merged.push_back(x);
  }
  EditResult applied = ApplyEdits(std::move(merged));
  applied.removed = std::move(result.removed);
  return applied;
}

EditResult Session::ApplyEdits(std::vector<TextEdit> edits) {
  EditResult result;
  std::sort(edits.begin(), edits.end(),
            [](const TextEdit& a, const TextEdit& b) { return a.begin < b.begin; });
  std::string next = text_;
  for (auto it = edits.rbegin(); it != edits.rend(); ++it)
    next.replace(it->begin, it->end - it->begin, it->text);
  for (TextEdit& e : edits) Locate(e, text_);
  pending_edits_ = edits;
  Adopt(next, true);
  result.ok = true;
  result.edits = std::move(edits);
  return result;
}

}  // namespace asgard::session
