// Simultaneous contact impulses over an island: projected Gauss–Seidel,
// with a direct step where the sweeps stall (below).
//
// Design
// ------
// Each contact has a normal impulse λ_n ≥ 0 and a tangential impulse λ_t in
// the contact plane, accumulated over sweeps (Catto's sequential impulses).
// One sweep visits the contacts in order; per contact:
//   normal:   Δλ = (target − u·n) / (nᵀK n),  λ_n ← max(0, λ_n + Δλ)
//   friction: sticking  λ_t + Δλ_t with Δλ_t = −K_t⁻¹ u_t (2×2 tangential
//             block), when that lies in the disc |λ_t| ≤ μ λ_n;
//             sliding   otherwise λ_t − u_t / k_t (k_t ≥ the largest
//             eigenvalue of K_t) projected on the disc
// where u is the relative velocity at the point (b − a) and K the contact's
// inverse effective mass (impulse.cc).  A contact inside the disc sticks
// (static friction: its tangential velocity is cancelled); on the rim it
// slides with the kinetic force μ λ_n opposing the slip.
//
// Why the sliding step is not the projected sticking impulse: K_t at a
// point off the centre of mass is anisotropic (a unit cube's corner: its
// eigenvalues are 2.5 and 5.5 per unit mass), so −K_t⁻¹ u_t points up to
// ~20° away from −u_t, and scaling it onto the rim gives a friction force
// that is not opposite to the slip — a box sliding on its four corners lost
// 6% of μ λ_n along the slope and drifted sideways.  The isotropic step's
// fixed point on the rim is λ_t = −μ λ_n u_t/|u_t| with u_t the slip after
// the impulse (maximal dissipation, Coulomb's kinetic law); with
// k_t ≥ λ_max(K_t) each step is a projected gradient step on the contact's
// kinetic energy and cannot overshoot.  Clamping the
// accumulated impulse, not the increment, lets contacts that were pushed too
// hard early in a sweep give impulse back later.  Stops when no impulse
// changes by more than `tolerance` in a sweep.
//
// Warm start: resting contact is a train of events whose solutions barely
// change from one to the next (a stack: the same impulses every hop).  From
// zero, Gauss–Seidel needs hundreds of sweeps for a column of four cubes
// and stops short, leaving spins of ~1e-4 rad/s whose direction changes
// from event to event; started from the last event's impulses it is at its
// fixed point in a few sweeps.  The caller supplies the guess.
//
// Rejected alternatives:
//   * A Lemke / Dantzig LCP per island: exact for frictionless contact, but
//     pivoting is fragile with the redundant contacts of a box on a face (four
//     points, three independent constraints) and friction makes it an NCP.
//   * Friction as a pyramid (box clamp per tangent): anisotropic — a box
//     would slide differently along the floor's axes than diagonally.
#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "core/collide/collide.h"

