// Uniform access to a scene's elements for change analysis and editing.
#pragma once

#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace asgard::session {

struct ElementRef {
  scene::ElementKind kind;
  int index;  // among the elements of its kind
  const scene::ElementBase* base;
  // The name used to address it: its name, "simulator", or kind#index.
  std::string key;
  bool named;
};

std::vector<ElementRef> Elements(const scene::Scene& s);
const ElementRef* Find(const std::vector<ElementRef>& elements, const std::string& key);

// Content of an element as written: kind, name and options (not where it is).
// With `without_initial_state`, a body's -init_* options are left out.
std::string Signature(const ElementRef& e, bool without_initial_state = false);

// Whether the option is part of a body's initial state.
bool IsInitialState(const std::string& option);

}  // namespace asgard::session
