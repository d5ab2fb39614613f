// Exact joints (design note in joints.h).
#include "core/physics/joints.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace asgard::physics {
namespace {

// Baumgarte rate Ω (1/s) of C̈ + 2ΩĊ + Ω²C = 0: integration drift decays in
// ~1/Ω s, while hΩ stays well inside an explicit method's stability region
// at the step sizes animation needs (h ≤ 0.1 s).
constexpr double kStabilization = 20.0;
// Relative regularization of K's diagonal: far below any tolerance, enough
// to make redundant constraints solvable.
constexpr double kRegularization = 1e-10;

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

}  // namespace

JointSolver::JointSolver(const EquationSystem& sys, std::vector<int> joints,
                         const std::function<int(int)>& local_first)
    : sys_(sys) {
  std::map<int, int> body_index;
  auto add_body = [&](int b) {
    auto it = body_index.find(b);
    if (it != body_index.end()) return it->second;
    const BodyModel& m = sys.bodies[b];
    BodyData d;
    d.body = b;
    d.local = local_first(b);
    d.inv_mass = 1.0 / m.mass;
    d.inv_inertia = m.inertia.inverse();
    if (d.inv_inertia.isDiagonal(0.0) && d.inv_inertia(0, 0) == d.inv_inertia(1, 1) &&
        d.inv_inertia(1, 1) == d.inv_inertia(2, 2))
      d.isotropic = d.inv_inertia(0, 0);
    else
      any_anisotropic_ = true;
    d.R.setIdentity();
    d.inv_inertia_world = d.inv_inertia;
    d.w.setZero();
    d.kinematic = false;
    bodies_.push_back(d);
    return body_index[b] = static_cast<int>(bodies_.size()) - 1;
  };
  std::vector<expr::NodeId> point_outputs;
  for (int ji : joints) {
    const Joint& j = sys.joints[ji];
    JointData d;
    d.a.body = add_body(j.body_a);
    d.a.s = j.s_a;
    if (j.body_b >= 0) {
      d.b.body = add_body(j.body_b);
      d.b.s = j.s_b;
    } else {
      d.point = static_cast<int>(point_outputs.size());
      for (const auto* e : {&j.p, &j.p_dot, &j.p_ddot})
        point_outputs.insert(point_outputs.end(), e->begin(), e->end());
    }
    joints_.push_back(d);
  }
  // Points fixed in space (the common case: a pendulum's pivot) need no
  // tape; their values are the constants themselves.
  points_constant_ = std::all_of(point_outputs.begin(), point_outputs.end(),
                                 [&](expr::NodeId e) { return sys.pool.IsConst(e); });
  point_values_.assign(point_outputs.size(), 0.0);
  if (points_constant_)
    for (size_t k = 0; k < point_outputs.size(); ++k)
      point_values_[k] = sys.pool.node(point_outputs[k]).value;
  else
    point_tape_ = expr::Tape::Compile(sys.pool, point_outputs);
  const size_t n = joints_.size();
  rhs_.assign(n, Eigen::Vector3d::Zero());
  Symbolic();
}

// Slot of the block coupling joints i and j (stored once per unordered pair).
int JointSolver::Slot(int i, int j) {
  const std::pair<int, int> key{std::min(i, j), std::max(i, j)};
  auto it = std::find(slot_keys_.begin(), slot_keys_.end(), key);
  if (it != slot_keys_.end()) return static_cast<int>(it - slot_keys_.begin());
  slot_keys_.push_back(key);
  return static_cast<int>(slot_keys_.size()) - 1;
}

