// The session: one text, one history, many views; incremental simulation
// (design note in session.h).
#include "core/session/session.h"

#include <algorithm>
#include <chrono>
#include <set>

#include "core/lang/lang.h"
#include "core/session/elements.h"

namespace asgard::session {
namespace {

// Kinds whose order in the script enters the equations (sums of forces,
// indices of bodies and trajectories); reordering them reforms equations so
// that results stay equal to a from-scratch run bit for bit.
bool OrderMatters(scene::ElementKind kind) {
  return kind == scene::ElementKind::kBody || kind == scene::ElementKind::kLink ||
         kind == scene::ElementKind::kForce || kind == scene::ElementKind::kTorque ||
         kind == scene::ElementKind::kTrajectory;
}

bool AffectsMotion(scene::ElementKind kind) {
  return kind != scene::ElementKind::kLightSource && kind != scene::ElementKind::kView;
}

}  // namespace

Session::Session(std::string text, pipeline::RunOptions options) : options_(std::move(options)) {
  options_.allow_scene_errors = true;
  text_ = std::move(text);
  scene_ = lang::Evaluate(text_);
  history_.push_back(text_);
}

Session::~Session() = default;

std::vector<scene::Diagnostic> Session::diagnostics() const {
  if (run_ && !structure_dirty_) return run_->diagnostics;
  return scene_.diagnostics;
}

std::vector<ElementChange> Session::UpdateText(const std::string& text) {
  return Adopt(text, true);
}

std::vector<ElementChange> Session::Adopt(const std::string& text, bool record) {
  scene::Scene next = lang::Evaluate(text);
  const auto changes = Diff(scene_, text_, next, text);
  const auto old_elements = Elements(scene_), new_elements = Elements(next);
  auto find = [](const std::vector<ElementRef>& list, scene::ElementKind kind, int index) {
    for (const auto& e : list)
      if (e.kind == kind && e.index == index) return &e;
    return static_cast<const ElementRef*>(nullptr);
  };
  for (const ElementChange& c : changes) {
    if (!AffectsMotion(c.kind)) continue;
    if (c.change == Change::kUnchanged) {
      if (OrderMatters(c.kind) && c.old_index != c.new_index) structure_dirty_ = true;
      continue;
    }
    if (c.change == Change::kModified && c.kind == scene::ElementKind::kBody &&
        c.old_index == c.new_index) {
      const ElementRef* o = find(old_elements, c.kind, c.old_index);
      const ElementRef* n = find(new_elements, c.kind, c.new_index);
      if (o && n && Signature(*o, true) == Signature(*n, true)) {
        dirty_bodies_.push_back(c.name);  // only its initial state changed
        continue;
      }
    }
    structure_dirty_ = true;
  }
  // The edits every language view applies to its copy of the text.
  std::vector<TextEdit> edits = std::move(pending_edits_);
  pending_edits_.clear();
  if (edits.empty() && text != text_) {
    TextEdit e;
    const int n = static_cast<int>(std::min(text.size(), text_.size()));
    while (e.begin < n && text[e.begin] == text_[e.begin]) ++e.begin;
    int s = 0;
    while (s < n - e.begin && text[text.size() - 1 - s] == text_[text_.size() - 1 - s]) ++s;
    e.end = static_cast<int>(text_.size()) - s;
    e.text = text.substr(e.begin, text.size() - s - e.begin);
    Locate(e, text_);
    edits.push_back(std::move(e));
  }
  text_ = text;
  scene_ = std::move(next);
  if (record) {
    // Another step of the same parameter's drag replaces its entry.
    const bool same_drag = !pending_key_.empty() && pending_key_ == open_key_ &&
                           history_index_ > 0 && history_index_ + 1 == history_.size();
    if (same_drag) {
      history_[history_index_] = text_;
    } else {
      history_.resize(history_index_ + 1);
      history_.push_back(text_);
      ++history_index_;
    }
  }
  open_key_ = record ? pending_key_ : std::string();
  pending_key_.clear();
  for (auto& [id, view] : views_) {
    view->TextChanged(edits, text_);
    view->SceneChanged(changes);
  }
  return changes;
}

void Session::FullRun(const std::function<void(double)>& progress) {
  pipeline::RunOptions opts = options_;
  opts.progress = progress;
  run_ = std::make_unique<pipeline::Run>(pipeline::Simulate(scene_, opts));
  stats_.rebuilt = true;
  stats_.components = run_->simulation ? run_->simulation->component_count() : 0;
  stats_.components_reset = stats_.components;
  stats_.steps = run_->simulation ? run_->simulation->totals().steps : 0;
}

bool Session::Simulate(const std::function<void(double)>& progress) {
  open_key_.clear();  // a drag ends with a simulation
  const auto start = std::chrono::steady_clock::now();
  stats_ = {};
  bool static_moved = false;
  if (run_ && run_->equations)
    for (const auto& name : dirty_bodies_) {
      const int b = run_->equations->FindBody(name);
      static_moved |= b < 0 || run_->equations->bodies[b].first_var < 0;
    }
  if (!run_ || !run_->simulation) {
    FullRun(progress);
  } else if (structure_dirty_ || static_moved) {
    CarryOverRun(progress);
  } else if (!dirty_bodies_.empty()) {
    auto& eq = *run_->equations;
    auto& sim = *run_->simulation;
    std::set<int> components;
    for (const auto& name : dirty_bodies_) {
      const int b = eq.FindBody(name);
      const scene::Body* body = scene_.FindBody(name);
      physics::BodyModel& m = eq.bodies[b];
      physics::SetInitialState(m, *body);
      const auto values = physics::InitialValues(m);
      for (int s = 0; s < physics::kBodySlots; ++s) {
        eq.variables[m.first_var + s].initial = values[s];
        components.insert(sim.component_of(m.first_var + s));
      }
    }
    const long steps_before = sim.totals().steps;
    for (int c : components) sim.ResetToStart(c);
    stats_.components = sim.component_count();
    for (int c = 0; c < sim.component_count(); ++c)
      stats_.components_reset += sim.component(c).waveform().size() == 1 ? 1 : 0;
    const bool ok = sim.Run(progress);
    run_->ok = ok;
    run_->solver_error = ok ? "" : sim.error();
    stats_.steps = sim.totals().steps - steps_before;
  }
  // Elements that only pictures use (light sources, views) may have changed
  // without a new run: the run's scene, which samplers draw, takes them.
  if (run_) {
    run_->scene.lights = scene_.lights;
    run_->scene.views = scene_.views;
  }
  dirty_bodies_.clear();
  structure_dirty_ = false;
  stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (auto& [id, view] : views_) view->Simulated();
  return run_ && run_->ok;
}

bool Session::Undo() {
  if (!CanUndo()) return false;
  --history_index_;
  Adopt(history_[history_index_], false);
  return true;
}

bool Session::Redo() {
  if (!CanRedo()) return false;
  ++history_index_;
  Adopt(history_[history_index_], false);
  return true;
}

int Session::AddView(SessionView* view) {
  views_.push_back({next_view_, view});
  return next_view_++;
}

void Session::RemoveView(int id) {
  std::erase_if(views_, [id](const auto& v) { return v.first == id; });
}

}  // namespace asgard::session