namespace asgard::collide {
namespace {

struct Row {
  Eigen::Vector3d ra, rb, n, t1, t2;
  // Change of each body's angular velocity per unit impulse along n, t1 and
  // t2 (I⁻¹ (r × d)), so that a sweep's pushes are sums of vectors.
  Eigen::Vector3d wa_n, wa_t1, wa_t2, wb_n, wb_t1, wb_t2;
  double inv_kn = 0.0;
  Eigen::Matrix2d inv_kt = Eigen::Matrix2d::Zero();
  double kt_max = 0.0;  // largest eigenvalue of K_t
  Eigen::Vector2d lambda_t = Eigen::Vector2d::Zero();
};

BodyState& Get(std::vector<BodyState>& bodies, int i, BodyState& world) {
  return i < 0 ? world : bodies[static_cast<size_t>(i)];
}

Eigen::Vector3d VelocityAt(const BodyState& s, const Eigen::Vector3d& r) {
  return s.v + s.w.cross(r);
}

// An impulse of x along the row's normal, or (x, y) along its tangents,
// from a to b.
void PushNormal(BodyState& a, BodyState& b, const Row& row, double x) {
  a.v -= (a.inv_mass * x) * row.n;
  a.w -= x * row.wa_n;
  b.v += (b.inv_mass * x) * row.n;
  b.w += x * row.wb_n;
}

void PushTangent(BodyState& a, BodyState& b, const Row& row, double x, double y) {
  const Eigen::Vector3d p = x * row.t1 + y * row.t2;
  a.v -= a.inv_mass * p;
  a.w -= x * row.wa_t1 + y * row.wa_t2;
  b.v += b.inv_mass * p;
  b.w += x * row.wb_t1 + y * row.wb_t2;
}

// Change of the relative velocity at the contact per unit impulse along x,
// projected on y.
double Coupling(const BodyState& a, const BodyState& b, const Row& row, const Eigen::Vector3d& x,
                const Eigen::Vector3d& y) {
  return (a.inv_mass + b.inv_mass) * x.dot(y) +
         (a.inv_inertia * row.ra.cross(x)).cross(row.ra).dot(y) +
         (b.inv_inertia * row.rb.cross(x)).cross(row.rb).dot(y);
}

// The direct step
// ---------------
// Gauss–Seidel's error in a stack falls by a factor close to 1 per sweep
// (the slowest mode is the column's rocking, whose rate falls as the square
// of its height): a leaning tower of six cubes used all 200 sweeps in 1053
// of 1074 solves and was left rocking at ~1e-3 m/s, never at rest.  When
// the sweeps stall, the island is solved at once with friction sticking at
// every pressed point: minimize
//   f(λ) = ½ λᵀ W λ + qᵀ λ,   W = J M⁻¹ Jᵀ,  q = u₀ − target,
// over λ_n ≥ 0 (tangential impulses free), whose gradient W λ + q is each
// point's velocity beyond its target (0 along the tangents): a convex
// quadratic program whose optimum is the contact problem's solution
// whenever its friction lies in the Coulomb discs.  W (two contacts couple
// through a body they share) is singular where points are redundant (a box
// on its face: four points, three constraints), so the program is
// regularized by the proximal term ½ ε ‖λ − λ_ref‖²_D (D: W's diagonal),
// which makes it strictly convex; three proximal steps, each from the last
// one's λ, take the error of every mode of W's range down by (ε/(σ+ε))³,
// and among equivalent shares of redundant points they keep the nearest to
// the warm start (the same shares, event after event).
// Each step is solved by a primal active-set method from the sweeps'
// pressed set: on the pressed points, the program with λ_n free is one
// linear system (LLᵀ; dense up to kDenseLimit unknowns, a dozen cubes,
// larger islands are left to the sweeps); the step towards its solution
// stops where a pressed point's λ_n reaches 0, which is released; at the
// solution, the released point approaching fastest is pressed.  With the
// friction states fixed each round lowers f; a redundant point's
// inconsistent target shows as a long step along W's null space, which the
// first point to reach 0 ends.
//
// Friction.  At the optimum a point whose sticking impulse leaves its disc
// slides: its tangential impulse is held on the rim (scaled back along
// itself) and the rest solved again — in a leaning stack the even shares of
// the tangential impulse put more on a lightly pressed corner than its disc
// holds, while the heavily pressed ones hold the rest.  A point that pulls
// as soon as it is pressed (its free friction, not its approach, made the
// step: a point touching with a fast slip) slides with no friction.  A
// point that slid stays sliding through the step, so friction cannot make
// the rounds cycle (kRounds bounds what degenerate ties might).  The held impulses are not
// Coulomb's kinetic law (their direction is not the slip's); the sweeps that follow correct them,
// and where they cannot settle either (tumbling, not stacking), a second
// step that slides ends the direct steps of the solve.  The result is
// projected on λ_n ≥ 0 and the discs and applied; a step that runs out of
// rounds (kRounds) or fails to factor changes nothing.
constexpr double kRegularization = 1e-6;
constexpr int kProximalSteps = 3;
constexpr int kSweepsBeforeDirect = 16;
constexpr int kDirectSteps = 3;    // per solve at most (two that slide)
constexpr int kRounds = 32;        // active-set rounds per direct step at most
constexpr long kDenseLimit = 150;  // unknowns at most (3 per contact)

// The impulse along one of a contact's three directions (0: normal, 1 and
// 2: tangents).
struct Unknown {
  int contact = 0;
  int axis = 0;
};

const Eigen::Vector3d& Direction(const Row& row, int axis) {
  return axis == 0 ? row.n : axis == 1 ? row.t1 : row.t2;
}

const Eigen::Vector3d& Turn(const Row& row, int axis, bool on_b) {
  if (on_b) return axis == 0 ? row.wb_n : axis == 1 ? row.wb_t1 : row.wb_t2;
  return axis == 0 ? row.wa_n : axis == 1 ? row.wa_t1 : row.wa_t2;
}

enum class Direct { kSolved, kSlides, kUnsolved };

class DirectStep {
 public:
  DirectStep(std::vector<BodyState>& bodies, std::vector<SolverContact>& contacts,
             std::vector<Row>& rows, double tolerance)
      : bodies_(bodies), contacts_(contacts), rows_(rows), tolerance_(tolerance) {}