// The joint graph (joints sharing a body are adjacent), an elimination order
// by minimum degree (ties: lowest index), and the fill it makes.
void JointSolver::Symbolic() {
  const int n = static_cast<int>(joints_.size());
  if (n == 1) return;  // one joint (a pendulum): Solve inverts its block directly
  std::vector<std::set<int>> adj(n);
  for (int i = 0; i < n; ++i)
    for (int k = i + 1; k < n; ++k) {
      const JointData &a = joints_[i], &b = joints_[k];
      const bool share = (a.a.body == b.a.body) || (a.a.body == b.b.body && b.b.body >= 0) ||
                         (a.b.body >= 0 && (a.b.body == b.a.body || a.b.body == b.b.body));
      if (share) {
        adj[i].insert(k);
        adj[k].insert(i);
      }
    }
  std::vector<char> done(n, 0);
  for (int step = 0; step < n; ++step) {
    int p = -1;
    for (int i = 0; i < n; ++i)
      if (!done[i] && (p < 0 || adj[i].size() < adj[p].size())) p = i;
    Pivot piv;
    piv.joint = p;
    piv.diag = Slot(p, p);
    piv.rows.assign(adj[p].begin(), adj[p].end());
    for (int r : piv.rows) piv.slots.push_back(Slot(r, p));
    // Eliminating p couples all its remaining neighbours (fill).
    for (size_t x = 0; x < piv.rows.size(); ++x)
      for (size_t y = x; y < piv.rows.size(); ++y) {
        const int i = piv.rows[x], k = piv.rows[y];
        piv.updates.push_back({Slot(i, k), static_cast<int>(x), static_cast<int>(y)});
        if (i != k) {
          adj[i].insert(k);
          adj[k].insert(i);
        }
      }
    for (int r : piv.rows) adj[r].erase(p);
    adj[p].clear();
    done[p] = 1;
    pivots_.push_back(std::move(piv));
  }
  blocks_.assign(slot_keys_.size(), Eigen::Matrix3d::Zero());
  coupling_.assign(slot_keys_.size(), Eigen::Matrix3d::Zero());
  residual_.assign(n, Eigen::Vector3d::Zero());
  dinv_.assign(n, Eigen::Matrix3d::Zero());
}

// K_ik: Σ over the bodies joints i and k share of σ_i σ_k W(s_i, s_k).
Eigen::Matrix3d JointSolver::Coupling(int i, int k) const {
  Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
  const End* ends_i[2] = {&joints_[i].a, &joints_[i].b};
  const End* ends_k[2] = {&joints_[k].a, &joints_[k].b};
  for (int x = 0; x < 2; ++x)
    for (int y = 0; y < 2; ++y) {
      const End &ei = *ends_i[x], &ek = *ends_k[y];
      if (ei.body < 0 || ei.body != ek.body) continue;
      if (i == k && x != y) continue;
      const BodyData& b = bodies_[ei.body];
      if (b.kinematic) continue;
      // W(s, s') = I₃/m − [r]× I_W⁻¹ [r']× with world arms r = R s; with
      // I_W⁻¹ = c I₃ that is I₃/m + c ((r·r') I₃ − r' rᵀ).  The bracket is
      // formed first, as the product is: an arm along an axis gives exact
      // zeros there, and a body hanging at rest gets joint forces that
      // cancel its weight to the last bit (the rest test, component.h).
      Eigen::Matrix3d W;
      if (b.isotropic > 0) {
        W.noalias() = -ek.arm * ei.arm.transpose();
        W.diagonal().array() += ei.arm.dot(ek.arm);
        W *= b.isotropic;
        W.diagonal().array() += b.inv_mass;
      } else {
        W.noalias() = -ei.arm_skew * b.inv_inertia_world * ek.arm_skew;
        W.diagonal().array() += b.inv_mass;
      }
      if (x == y)  // σ_i σ_k = +1: a's side with a's, b's with b's
        K += W;
      else
        K -= W;
    }
  return K;
}

void JointSolver::Prepare(double t, const double* values, const char* prescribed,
                          const expr::ExternFn* externs, int32_t x_offset) {
  for (BodyData& b : bodies_) {
    const int v0 = sys_.bodies[b.body].first_var - x_offset;
    Eigen::Quaterniond q(values[v0 + kQw], values[v0 + kQx], values[v0 + kQy], values[v0 + kQz]);
    b.R = q.normalized().toRotationMatrix();
    if (b.isotropic == 0) b.inv_inertia_world.noalias() = b.R * b.inv_inertia * b.R.transpose();
    b.w = Eigen::Vector3d(values[v0 + kW1], values[v0 + kW2], values[v0 + kW3]);
    b.kinematic = false;
    for (int slot = kX; prescribed && slot <= kW3; ++slot)
      if (prescribed[b.local + slot]) b.kinematic = true;
  }
  for (JointData& d : joints_)
    for (End* e : {&d.a, &d.b})
      if (e->body >= 0) {
        e->arm = bodies_[e->body].R * e->s;
        if (any_anisotropic_) e->arm_skew = Skew(e->arm);
      }
  if (!point_values_.empty() && !points_constant_)
    point_tape_.Evaluate(t, values, point_values_.data(), externs, x_offset);
}

