// Incremental re-simulation after an edit that changed equations.
//
//   old run ──┐                          ┌── component unchanged and all its
//             ├─ match variables by name ┤   inputs unchanged: results copied
//   new equations ┘                      └── otherwise: computed afresh
//
// Two equations are the same when their expression DAGs are structurally
// identical — operators, constants to the bit, operands in the same order,
// variables matched by name and trajectory functions by name and knots.  The
// comparison is deliberately strict: operand order decides the order of
// floating-point operations, so only an identical DAG is guaranteed to give
// identical numbers, and results carried over must equal a from-scratch run
// bit for bit.  Impacts between two carried-over bodies stay; an impact
// between a carried-over body and a changed one cuts the carried-over body
// back to just before it.
#include <algorithm>
#include <cstring>
#include <map>
#include <set>

#include "core/physics/trajectory.h"
#include "core/session/elements.h"
#include "core/session/session.h"

namespace asgard::session {
namespace {

class Matcher {
 public:
  Matcher(const physics::EquationSystem& a, const physics::EquationSystem& b,
          const scene::Scene& sa, const scene::Scene& sb)
      : a_(a), b_(b) {
    std::map<std::string, int> by_name;
    for (size_t i = 0; i < a.variables.size(); ++i)
      by_name[a.variables[i].name] = static_cast<int>(i);
    var_.assign(b.variables.size(), -1);
    for (size_t i = 0; i < b.variables.size(); ++i) {
      auto it = by_name.find(b.variables[i].name);
      if (it != by_name.end()) var_[i] = it->second;
    }
    curve_.assign(b.curves.size(), -1);
    for (size_t k = 0; k < b.curves.size() && k < sb.trajectories.size(); ++k)
      for (size_t j = 0; j < a.curves.size() && j < sa.trajectories.size(); ++j)
        if (sa.trajectories[j].name == sb.trajectories[k].name &&
            a.curves[j]->times == b.curves[k]->times && a.curves[j]->points == b.curves[k]->points)
          curve_[k] = static_cast<int>(j);
  }

  // Old variable for new variable i, or -1.
  int OldVariable(int i) const { return var_[i]; }

  bool SameVariable(int i) {
    const int o = var_[i];
    if (o < 0) return false;
    const auto& nv = b_.variables[i];
    const auto& ov = a_.variables[o];
    if (std::memcmp(&nv.initial, &ov.initial, sizeof(double)) != 0 ||
        nv.breakpoints != ov.breakpoints || nv.overrides.size() != ov.overrides.size() ||
        !Same(ov.rhs, nv.rhs))
      return false;
    for (size_t k = 0; k < nv.overrides.size(); ++k) {
      const auto &x = ov.overrides[k], &y = nv.overrides[k];
      if (x.kind != y.kind || x.from != y.from || x.to != y.to || !Same(x.expr, y.expr))
        return false;
    }
    return true;
  }

 private:
  bool Same(expr::NodeId x, expr::NodeId y) {
    const auto key = std::make_pair(x, y);
    if (auto it = memo_.find(key); it != memo_.end()) return it->second;
    const expr::Node& p = a_.pool.node(x);
    const expr::Node& q = b_.pool.node(y);
    bool same = p.op == q.op && p.order == q.order && p.args.size() == q.args.size() &&
                std::memcmp(&p.value, &q.value, sizeof(double)) == 0;
    if (same && p.op == expr::Op::kVar)
      same = var_[q.index] == p.index;
    else if (same && p.op == expr::Op::kExtern)
      same = p.index % 3 == q.index % 3 && curve_[q.index / 3] == p.index / 3;
    else if (same)
      same = p.index == q.index;
    for (size_t k = 0; same && k < p.args.size(); ++k) same = Same(p.args[k], q.args[k]);
    memo_[key] = same;
    return same;
  }

