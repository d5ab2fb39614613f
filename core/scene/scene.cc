#include "core/scene/scene.h"

#include <algorithm>

namespace asgard::scene {

const char* ElementKindName(ElementKind kind) {
  switch (kind) {
    case ElementKind::kSimulator: return "simulator";
    case ElementKind::kShapeSet: return "shape_set";
    case ElementKind::kBody: return "body";
    case ElementKind::kLink: return "link";
    case ElementKind::kForce: return "force";
    case ElementKind::kTorque: return "torque";
    case ElementKind::kTrajectory: return "trajectory";
    case ElementKind::kLightSource: return "lightsource";
    case ElementKind::kView: return "view";
  }
  return "?";
}

const Word* ElementBase::option(const std::string& key) const {
  for (const auto& [k, w] : options) {
    if (k == key) return &w;
  }
  return nullptr;
}

bool Scene::has_errors() const {
  return std::any_of(diagnostics.begin(), diagnostics.end(),
                     [](const Diagnostic& d) { return d.severity == Severity::kError; });
}

namespace {
template <typename T>
const T* FindByName(const std::vector<T>& items, const std::string& name) {
  for (const T& item : items) {
    if (item.name == name) return &item;
  }
  return nullptr;
}
}  // namespace

const ShapeSet* Scene::FindShapeSet(const std::string& name) const {
  return FindByName(shape_sets, name);
}
const Body* Scene::FindBody(const std::string& name) const { return FindByName(bodies, name); }
const Trajectory* Scene::FindTrajectory(const std::string& name) const {
  return FindByName(trajectories, name);
}

}  // namespace asgard::scene