void JointSolver::ProjectVelocities(double t, const double* values, double* state,
                                    const char* prescribed, const expr::ExternFn* externs) {
  Prepare(t, values, prescribed, externs);
  for (size_t j = 0; j < joints_.size(); ++j) {
    auto velocity = [&](const End& e) -> Eigen::Vector3d {
      const BodyData& b = bodies_[e.body];
      const double* s = state + b.local;
      return Eigen::Vector3d(s[kDx], s[kDy], s[kDz]) +
             b.R * Eigen::Vector3d(s[kW1], s[kW2], s[kW3]).cross(e.s);
    };
    const JointData& d = joints_[j];
    Eigen::Vector3d vb = Eigen::Vector3d::Zero();
    if (d.b.body >= 0)
      vb = velocity(d.b);
    else
      vb = Eigen::Vector3d(point_values_[d.point + 3], point_values_[d.point + 4],
                           point_values_[d.point + 5]);
    rhs_[j] = -(velocity(d.a) - vb);
  }
  Solve();
  Distribute(state, prescribed);
}

void JointSolver::Apply(double t, const double* values, double* rates, const char* prescribed,
                        const expr::ExternFn* externs, double* magnitude, int refinements,
                        int32_t x_offset) {
  Prepare(t, values, prescribed, externs, x_offset);

  // Position, velocity and free acceleration of one end of a joint.
  auto end_state = [&](const End& e, Eigen::Vector3d& p, Eigen::Vector3d& v, Eigen::Vector3d& a) {
    const BodyData& b = bodies_[e.body];
    const int v0 = sys_.bodies[b.body].first_var - x_offset;
    p = Eigen::Vector3d(values[v0 + kX], values[v0 + kY], values[v0 + kZ]) + e.arm;
    v = Eigen::Vector3d(values[v0 + kDx], values[v0 + kDy], values[v0 + kDz]) +
        b.R * b.w.cross(e.s);
    Eigen::Vector3d acc = Eigen::Vector3d::Zero(), alpha = Eigen::Vector3d::Zero();
    if (!b.kinematic) {
      acc = Eigen::Vector3d(rates[b.local + kDx], rates[b.local + kDy], rates[b.local + kDz]);
      alpha = Eigen::Vector3d(rates[b.local + kW1], rates[b.local + kW2], rates[b.local + kW3]);
    }
    a = acc + b.R * (alpha.cross(e.s) + b.w.cross(b.w.cross(e.s)));
  };

  const int n = static_cast<int>(joints_.size());
  for (int j = 0; j < n; ++j) {
    const JointData& d = joints_[j];
    Eigen::Vector3d pa, va, aa, pb, vb, ab;
    end_state(d.a, pa, va, aa);
    if (d.b.body >= 0) {
      end_state(d.b, pb, vb, ab);
    } else {
      const double* pv = &point_values_[d.point];
      pb = Eigen::Vector3d(pv[0], pv[1], pv[2]);
      vb = Eigen::Vector3d(pv[3], pv[4], pv[5]);
      ab = Eigen::Vector3d(pv[6], pv[7], pv[8]);
    }
    const Eigen::Vector3d C = pa - pb, Cd = va - vb, Cdd = aa - ab;
    rhs_[j] = -(Cdd + 2.0 * kStabilization * Cd + kStabilization * kStabilization * C);
  }

  Solve(refinements);
  Distribute(rates, prescribed, magnitude);
}

// The diagonal block of K + εD: K's block with ε times its mean diagonal
// added, or the identity where both ends are immovable (the force then acts
// on nothing).
Eigen::Matrix3d JointSolver::Regularized(const Eigen::Matrix3d& K) {
  Eigen::Matrix3d A = K;
  const double scale = A.trace() / 3.0;
  if (scale > 0)
    A.diagonal().array() += kRegularization * scale;
  else
    A.setIdentity();
  return A;
}