  // kSolved: the impulses and the bodies are the program's solution;
  // kSlides: its solution with some points' friction held on the rim;
  // kUnsolved: both are left as they were.
  Direct Run() {
    const size_t n = contacts_.size();
    first_.assign(n, -1);
    for (size_t i = 0; i < n; ++i) {
      if (rows_[i].inv_kn == 0.0) continue;
      first_[i] = static_cast<long>(slot_.size());
      for (int axis = 0; axis < (HasFriction(i) ? 3 : 1); ++axis)
        slot_.push_back(Unknown{static_cast<int>(i), axis});
    }
    const long m = static_cast<long>(slot_.size());
    if (m == 0 || m > kDenseLimit) return Direct::kUnsolved;
    Assemble();
    // λ now, and q = u − W λ − target (u: each slot's relative velocity
    // now, the target only along normals).
    Eigen::VectorXd now(m), u(m);
    for (size_t i = 0; i < n; ++i) {
      if (first_[i] < 0) continue;
      const Row& row = rows_[i];
      const Eigen::Vector3d relative =
          VelocityAt(Body(contacts_[i].b), row.rb) - VelocityAt(Body(contacts_[i].a), row.ra);
      for (int axis = 0; axis < (HasFriction(i) ? 3 : 1); ++axis) {
        const long k = first_[i] + axis;
        now[k] = axis == 0 ? contacts_[i].normal_impulse : row.lambda_t[axis - 1];
        u[k] = relative.dot(Direction(row, axis));
      }
    }
    q_ = u - full_ * now;
    for (size_t i = 0; i < n; ++i)
      if (first_[i] >= 0) q_[first_[i]] -= contacts_[i].target;
    pressed_.assign(n, 0);
    for (size_t i = 0; i < n; ++i)
      pressed_[i] = first_[i] >= 0 && contacts_[i].normal_impulse > 0.0;
    sliding_.assign(n, 0);
    Eigen::VectorXd lambda = now;
    int rounds = std::min(4 * static_cast<int>(n) + 8, kRounds);
    for (int step = 0; step < kProximalSteps; ++step) {
      ref_ = lambda;
      for (;;) {
        if (!Minimize(lambda, rounds)) return Direct::kUnsolved;
        // A sticking impulse outside its disc: the point slides, its
        // friction held on the rim.
        bool slid = false;
        for (size_t i = 0; i < n; ++i) {
          if (!pressed_[i] || sliding_[i] || !HasFriction(i)) continue;
          const long k = first_[i];
          const double length = lambda.segment<2>(k + 1).norm();
          const double limit = contacts_[i].friction * lambda[k];
          if (length > limit * (1.0 + 1e-9) + tolerance_) {
            sliding_[i] = 1;
            lambda.segment<2>(k + 1) *= limit / length;
            slid = true;
          }
        }
        if (!slid) break;
        if (--rounds < 0) return Direct::kUnsolved;
      }
    }
    for (size_t i = 0; i < n; ++i) {
      if (first_[i] < 0) continue;
      const long k = first_[i];
      SolverContact& c = contacts_[i];
      Row& row = rows_[i];
      BodyState& a = Body(c.a);
      BodyState& b = Body(c.b);
      const double normal = std::max(0.0, lambda[k]);  // ≥ 0 but for round-off
      PushNormal(a, b, row, normal - c.normal_impulse);
      c.normal_impulse = normal;
      if (!HasFriction(i)) continue;
      Eigen::Vector2d t = lambda.segment<2>(k + 1);
      const double limit = c.friction * normal;
      if (t.norm() > limit) t *= limit / t.norm();
      const Eigen::Vector2d d = t - row.lambda_t;
      PushTangent(a, b, row, d.x(), d.y());
      row.lambda_t = t;
    }
    return std::count(sliding_.begin(), sliding_.end(), 1) > 0 ? Direct::kSlides : Direct::kSolved;
  }