  const physics::EquationSystem& a_;
  const physics::EquationSystem& b_;
  std::vector<int> var_, curve_;
  std::map<std::pair<expr::NodeId, expr::NodeId>, bool> memo_;
};

}  // namespace

void Session::CarryOverRun(const std::function<void(double)>& progress) {
  std::unique_ptr<pipeline::Run> old = std::move(run_);
  pipeline::RunOptions opts = options_;
  opts.prepare_only = true;
  run_ = std::make_unique<pipeline::Run>(pipeline::Simulate(scene_, opts));
  stats_.rebuilt = true;
  if (!run_->simulation) return;
  auto& sim = *run_->simulation;
  const auto& ne = *run_->equations;
  const auto& oe = *old->equations;
  const auto& osim = *old->simulation;
  Matcher match(oe, ne, old->scene, run_->scene);
  // Components in dependency order: clean when every variable is the same,
  // they were one component before, and every input component is clean.
  std::vector<char> clean(sim.component_count(), 0);
  for (int c = 0; c < sim.component_count(); ++c) {
    const auto& vars = sim.component(c).variables();
    int oc = -1;
    bool ok = true;
    for (int v : vars) {
      ok = ok && match.SameVariable(v);
      if (!ok) break;
      const int o = osim.component_of(match.OldVariable(v));
      if (oc < 0) oc = o;
      ok = ok && o == oc;
    }
    ok = ok && oc >= 0 && osim.component(oc).variables().size() == vars.size();
    for (int u : sim.partition().upstream[c]) ok = ok && clean[u];
    if (!ok) continue;
    clean[c] = 1;
    sim.CopyResults(c, osim.component(oc));
  }
  // A moving body whose every component was carried over.
  auto body_clean = [&](int b) {
    const auto& m = ne.bodies[b];
    for (int k = 0; k < physics::kBodySlots; ++k)
      if (!clean[sim.component_of(m.first_var + k)]) return false;
    return true;
  };
  std::map<std::string, int> new_body;
  for (size_t b = 0; b < ne.bodies.size(); ++b) new_body[ne.bodies[b].name] = static_cast<int>(b);
  // What the collision monitor reads of a body besides its motion: its
  // pieces, how it bounces and rubs, whether it is tested.  A change of
  // any of these voids its events (its motion before the first stands).
  auto same_piece = [](const physics::BodyPiece& x, const physics::BodyPiece& y) {
    return x.is_sphere == y.is_sphere && x.center == y.center && x.radius == y.radius &&
           x.hull.vertices == y.hull.vertices;
  };
  auto collides_same = [&](int ob, int nb) {
    const auto &x = oe.bodies[ob], &y = ne.bodies[nb];
    return x.is_static == y.is_static && x.collision_test == y.collision_test &&
           x.restitution == y.restitution && x.friction == y.friction && x.artbody == y.artbody &&
           std::equal(x.pieces.begin(), x.pieces.end(), y.pieces.begin(), y.pieces.end(),
                      same_piece);
  };
  auto static_same = [&](int ob, int nb) {
    const auto &x = oe.bodies[ob], &y = ne.bodies[nb];
    return x.x0 == y.x0 && x.q0.coeffs() == y.q0.coeffs() && collides_same(ob, nb);
  };
  if (old->collisions && run_->collisions) {
    // The landing gap is the whole scene's (the smallest body, the
    // tolerance): where it changed, no event stands.
    const bool same_gap = old->collisions->separation() == run_->collisions->separation();
    // The bodies carried over (a static one: the same body as before).
    std::map<std::string, int> old_body;
    for (size_t b = 0; b < oe.bodies.size(); ++b) old_body[oe.bodies[b].name] = static_cast<int>(b);
    std::vector<char> carried(ne.bodies.size(), 0);
    for (size_t b = 0; b < ne.bodies.size(); ++b) {
      const int nb = static_cast<int>(b);
      auto it = old_body.find(ne.bodies[b].name);
      if (it == old_body.end()) continue;
      carried[b] = same_gap &&
                   (ne.bodies[b].first_var < 0 ? static_same(it->second, nb)
                                               : body_clean(nb) && collides_same(it->second, nb));
    }
    std::vector<solver::Impact> keep;
    for (const auto& imp : old->collisions->impacts()) {
      // Every body whose variables jumped at the event (both of an impact,
      // the whole island of a resting solve) must be carried over unchanged
      // for the event to stand; its indices are this run's.
      std::vector<int> involved = {imp.a, imp.b};
      for (int b : imp.bodies)
        if (std::find(involved.begin(), involved.end(), b) == involved.end()) involved.push_back(b);
      std::map<int, int> to_new;  // old index → new index, for the bodies carried over
      std::vector<int> copied;    // new indices of the moving bodies whose results were copied
      bool all_ok = true;
      for (int ob : involved) {
        auto it = new_body.find(oe.bodies[ob].name);
        const bool ok = it != new_body.end() && carried[static_cast<size_t>(it->second)];
        if (ok) to_new[ob] = it->second;
        all_ok = all_ok && ok;
        if (it != new_body.end() && ne.bodies[it->second].first_var >= 0 && body_clean(it->second))
          copied.push_back(it->second);
      }
      if (all_ok) {
        solver::Impact moved = imp;
        moved.a = std::min(to_new[imp.a], to_new[imp.b]);
        moved.b = std::max(to_new[imp.a], to_new[imp.b]);
        if (moved.a != to_new[imp.a]) moved.normal = -moved.normal;  // from a towards b
        for (int& b : moved.bodies) b = to_new[b];
        for (int& b : moved.slow) b = to_new[b];
        keep.push_back(moved);
        continue;
      }
      // The copied motion after the event depended on what changed (a body's
      // own bounce, when only that changed).
      for (int nb : copied) {
        for (int k = 0; k < physics::kBodySlots; ++k)
          sim.Truncate(sim.component_of(ne.bodies[nb].first_var + k), imp.t, /*strict=*/true);
      }
    }
    run_->collisions->AdoptImpacts(keep, carried);
  }
  stats_.components = sim.component_count();
  for (char c : clean) stats_.components_reset += c ? 0 : 1;
  const long steps_before = sim.totals().steps;
  run_->ok = sim.Run(progress);
  if (!run_->ok) run_->solver_error = sim.error();
  stats_.steps = sim.totals().steps - steps_before;
}

}  // namespace asgard::session