void JointSolver::Solve(int refinements) {
  if (joints_.size() == 1) {  // one 3×3 block, solved directly
    const Eigen::Matrix3d K = Coupling(0, 0);
    const Eigen::Matrix3d inv = Regularized(K).inverse();
    const Eigen::Vector3d b = rhs_[0];
    Eigen::Vector3d l = inv * b;
    for (int pass = 0; pass < refinements; ++pass) l += inv * (b - K * l);
    rhs_[0] = l;
    return;
  }
  // Assemble K (kept for the refinement) and K + εD in the factor's slots,
  // then factor L D Lᵀ.
  for (size_t s = 0; s < slot_keys_.size(); ++s) {
    const auto [i, k] = slot_keys_[s];
    coupling_[s] = Coupling(i, k);
    blocks_[s] = i == k ? Regularized(coupling_[s]) : coupling_[s];
  }
  for (const Pivot& p : pivots_) {
    dinv_[p.joint] = blocks_[p.diag].inverse();
    // A_ip (row i, column p) as stored: slot keys are (min, max).
    auto lower = [&](size_t r) -> Eigen::Matrix3d {
      const int i = p.rows[r];
      return i > p.joint ? blocks_[p.slots[r]].transpose() : blocks_[p.slots[r]];
    };
    for (const Update& u : p.updates) {
      const Eigen::Matrix3d Aip = lower(u.lhs), Akp = lower(u.rhs);
      Eigen::Matrix3d delta = Aip * dinv_[p.joint] * Akp.transpose();
      const int i = p.rows[u.lhs], k = p.rows[u.rhs];
      // Slot (min, max) holds the block with row min(i, k).
      if (i > k) delta.transposeInPlace();
      blocks_[u.target] -= delta;
    }
    // Store L_ip = A_ip D_p⁻¹ back in the slot, in the same orientation.
    for (size_t r = 0; r < p.rows.size(); ++r) {
      const Eigen::Matrix3d L = lower(r) * dinv_[p.joint];
      blocks_[p.slots[r]] = p.rows[r] > p.joint ? Eigen::Matrix3d(L.transpose()) : L;
    }
  }
  // λ₀ = (K + εD)⁻¹ b, then one step of iterative refinement against K
  // itself: λ = λ₀ + (K + εD)⁻¹ (b − K λ₀).  Where K is regular this leaves a
  // relative error of ε² instead of ε, so joint forces balance the applied
  // ones to rounding and a body hanging at rest has rates at rounding level
  // (which lets a component at rest take rest steps, see component.h).
  // Where K is singular (redundant constraints) the correction only grows λ
  // in K's null space, whose forces cancel on every body (K λ = 0 ⇔ Jᵀλ = 0).
  const size_t n = joints_.size();
  b_.assign(rhs_.begin(), rhs_.end());
  Substitute(rhs_);
  for (int pass = 0; pass < refinements; ++pass) {
    for (size_t j = 0; j < n; ++j) residual_[j] = b_[j];
    for (size_t s = 0; s < slot_keys_.size(); ++s) {
      const auto [i, k] = slot_keys_[s];
      residual_[i] -= coupling_[s] * rhs_[k];
      if (i != k) residual_[k] -= coupling_[s].transpose() * rhs_[i];
    }
    Substitute(residual_);
    for (size_t j = 0; j < n; ++j) rhs_[j] += residual_[j];
  }
}

// v ← (L D Lᵀ)⁻¹ v with the factor Solve left in blocks_ and dinv_.
void JointSolver::Substitute(std::vector<Eigen::Vector3d>& v) const {
  auto L = [&](const Pivot& p, size_t r) -> Eigen::Matrix3d {
    return p.rows[r] > p.joint ? blocks_[p.slots[r]].transpose() : blocks_[p.slots[r]];
  };
  for (const Pivot& p : pivots_)
    for (size_t r = 0; r < p.rows.size(); ++r) v[p.rows[r]] -= L(p, r) * v[p.joint];
  for (const Pivot& p : pivots_) v[p.joint] = dinv_[p.joint] * v[p.joint];
  for (auto it = pivots_.rbegin(); it != pivots_.rend(); ++it)
    for (size_t r = 0; r < it->rows.size(); ++r)
      v[it->joint] -= L(*it, r).transpose() * v[it->rows[r]];
}

void JointSolver::Distribute(double* out, const char* prescribed, double* magnitude) const {
  const int n = static_cast<int>(joints_.size());
  // Apply λ: +λ on a's anchor, −λ on b's.
  auto push = [&](const End& e, const Eigen::Vector3d& force) {
    if (e.body < 0) return;
    const BodyData& b = bodies_[e.body];
    if (b.kinematic) return;
    const Eigen::Vector3d dv = b.inv_mass * force;
    const Eigen::Vector3d dw = b.inv_inertia * e.s.cross(b.R.transpose() * force);
    for (int a = 0; a < 3; ++a) {
      if (!prescribed || !prescribed[b.local + kDx + a]) out[b.local + kDx + a] += dv[a];
      if (!prescribed || !prescribed[b.local + kW1 + a]) out[b.local + kW1 + a] += dw[a];
    }
    if (magnitude)
      for (int a = 0; a < 3; ++a) {
        magnitude[b.local + kDx + a] += std::abs(dv[a]);
        magnitude[b.local + kW1 + a] += std::abs(dw[a]);
      }
  };
  for (int j = 0; j < n; ++j) {
    push(joints_[j].a, rhs_[j]);
    push(joints_[j].b, -rhs_[j]);
  }
}

}  // namespace asgard::physics
