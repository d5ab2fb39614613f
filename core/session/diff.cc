// Change analysis (seed 4.2.2): which elements were added, removed, renamed
// or modified between two evaluations of a scene.
//
//   old text  ──────────┬────────── edited region ─────────┬──────────
//   new text  ──────────┴──────── (common prefix/suffix) ──┴──────────
//
// Named elements match by name.  Unnamed ones (forces, links, nameless lights
// and views) match in three passes: (1) same place — the old command's span,
// carried through the edit, equals a new command's span; (2) same content
// anywhere (a command moved); (3) old commands the edit touched, in order,
// with new commands inside the edited region (modified).  What is left was
// removed or added.  A named element that vanished where one of a new name
// appeared, at the same place, was renamed.
#include <algorithm>
#include <map>
#include <sstream>

#include "core/session/elements.h"
#include "core/session/session.h"

namespace asgard::session {
namespace {

std::string KindKey(scene::ElementKind kind, int index) {
  return std::string(scene::ElementKindName(kind)) + "#" + std::to_string(index);
}

template <typename T>
void Add(std::vector<ElementRef>& out, scene::ElementKind kind, const std::vector<T>& items,
         bool always_named) {
  for (size_t i = 0; i < items.size(); ++i) {
    const bool named = always_named || !items[i].name.empty();
    out.push_back({kind, static_cast<int>(i), &items[i],
                   named ? items[i].name : KindKey(kind, static_cast<int>(i)), named});
  }
}

// The edited region: [prefix, old_size - suffix) of the old text became
// [prefix, new_size - suffix) of the new one.
struct Region {
  int prefix = 0, suffix = 0, old_size = 0, new_size = 0;
  // Where an old span is in the new text, or false if the edit touched it.
  bool Map(const scene::SourceSpan& s, int& begin, int& end) const {
    if (s.end <= prefix) {
      begin = s.begin;
      end = s.end;
      return true;
    }
    if (s.begin >= old_size - suffix) {
      begin = s.begin + (new_size - old_size);
      end = s.end + (new_size - old_size);
      return true;
    }
    return false;
  }
  bool Inside(const scene::SourceSpan& s) const {  // new span overlaps the edit
    return s.end > prefix && s.begin < new_size - suffix;
  }
};

Region FindRegion(const std::string& a, const std::string& b) {
  Region r;
  r.old_size = static_cast<int>(a.size());
  r.new_size = static_cast<int>(b.size());
  const int n = std::min(r.old_size, r.new_size);
  while (r.prefix < n && a[r.prefix] == b[r.prefix]) ++r.prefix;
  while (r.suffix < n - r.prefix &&
         a[r.old_size - 1 - r.suffix] == b[r.new_size - 1 - r.suffix])
    ++r.suffix;
  return r;
}

}  // namespace

std::vector<ElementRef> Elements(const scene::Scene& s) {
  std::vector<ElementRef> out;
  if (s.simulator)
    out.push_back({scene::ElementKind::kSimulator, 0, &*s.simulator, "simulator", true});
  Add(out, scene::ElementKind::kShapeSet, s.shape_sets, true);
  Add(out, scene::ElementKind::kBody, s.bodies, true);
  Add(out, scene::ElementKind::kTrajectory, s.trajectories, true);
  Add(out, scene::ElementKind::kLink, s.links, false);
  Add(out, scene::ElementKind::kForce, s.forces, false);
  Add(out, scene::ElementKind::kTorque, s.torques, false);
  Add(out, scene::ElementKind::kLightSource, s.lights, false);
  Add(out, scene::ElementKind::kView, s.views, false);
  return out;
}

const ElementRef* Find(const std::vector<ElementRef>& elements, const std::string& key) {
  for (const auto& e : elements)
    if (e.key == key) return &e;
  return nullptr;
}

bool IsInitialState(const std::string& option) {
  return option == "init_pos" || option == "init_rot" || option == "init_dpos" ||
         option == "init_drot";
}

std::string Signature(const ElementRef& e, bool without_initial_state) {
  std::vector<std::string> parts;
  for (const auto& [key, word] : e.base->options) {
    if (without_initial_state && e.kind == scene::ElementKind::kBody && IsInitialState(key)) continue;
    parts.push_back(key + "=" + word.text);
  }
  std::sort(parts.begin(), parts.end());
  std::string sig = std::string(scene::ElementKindName(e.kind)) + "\x1f" + e.base->name;
  for (const auto& p : parts) sig += "\x1f" + p;
  return sig;
}

std::vector<ElementChange> Diff(const scene::Scene& before, const std::string& before_text,
                                const scene::Scene& after, const std::string& after_text) {
  const auto old_elements = Elements(before);
  const auto new_elements = Elements(after);
  const Region region = FindRegion(before_text, after_text);
  std::vector<char> old_used(old_elements.size(), 0), new_used(new_elements.size(), 0);
  std::vector<ElementChange> out;
  auto emit = [&](size_t o, size_t n, Change c) {
    ElementChange ch;
    const ElementRef& e = n < new_elements.size() ? new_elements[n] : old_elements[o];
    ch.kind = e.kind;
    ch.change = c;
    ch.name = e.base->name;
    if (o < old_elements.size()) ch.old_index = old_elements[o].index;
    if (n < new_elements.size()) ch.new_index = new_elements[n].index;
    if (c == Change::kRenamed) ch.old_name = old_elements[o].base->name;
    out.push_back(ch);
    if (o < old_elements.size()) old_used[o] = 1;
    if (n < new_elements.size()) new_used[n] = 1;
  };
  const size_t none = static_cast<size_t>(-1);
  auto same_content = [&](size_t o, size_t n) {
    return Signature(old_elements[o]) == Signature(new_elements[n]);
  };
  // Named elements by name.
  for (size_t o = 0; o < old_elements.size(); ++o) {
    if (!old_elements[o].named) continue;
    for (size_t n = 0; n < new_elements.size(); ++n) {
      if (new_used[n] || !new_elements[n].named || new_elements[n].kind != old_elements[o].kind ||
          new_elements[n].key != old_elements[o].key)
        continue;
      emit(o, n, same_content(o, n) ? Change::kUnchanged : Change::kModified);
      break;
    }
  }
  // Pass 1: same place (also renames of named elements).
  for (size_t o = 0; o < old_elements.size(); ++o) {
    if (old_used[o]) continue;
    int b, e;
    if (!region.Map(old_elements[o].base->command, b, e)) continue;
    for (size_t n = 0; n < new_elements.size(); ++n) {
      const auto& ne = new_elements[n];
      if (new_used[n] || ne.kind != old_elements[o].kind || ne.named != old_elements[o].named ||
          ne.base->command.begin != b || ne.base->command.end != e)
        continue;
      if (ne.named) emit(o, n, Change::kRenamed);
      else emit(o, n, same_content(o, n) ? Change::kUnchanged : Change::kModified);
      break;
    }
  }
  // Renamed in place: the edit touched the command, and apart from the name
  // the content is the same.
  auto nameless = [](const ElementRef& e) {
    std::string sig = Signature(e);
    const size_t a = sig.find('\x1f'), b = sig.find('\x1f', a + 1);
    return sig.substr(0, a) + (b == std::string::npos ? "" : sig.substr(b));
  };
  for (size_t o = 0; o < old_elements.size(); ++o) {
    int b, e;
    if (old_used[o] || !old_elements[o].named ||
        region.Map(old_elements[o].base->command, b, e))
      continue;
    for (size_t n = 0; n < new_elements.size(); ++n) {
      const auto& ne = new_elements[n];
      if (new_used[n] || !ne.named || ne.kind != old_elements[o].kind ||
          !region.Inside(ne.base->command) || nameless(ne) != nameless(old_elements[o]))
        continue;
      emit(o, n, Change::kRenamed);
      break;
    }
  }
  // Pass 2: same content elsewhere (moved).
  for (size_t o = 0; o < old_elements.size(); ++o) {
    if (old_used[o] || old_elements[o].named) continue;
    for (size_t n = 0; n < new_elements.size(); ++n) {
      if (new_used[n] || new_elements[n].named || new_elements[n].kind != old_elements[o].kind ||
          !same_content(o, n))
        continue;
      emit(o, n, Change::kUnchanged);
      break;
    }
  }
  // Pass 3: touched by the edit, in order.
  for (size_t o = 0; o < old_elements.size(); ++o) {
    if (old_used[o] || old_elements[o].named) continue;
    int b, e;
    if (region.Map(old_elements[o].base->command, b, e)) continue;
    for (size_t n = 0; n < new_elements.size(); ++n) {
      if (new_used[n] || new_elements[n].named || new_elements[n].kind != old_elements[o].kind ||
          !region.Inside(new_elements[n].base->command))
        continue;
      emit(o, n, Change::kModified);
      break;
    }
  }
  for (size_t o = 0; o < old_elements.size(); ++o)
    if (!old_used[o]) emit(o, none, Change::kRemoved);
  for (size_t n = 0; n < new_elements.size(); ++n)
    if (!new_used[n]) emit(none, n, Change::kAdded);
  return out;
}

const char* ChangeName(Change c) {
  switch (c) {
    case Change::kUnchanged: return "unchanged";
    case Change::kModified: return "modified";
    case Change::kAdded: return "added";
    case Change::kRemoved: return "removed";
    case Change::kRenamed: return "renamed";
  }
  return "?";
}

}  // namespace asgard::session