 private:
  BodyState& Body(int i) { return i < 0 ? world_ : bodies_[static_cast<size_t>(i)]; }
  bool HasFriction(size_t i) const {
    return contacts_[i].friction > 0.0 && rows_[i].inv_kt(0, 0) > 0.0;
  }
  // W over every slot, from each body's slots: a unit impulse along slot k
  // changes the relative velocity along slot j by
  // s_j s_k (m⁻¹ d_j·d_k + (r_j × d_j)·I⁻¹(r_k × d_k)), s = +1 on the
  // contact's b side and −1 on its a side.
  void Assemble() {
    struct Touch {
      int slot;
      double sign;
      Eigen::Vector3d d, arm, turn;  // direction, r × d, I⁻¹ (r × d)
    };
    std::vector<std::vector<Touch>> per_body(bodies_.size());
    for (size_t k = 0; k < slot_.size(); ++k) {
      const Unknown& s = slot_[k];
      const SolverContact& c = contacts_[size_t(s.contact)];
      const Row& row = rows_[size_t(s.contact)];
      const Eigen::Vector3d& d = Direction(row, s.axis);
      if (c.a >= 0)
        per_body[size_t(c.a)].push_back(
            {int(k), -1.0, d, row.ra.cross(d), Turn(row, s.axis, false)});
      if (c.b >= 0)
        per_body[size_t(c.b)].push_back({int(k), 1.0, d, row.rb.cross(d), Turn(row, s.axis, true)});
    }
    const long m = static_cast<long>(slot_.size());
    full_ = Eigen::MatrixXd::Zero(m, m);
    for (size_t body = 0; body < per_body.size(); ++body) {
      const double inv_mass = bodies_[body].inv_mass;
      for (const Touch& x : per_body[body])
        for (const Touch& y : per_body[body])
          full_(x.slot, y.slot) += x.sign * y.sign * (inv_mass * x.d.dot(y.d) + x.arm.dot(y.turn));
    }
    diagonal_ = full_.diagonal();
    max_diagonal_ = diagonal_.maxCoeff();
  }

  // One proximal step: the primal active-set rounds from λ (feasible:
  // λ_n ≥ 0 on pressed points, 0 with its friction on released ones) to the
  // regularized program's optimum.  False when `rounds` run out or a
  // factorization fails.
  bool Minimize(Eigen::VectorXd& lambda, int& rounds) {
    const size_t n = contacts_.size();
    const double slack = tolerance_ * max_diagonal_;
    Eigen::VectorXd goal;
    long pressing = -1;  // the point pressed in the last round
    while (rounds-- > 0) {
      if (!Solve(lambda, goal)) return false;
      const Eigen::VectorXd step = goal - lambda;
      double alpha = 1.0;
      long blocking = -1;
      for (size_t i = 0; i < n; ++i) {
        if (!pressed_[i]) continue;
        const long k = first_[i];
        if (goal[k] < 0.0 && lambda[k] < alpha * -step[k]) {
          alpha = lambda[k] / -step[k];
          blocking = static_cast<long>(i);
        }
      }
      lambda += alpha * step;
      if (blocking >= 0 && blocking == pressing && HasFriction(size_t(blocking)) &&
          !sliding_[size_t(blocking)]) {
        // The point just pressed pulls at once: its free friction, not its
        // approach, made it (a point touching with a fast slip).  It slides,
        // with no friction until its normal impulse grows.
        sliding_[size_t(blocking)] = 1;
        lambda.segment<2>(first_[size_t(blocking)] + 1).setZero();
        pressing = -1;
        continue;
      }
      pressing = -1;
      if (blocking >= 0) {
        const size_t i = static_cast<size_t>(blocking);
        pressed_[i] = 0;
        lambda.segment(first_[i], HasFriction(i) ? 3 : 1).setZero();
        continue;
      }
      // At the optimum on the pressed set: the gradient of the regularized
      // f on the released points is their approach beyond the target.
      const Eigen::VectorXd gradient =
          full_ * lambda + q_ + kRegularization * diagonal_.cwiseProduct(lambda - ref_);
      long worst = -1;
      for (size_t i = 0; i < n; ++i) {
        if (first_[i] < 0 || pressed_[i]) continue;
        const double g = gradient[first_[i]];
        if (g < -slack && (worst < 0 || g < gradient[first_[size_t(worst)]]))
          worst = static_cast<long>(i);
      }
      if (worst < 0) return true;
      pressed_[size_t(worst)] = 1;
      pressing = worst;
    }
    return false;
  }

