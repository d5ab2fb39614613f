// Post-evaluation pass: run counts, loop-made words, cross references.
//
// Design: the run count of a command is only known once the whole script
// has run, so every element gets it here (by its command span), and words of
// elements whose command ran more than once lose their literal flag ("made
// in a loop": rewriting the source word would change all of them).
// References are checked here as well, so a link may name a body defined
// further down.  Bodies are checked first; links, forces, torques and
// trajectories are then checked against the bodies that survived, with a
// message that says whether the body is unknown or failed earlier.
#include <algorithm>

#include "core/lang/elements.h"
#include "core/lang/eval_context.h"

namespace asgard::lang {
namespace {

template <typename T>
void FinishBase(const EvalContext& ctx, std::vector<T>& items) {
  for (T& item : items) {
    auto it = ctx.run_counts.find(item.command.begin);
    item.run_count = it == ctx.run_counts.end() ? 1 : std::max(1, it->second);
    if (item.run_count > 1) {
      for (auto& [key, word] : item.options) {
        word.literal = false;
        word.reason = "made in a loop";
      }
    }
  }
}

scene::SourceSpan OptionSpan(const scene::ElementBase& e, const char* key) {
  const scene::Word* w = e.option(key);
  return w != nullptr && w->span.known() ? w->span : e.command;
}

class RefChecker {
 public:
  explicit RefChecker(EvalContext& ctx) : ctx_(ctx) {}

  // True if `name` is a surviving element of `kind`; else records an error.
  bool Check(const scene::ElementBase& e, const char* what, const char* option,
             const std::string& name, scene::ElementKind kind, bool exists) {
    if (exists) return true;
    std::string msg = std::string(what) + ": ";
    const char* kind_name = scene::ElementKindName(kind);
    auto failed = ctx_.failed.find(kind);
    if (failed != ctx_.failed.end() && failed->second.count(name) != 0) {
      msg += std::string(kind_name) + " '" + name + "' was not created because of an earlier error";
    } else {
      msg += "unknown " + std::string(kind_name) + " '" + name + "'";
    }
    ctx_.AddError(msg, OptionSpan(e, option));
    return false;
  }

 private:
  EvalContext& ctx_;
};

template <typename T, typename Pred>
void DropIf(std::vector<T>& items, Pred bad) {
  items.erase(std::remove_if(items.begin(), items.end(), bad), items.end());
}

}  // namespace

void FinishScene(EvalContext& ctx) {
  scene::Scene& s = ctx.scene;
  if (s.simulator) {
    std::vector<scene::Simulator> one{*s.simulator};
    FinishBase(ctx, one);
    s.simulator = one[0];
  }
  FinishBase(ctx, s.shape_sets);
  FinishBase(ctx, s.bodies);
  FinishBase(ctx, s.links);
  FinishBase(ctx, s.forces);
  FinishBase(ctx, s.torques);
  FinishBase(ctx, s.trajectories);
  FinishBase(ctx, s.lights);
  FinishBase(ctx, s.views);

  using K = scene::ElementKind;
  RefChecker refs(ctx);
  auto body_ok = [&](const scene::ElementBase& e, const char* what, const char* option,
                     const std::string& name) {
    return refs.Check(e, what, option, name, K::kBody, s.FindBody(name) != nullptr);
  };
  auto trajectory_ok = [&](const scene::ElementBase& e, const char* what, const char* option,
                           const std::string& name) {
    return refs.Check(e, what, option, name, K::kTrajectory, s.FindTrajectory(name) != nullptr);
  };

  DropIf(s.bodies, [&](const scene::Body& b) {
    bool ok = refs.Check(b, ("body '" + b.name + "'").c_str(), "shape", b.shape, K::kShapeSet,
                         s.FindShapeSet(b.shape) != nullptr);
    if (!ok) ctx.failed[K::kBody].insert(b.name);
    return !ok;
  });
  DropIf(s.trajectories, [&](const scene::Trajectory& t) {
    std::string what = "trajectory '" + t.name + "'";
    bool ok = t.body.empty() || body_ok(t, what.c_str(), "body", t.body);
    if (ok && s.FindBody(t.name) != nullptr) {
      ctx.AddError(what + ": the name is also used by a body", t.command);
      ok = false;
    }
    if (!ok) ctx.failed[K::kTrajectory].insert(t.name);
    return !ok;
  });
  DropIf(s.links, [&](const scene::Link& l) {
    bool ok = body_ok(l, "link", "body1", l.body1);
    if (!l.body2.empty()) ok = body_ok(l, "link", "body2", l.body2) && ok;
    if (!l.trajectory.empty()) ok = trajectory_ok(l, "link", "trajectory", l.trajectory) && ok;
    return !ok;
  });
  DropIf(s.forces, [&](const scene::Force& f) { return !body_ok(f, "force", "body", f.body); });
  DropIf(s.torques, [&](const scene::Torque& t) { return !body_ok(t, "torque", "body", t.body); });
  CheckViewExpressions(ctx);
}

}  // namespace asgard::lang