  // The regularized program's optimum with the pressed points' impulses
  // free and every other 0: (W + ε D) λ = −q + ε D λ_ref on the free slots.
  bool Solve(const Eigen::VectorXd& now, Eigen::VectorXd& lambda) {
    const long m = static_cast<long>(slot_.size());
    std::vector<long> free_slot;
    Eigen::VectorXd held = Eigen::VectorXd::Zero(m);
    for (long k = 0; k < m; ++k) {
      const Unknown& s = slot_[size_t(k)];
      if (!pressed_[size_t(s.contact)]) continue;
      if (s.axis > 0 && sliding_[size_t(s.contact)]) {
        held[k] = now[k];
        continue;
      }
      free_slot.push_back(k);
    }
    lambda = held;
    const long f = static_cast<long>(free_slot.size());
    if (f == 0) return true;
    const Eigen::VectorXd moved = q_ + full_ * held;
    Eigen::VectorXd rhs(f);
    for (long k = 0; k < f; ++k) {
      const long slot = free_slot[size_t(k)];
      rhs[k] = -moved[slot] + kRegularization * diagonal_[slot] * ref_[slot];
    }
    // Dense: the islands solved here are small (kDenseLimit), where a sparse
    // factorization's bookkeeping costs more than its arithmetic.  The
    // proximal steps after the first usually solve on the same free set: its
    // factorization is kept.
    if (free_slot != factored_) {
      Eigen::MatrixXd w(f, f);
      for (long c = 0; c < f; ++c)
        for (long r = 0; r < f; ++r) w(r, c) = full_(free_slot[size_t(r)], free_slot[size_t(c)]);
      for (long k = 0; k < f; ++k) w(k, k) += kRegularization * diagonal_[free_slot[size_t(k)]];
      llt_.compute(w);
      factored_ = llt_.info() == Eigen::Success ? free_slot : std::vector<long>{};
      if (factored_.empty()) return false;
    }
    const Eigen::LLT<Eigen::MatrixXd>& llt = llt_;
    const Eigen::VectorXd x = llt.solve(rhs);
    if (!x.allFinite()) return false;
    for (long k = 0; k < f; ++k) lambda[free_slot[size_t(k)]] = x[k];
    return true;
  }

  std::vector<BodyState>& bodies_;
  std::vector<SolverContact>& contacts_;
  std::vector<Row>& rows_;
  BodyState world_;  // immovable
  double tolerance_;
  std::vector<Unknown> slot_;
  std::vector<long> first_;  // per contact: its normal's slot, −1 when it has none
  Eigen::MatrixXd full_;     // W over every slot
  Eigen::LLT<Eigen::MatrixXd> llt_;
  std::vector<long> factored_;  // the free slots llt_ is of
  Eigen::VectorXd q_, ref_, diagonal_;
  double max_diagonal_ = 0.0;
  std::vector<char> pressed_, sliding_;  // sliding: friction held on the rim
};

}  // namespace

int SolveContacts(std::vector<BodyState>& bodies, std::vector<SolverContact>& contacts,
                  int max_sweeps, double tolerance) {
  BodyState world;  // immovable: zero inverse mass and inertia, at rest
  std::vector<Row> rows(contacts.size());
  for (size_t i = 0; i < contacts.size(); ++i) {
    SolverContact& c = contacts[i];
    Row& row = rows[i];
    BodyState& a = Get(bodies, c.a, world);
    BodyState& b = Get(bodies, c.b, world);
    row.n = c.normal.normalized();
    row.t1 = row.n.unitOrthogonal();
    row.t2 = row.n.cross(row.t1);
    row.ra = c.point - a.com;
    row.rb = c.point - b.com;
    row.wa_n = a.inv_inertia * row.ra.cross(row.n);
    row.wa_t1 = a.inv_inertia * row.ra.cross(row.t1);
    row.wa_t2 = a.inv_inertia * row.ra.cross(row.t2);
    row.wb_n = b.inv_inertia * row.rb.cross(row.n);
    row.wb_t1 = b.inv_inertia * row.rb.cross(row.t1);
    row.wb_t2 = b.inv_inertia * row.rb.cross(row.t2);
    const double kn = Coupling(a, b, row, row.n, row.n);
    row.inv_kn = kn > 0.0 ? 1.0 / kn : 0.0;
    Eigen::Matrix2d kt;
    kt << Coupling(a, b, row, row.t1, row.t1), Coupling(a, b, row, row.t2, row.t1),
        Coupling(a, b, row, row.t1, row.t2), Coupling(a, b, row, row.t2, row.t2);
    const double det = kt.determinant();
    if (det > 0.0 && kt(0, 0) > 0.0) {
      row.inv_kt = kt.inverse();
      const double half_trace = 0.5 * kt.trace();
      row.kt_max = half_trace + std::sqrt(std::max(0.0, half_trace * half_trace - det));
    }
    // Warm start: the guess applied as if a first sweep had found it.
    c.normal_impulse = std::max(0.0, c.warm_normal);
    if (c.friction > 0.0 && row.inv_kt(0, 0) > 0.0) {
      row.lambda_t = {c.warm_tangent.dot(row.t1), c.warm_tangent.dot(row.t2)};
      const double limit = c.friction * c.normal_impulse, length = row.lambda_t.norm();
      if (length > limit) row.lambda_t *= length > 0.0 ? limit / length : 0.0;
    }
    if (c.normal_impulse > 0.0) PushNormal(a, b, row, c.normal_impulse);
    if (row.lambda_t.squaredNorm() > 0.0)
      PushTangent(a, b, row, row.lambda_t.x(), row.lambda_t.y());
  }
  int sweep = 0, since_direct = 0, direct_steps = 0, slid = 0;
  while (sweep < max_sweeps) {
    ++sweep;
    // Stalled: the direct step (above).
    if (++since_direct > kSweepsBeforeDirect && direct_steps < kDirectSteps &&
        contacts.size() > 1) {
      ++direct_steps;
      const Direct outcome = DirectStep(bodies, contacts, rows, tolerance).Run();
      // Sliding twice, or no solution: the sweeps go on alone.
      if (outcome == Direct::kUnsolved || (outcome == Direct::kSlides && ++slid == 2))
        direct_steps = kDirectSteps;
      since_direct = 0;
    }
    double change = 0.0;
    for (size_t i = 0; i < contacts.size(); ++i) {
      SolverContact& c = contacts[i];
      Row& row = rows[i];
      BodyState& a = Get(bodies, c.a, world);
      BodyState& b = Get(bodies, c.b, world);
      if (row.inv_kn == 0.0) continue;
      Eigen::Vector3d u = VelocityAt(b, row.rb) - VelocityAt(a, row.ra);
      const double old_n = c.normal_impulse;
      c.normal_impulse = std::max(0.0, old_n + (c.target - u.dot(row.n)) * row.inv_kn);
      PushNormal(a, b, row, c.normal_impulse - old_n);
      change = std::max(change, std::abs(c.normal_impulse - old_n));
      if (c.friction > 0.0 && row.inv_kt(0, 0) > 0.0) {
        u = VelocityAt(b, row.rb) - VelocityAt(a, row.ra);
        const Eigen::Vector2d ut(u.dot(row.t1), u.dot(row.t2));
        const Eigen::Vector2d old_t = row.lambda_t;
        const double limit = c.friction * c.normal_impulse;
        Eigen::Vector2d next = old_t - row.inv_kt * ut;  // sticking
        if (next.norm() > limit) {
          // Sliding: kinetic friction opposes the slip (see the design note).
          next = old_t - ut / row.kt_max;
          const double length = next.norm();
          if (length > limit) next *= limit / length;
        }
        row.lambda_t = next;
        const Eigen::Vector2d d = next - old_t;
        PushTangent(a, b, row, d.x(), d.y());
        change = std::max(change, d.norm());
      }
    }
    if (change <= tolerance) break;
  }
  for (size_t i = 0; i < contacts.size(); ++i)
    contacts[i].tangent_impulse =
        rows[i].lambda_t.x() * rows[i].t1 + rows[i].lambda_t.y() * rows[i].t2;
  // Bodies of infinite mass are never written: `world` absorbs their rows,
  // and a listed body with zero inverse mass and inertia is left as it was
  // by Push (both terms vanish).
  return sweep;
}

}  // namespace asgard::collide
