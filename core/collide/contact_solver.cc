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
#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <iterator>

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
  Eigen::Vector2d target_t = Eigen::Vector2d::Zero();  // on t1 and t2
};

// The sweep's helpers are forced inline: the compiler called PushNormal and
// PushTangent, a third of the sweeps' instructions in a pile of 30 cubes;
// inline, the sweeps take 4% fewer (the arithmetic, and so the results,
// are the same).
#define ASGARD_INLINE inline __attribute__((always_inline))

ASGARD_INLINE BodyState& Get(std::vector<BodyState>& bodies, int i, BodyState& world) {
  return i < 0 ? world : bodies[static_cast<size_t>(i)];
}

ASGARD_INLINE Eigen::Vector3d VelocityAt(const BodyState& s, const Eigen::Vector3d& r) {
  return s.v + s.w.cross(r);
}

// An impulse of x along the row's normal, or (x, y) along its tangents,
// from a to b.
ASGARD_INLINE void PushNormal(BodyState& a, BodyState& b, const Row& row, double x) {
  a.v -= (a.inv_mass * x) * row.n;
  a.w -= x * row.wa_n;
  b.v += (b.inv_mass * x) * row.n;
  b.w += x * row.wb_n;
}

ASGARD_INLINE void PushTangent(BodyState& a, BodyState& b, const Row& row, double x, double y) {
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
// the sweeps stall, the island is solved at once, friction cone included,
// in the bodies' velocities: minimize
//   E(v) = ½ ‖v − v₀‖²_M + Σᵢ (rᵢ/2) |Π_K(yᵢ)|²,   yᵢ = λ_ref,i − (Jᵢ v − cᵢ)/rᵢ
// where v₀ is the bodies' velocity without the contact impulses, Jᵢ v point
// i's relative velocity (normal, t1, t2), cᵢ its target (normal only), Π_K
// the projection on its Coulomb cone K = {|λ_t| ≤ μ λ_n} and rᵢ a
// regularization (a fraction of W's normal diagonal, W = J M⁻¹ Jᵀ).  E is
// convex and once differentiable; its gradient M(v − v₀) − Σ Jᵢᵀ λᵢ with
// λᵢ = Π_K(yᵢ) vanishes where the impulses λ give the velocities v: each
// point sticks (λ inside K, its relative velocity at the target), separates
// (λ = 0) or slides on the rim.  The unknowns are six per body, not three
// per contact, so a face's redundant corners (four points, three
// independent constraints) cost nothing, and the friction shares among
// them are ones the discs allow.
//
// Newton's method with an exact line search: the Hessian
// M + Σ Jᵢᵀ ∂Π_K Jᵢ / rᵢ is positive definite (M is); ∂Π_K is 0, the
// identity or a rank-two matrix on the rim; E is piecewise quadratic, so
// once the zones stop changing the next step is exact.  Dense up to
// kDenseBodies bodies, a sparse LDLᵀ (fixed pattern, one symbolic
// analysis) above.  Proximal steps (λ_ref ← λ) remove the regularization's
// bias, each by a factor r/(σ + r) on every mode σ of W, and among
// equivalent shares of redundant points they keep the nearest to the warm
// start (the same shares, event after event).  r falls from step to step
// (kRegularizationSchedule): Newton from the sweeps' state with r at 1e-4
// of W's diagonal at once took up to 40 iterations and often failed,
// because the zones' curvature jumps by 1/r; from a soft solve each harder
// one starts next to its optimum.  The schedule ends at 1e-12: a leaning
// column of thirty cubes, whose rocking mode's σ lies far below W's
// diagonal, was left moving at ~1e-7 m/s by a schedule that ended at 1e-6.
// A later step that does not converge leaves the one before it standing.
//
// Sliding points get Anitescu's convex model (a slip s leaves the normal
// velocity μ s above its target), not Coulomb's: a stack's points stick,
// and where the island slides the step is not run, or is dropped — the
// sweeps' kinetic law is the better answer there.  It is not run when a
// pressed point of the sweeps slips on its rim by more than a tenth of the
// velocity change its normal impulse makes (tumbling dominoes or a pile:
// 3353 of 4141 steps in the first 2 s of a pile of 100), and dropped when
// the first, softest solve has a point whose sticking impulse lies further
// outside its cone than its own size.
//
// Measured against the step it replaced (an active-set quadratic program
// over the pressed points' impulses with sticking friction, the discs
// imposed only after the solve, dense up to 150 unknowns): twelve random
// piles of 30 cubes all settle (one did not: a seven-cube island hopped for
// ever on the spin noise its unconverged steps left), in 22.6 s instead of
// 33.3 s; forty piles of 10, 16.4 s instead of 17.5 s (all settle with
// both); the program gave a corner with a tiny normal share a tangential
// share outside its disc, and islands above 150 unknowns were left to the
// sweeps.
constexpr double kRegularizationSchedule[] = {1e-1, 1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12};
constexpr int kSweepsBeforeDirect = 16;
constexpr int kDirectSteps = 3;  // per solve at most (two that slide)
// Newton iterations per proximal step at most: the first, from the sweeps'
// state; each later one starts next to its optimum.
constexpr int kNewtonIterations[2] = {40, 30};
constexpr int kProximalSteps = std::size(kRegularizationSchedule);
constexpr long kDenseBodies = 24;  // a dense Hessian up to this many bodies
// Sweeps at most after the direct step has been refused or has slid twice:
// the island is not a stack at rest but tumbling or sliding, its velocities
// serve one hop, and the next event's solve starts from what the bodies then
// do, so their error does not add up from event to event.  Over a tumbling
// pile's hundreds of coupled contacts the sweeps converge slowly: with the
// full 200, a pile of 100 cubes spent half its run in them (4 461 of its
// 20 660 solves ran all 200 sweeps; an exact local solve of each sliding
// contact on its friction disc changed nothing, so it is the coupling).
// Eight random piles of 30 cubes, 5 s: 18.2 s in all with 200, 14.4 s with
// 40 (14.7 s with 80, 13.2 s with 15); their deepest penetration 5.7e-5 →
// 1.6e-4 of the cube (3.9e-4 with 15); settled at the end (kinetic energy
// below 0.05) 2 of 8 → 3 of 8.  The pile of 100: 12.9 s → 9.2 s.
// A settled island (SolveContacts' `settled`: every body moving no faster
// than its hop) keeps its full sweeps: the refusal there is the sweeps'
// own transient (a point on its rim before the normal impulses beneath it
// have converged), and the residual 40 sweeps leave over a pile's hundreds
// of contacts is spin noise that kept the pile of 100's island of 72 cubes
// from sleeping for 6 s after it had settled: its spins (times the radius)
// changed by 1e-5 to 2e-3 m/s from solve to solve, a rocking cube's by up
// to 0.09, against a hop speed of 0.13; with 200 sweeps by 1e-6 to 1e-5.
constexpr int kSlidingSweeps = 40;

enum class Direct { kSolved, kSlides, kUnsolved };

enum class Zone { kSeparate, kStick, kSlide };

// Π_K(y) for K = {(n, t): |t| ≤ μ n} (μ > 0), and its Jacobian ∂Π/∂y.
Zone ProjectOnCone(const Eigen::Vector3d& y, double mu, Eigen::Vector3d& lambda,
                   Eigen::Matrix3d& jacobian) {
  const double s = y.tail<2>().norm();
  if (s <= mu * y[0]) {
    lambda = y;
    jacobian.setIdentity();
    return Zone::kStick;
  }
  if (mu * s <= -y[0]) {
    lambda.setZero();
    jacobian.setZero();
    return Zone::kSeparate;
  }
  const double k = 1.0 / (1.0 + mu * mu);
  const double a = (y[0] + mu * s) * k;
  const Eigen::Vector2d dir = y.tail<2>() / s;
  lambda << a, mu * a * dir;
  jacobian(0, 0) = k;
  jacobian.block<1, 2>(0, 1) = (mu * k) * dir.transpose();
  jacobian.block<2, 1>(1, 0) = (mu * k) * dir;
  jacobian.block<2, 2>(1, 1) = (mu * mu * k) * dir * dir.transpose() +
                               (mu * a / s) * (Eigen::Matrix2d::Identity() - dir * dir.transpose());
  return Zone::kSlide;
}

class NewtonStep {
 public:
  NewtonStep(std::vector<BodyState>& bodies, std::vector<SolverContact>& contacts,
             std::vector<Row>& rows, double tolerance)
      : bodies_(bodies), contacts_(contacts), rows_(rows), tolerance_(tolerance) {}

  // kSolved: the impulses and the bodies are the step's solution; kSlides:
  // its solution with some points slipping; kUnsolved: both are left as
  // they were.
  Direct Run() {
    if (SweepsSlide()) return Direct::kUnsolved;
    // The movable bodies, six unknowns each.
    block_.assign(bodies_.size(), -1);
    for (size_t i = 0; i < contacts_.size(); ++i) {
      if (rows_[i].inv_kn == 0.0) continue;
      for (int side : {contacts_[i].a, contacts_[i].b}) {
        if (side < 0 || block_[size_t(side)] >= 0 || bodies_[size_t(side)].inv_mass == 0.0)
          continue;
        block_[size_t(side)] = static_cast<long>(movable_.size());
        movable_.push_back(side);
      }
    }
    const long nb = static_cast<long>(movable_.size());
    if (nb == 0) return Direct::kUnsolved;
    mass_.resize(nb);
    inertia_.resize(size_t(nb));
    for (long k = 0; k < nb; ++k) {
      const BodyState& s = bodies_[size_t(movable_[size_t(k)])];
      Eigen::FullPivLU<Eigen::Matrix3d> lu(s.inv_inertia);
      if (!lu.isInvertible()) return Direct::kUnsolved;
      mass_[k] = 1.0 / s.inv_mass;
      inertia_[size_t(k)] = lu.inverse();
    }
    // The contacts' Jacobians, their current impulses, and v₀.
    const size_t n = contacts_.size();
    point_.assign(n, Point{});
    Eigen::VectorXd v(6 * nb);
    for (long k = 0; k < nb; ++k) {
      const BodyState& s = bodies_[size_t(movable_[size_t(k)])];
      v.segment<3>(6 * k) = s.v;
      v.segment<3>(6 * k + 3) = s.w;
    }
    v0_ = v;
    for (size_t i = 0; i < n; ++i) {
      Point& p = point_[i];
      const Row& row = rows_[i];
      const SolverContact& c = contacts_[i];
      if (row.inv_kn == 0.0) continue;
      p.active = true;
      p.mu = HasFriction(i) ? c.friction : 0.0;
      p.target << c.target, row.target_t;
      p.now << c.normal_impulse, row.lambda_t;
      if (p.mu == 0.0) p.now.tail<2>().setZero();
      p.ref = p.now;
      const Eigen::Matrix3d d = (Eigen::Matrix3d() << row.n, row.t1, row.t2).finished();
      p.a = c.a >= 0 ? block_[size_t(c.a)] : -1;
      p.b = c.b >= 0 ? block_[size_t(c.b)] : -1;
      // Jᵢ's rows: d·v + (r × d)·ω on b, minus the same on a.
      if (p.a >= 0) {
        p.ja.leftCols<3>() = -d.transpose();
        for (int r = 0; r < 3; ++r) p.ja.block<1, 3>(r, 3) = -row.ra.cross(d.col(r)).transpose();
      }
      if (p.b >= 0) {
        p.jb.leftCols<3>() = d.transpose();
        for (int r = 0; r < 3; ++r) p.jb.block<1, 3>(r, 3) = row.rb.cross(d.col(r)).transpose();
      }
      // v₀ = v − M⁻¹ Σ Jᵀ λ_now.
      const Eigen::Matrix<double, 6, 1> ga = p.ja.transpose() * p.now;
      const Eigen::Matrix<double, 6, 1> gb = p.jb.transpose() * p.now;
      if (p.a >= 0) SubtractImpulse(p.a, ga);
      if (p.b >= 0) SubtractImpulse(p.b, gb);
    }
    // The world side of a contact moves as it moves (a driven body).
    for (size_t i = 0; i < n; ++i) {
      Point& p = point_[i];
      if (!p.active) continue;
      const SolverContact& c = contacts_[i];
      const Row& row = rows_[i];
      p.fixed.setZero();
      const Eigen::Matrix3d d = (Eigen::Matrix3d() << row.n, row.t1, row.t2).finished();
      if (c.a >= 0 && p.a < 0) p.fixed -= d.transpose() * VelocityAt(bodies_[size_t(c.a)], row.ra);
      if (c.b >= 0 && p.b < 0) p.fixed += d.transpose() * VelocityAt(bodies_[size_t(c.b)], row.rb);
    }
    bool slides = false;
    for (int step = 0; step < kProximalSteps; ++step) {
      for (size_t i = 0; i < n; ++i)
        if (point_[i].active) point_[i].r = kRegularizationSchedule[step] / rows_[i].inv_kn;
      const Eigen::VectorXd last_v = v;
      if (!Minimize(v, kNewtonIterations[step == 0 ? 0 : 1])) {
        if (step == 0) return Direct::kUnsolved;
        // The previous, softer solve stands.
        v = last_v;
        for (Point& p : point_)
          if (p.active) p.lambda = p.ref;
        break;
      }
      // Sliding already at the first, softest solve: the island is not a
      // stack; the sweeps' Coulomb law is the better answer.
      for (const Point& p : point_) {
        if (!p.active || !Slipping(p, v)) continue;
        if (step == 0) return Direct::kUnsolved;
        if (step == kProximalSteps - 1) slides = true;
      }
      for (Point& p : point_)
        if (p.active) p.ref = p.lambda;
    }
    // Apply λ − λ_now through the rows, as the sweeps would.
    for (size_t i = 0; i < n; ++i) {
      const Point& p = point_[i];
      if (!p.active) continue;
      SolverContact& c = contacts_[i];
      Row& row = rows_[i];
      BodyState& a = Body(c.a);
      BodyState& b = Body(c.b);
      PushNormal(a, b, row, p.lambda[0] - c.normal_impulse);
      c.normal_impulse = p.lambda[0];
      if (p.mu == 0.0) continue;
      const Eigen::Vector2d t = p.lambda.tail<2>();
      const Eigen::Vector2d dt = t - row.lambda_t;
      PushTangent(a, b, row, dt.x(), dt.y());
      row.lambda_t = t;
    }
    return slides ? Direct::kSlides : Direct::kSolved;
  }

 private:
  struct Point {
    bool active = false;
    long a = -1, b = -1;  // movable blocks, −1: fixed
    double mu = 0.0, r = 0.0;
    Eigen::Vector3d target = Eigen::Vector3d::Zero();  // normal, t1, t2
    Eigen::Matrix<double, 3, 6> ja = Eigen::Matrix<double, 3, 6>::Zero(),
                                jb = Eigen::Matrix<double, 3, 6>::Zero();
    Eigen::Vector3d fixed = Eigen::Vector3d::Zero();  // relative velocity of fixed sides
    Eigen::Vector3d now = Eigen::Vector3d::Zero(), ref = Eigen::Vector3d::Zero(),
                    lambda = Eigen::Vector3d::Zero(), jd = Eigen::Vector3d::Zero(),
                    now_w = Eigen::Vector3d::Zero();
    Eigen::Matrix3d dpi = Eigen::Matrix3d::Zero();
    Zone zone = Zone::kSeparate;
  };

  BodyState& Body(int i) { return i < 0 ? world_ : bodies_[size_t(i)]; }
  bool HasFriction(size_t i) const {
    return contacts_[i].friction > 0.0 && rows_[i].inv_kt(0, 0) > 0.0;
  }
  // On the rim and slipping: y, the impulse the point would take to stick,
  // lies further outside the cone than λ's own size (a point held on the
  // rim by static friction at its limit has y on the rim once the proximal
  // steps converge).
  bool Slipping(const Point& p, const Eigen::VectorXd& v) const {
    if (p.zone != Zone::kSlide || p.lambda[0] <= tolerance_) return false;
    const Eigen::Vector3d y = Unprojected(p, Relative(p, v));
    return (y - p.lambda).norm() > std::max(p.lambda.norm(), 10.0 * tolerance_);
  }
  // The sweeps have a pressed point sliding on its rim faster than a tenth
  // of the velocity change its normal impulse makes: not a stalled stack.
  bool SweepsSlide() const {
    for (size_t i = 0; i < contacts_.size(); ++i) {
      const SolverContact& c = contacts_[i];
      const Row& row = rows_[i];
      if (row.inv_kn == 0.0 || !HasFriction(i) || c.normal_impulse <= tolerance_) continue;
      if (row.lambda_t.norm() < c.friction * c.normal_impulse * (1.0 - 1e-9)) continue;
      const Eigen::Vector3d u = VelocityAt(Side(c.b), row.rb) - VelocityAt(Side(c.a), row.ra);
      const Eigen::Vector2d slip = Eigen::Vector2d(u.dot(row.t1), u.dot(row.t2)) - row.target_t;
      if (slip.norm() * row.inv_kn > 0.1 * c.normal_impulse) return true;
    }
    return false;
  }
  const BodyState& Side(int i) const { return i < 0 ? world_ : bodies_[size_t(i)]; }
  void SubtractImpulse(long k, const Eigen::Matrix<double, 6, 1>& g) {
    const BodyState& s = bodies_[size_t(movable_[size_t(k)])];
    v0_.segment<3>(6 * k) -= s.inv_mass * g.head<3>();
    v0_.segment<3>(6 * k + 3) -= s.inv_inertia * g.tail<3>();
  }
  Eigen::Vector3d Relative(const Point& p, const Eigen::VectorXd& v) const {
    Eigen::Vector3d w = p.fixed;
    if (p.a >= 0) w += p.ja * v.segment<6>(6 * p.a);
    if (p.b >= 0) w += p.jb * v.segment<6>(6 * p.b);
    return w;
  }
  // y = λ_ref − (w − c)/r at relative velocity w: the impulse before its
  // projection on the cone.
  static Eigen::Vector3d Unprojected(const Point& p, const Eigen::Vector3d& w) {
    return p.ref - w / p.r + p.target / p.r;
  }
  // λ and ∂Π at relative velocity w.
  static Zone Impulse(const Point& p, const Eigen::Vector3d& w, Eigen::Vector3d& lambda,
                      Eigen::Matrix3d& dpi) {
    const Eigen::Vector3d y = Unprojected(p, w);
    if (p.mu > 0.0) return ProjectOnCone(y, p.mu, lambda, dpi);
    lambda.setZero();
    dpi.setZero();
    if (y[0] <= 0.0) return Zone::kSeparate;
    lambda[0] = y[0];
    dpi(0, 0) = 1.0;
    return Zone::kStick;
  }
  Eigen::VectorXd MassTimes(const Eigen::VectorXd& x) const {
    Eigen::VectorXd y(x.size());
    for (long k = 0; k < static_cast<long>(movable_.size()); ++k) {
      y.segment<3>(6 * k) = mass_[k] * x.segment<3>(6 * k);
      y.segment<3>(6 * k + 3) = inertia_[size_t(k)] * x.segment<3>(6 * k + 3);
    }
    return y;
  }

  // Newton's method on E from v; false when it does not converge.
  bool Minimize(Eigen::VectorXd& v, int iterations) {
    for (int iteration = 0; iteration < iterations; ++iteration) {
      Eigen::VectorXd g = MassTimes(v - v0_);
      for (Point& p : point_) {
        if (!p.active) continue;
        p.zone = Impulse(p, Relative(p, v), p.lambda, p.dpi);
        if (p.a >= 0) g.segment<6>(6 * p.a) -= p.ja.transpose() * p.lambda;
        if (p.b >= 0) g.segment<6>(6 * p.b) -= p.jb.transpose() * p.lambda;
      }
      if (!g.allFinite()) return false;
      // Converged to the tolerance, or to round-off in λ = Π(λ_ref − w/r).
      double scale = 0.0;
      for (const Point& p : point_)
        if (p.active) scale = std::max(scale, p.lambda.lpNorm<Eigen::Infinity>());
      if (g.lpNorm<Eigen::Infinity>() <= std::max(tolerance_, 1e-11 * scale)) return true;
      Eigen::VectorXd d;
      if (!NewtonDirection(g, d)) return false;
      const double alpha = LineSearch(v, d);
      if (!(alpha > 0.0)) return false;
      v += alpha * d;
    }
    return false;
  }

  // H d = −g with H = M + Σ Jᵀ ∂Π J / r.
  bool NewtonDirection(const Eigen::VectorXd& g, Eigen::VectorXd& d) {
    const long nb = static_cast<long>(movable_.size());
    auto mass_block = [&](long k) {
      Eigen::Matrix<double, 6, 6> m = Eigen::Matrix<double, 6, 6>::Zero();
      m.topLeftCorner<3, 3>().diagonal().setConstant(mass_[k]);
      m.bottomRightCorner<3, 3>() = inertia_[size_t(k)];
      return m;
    };
    if (nb <= kDenseBodies) {
      Eigen::MatrixXd h = Eigen::MatrixXd::Zero(6 * nb, 6 * nb);
      for (long k = 0; k < nb; ++k) h.block<6, 6>(6 * k, 6 * k) = mass_block(k);
      for (const Point& p : point_) {
        if (!p.active || p.zone == Zone::kSeparate) continue;
        const Eigen::Matrix3d s = p.dpi / p.r;
        if (p.a >= 0) h.block<6, 6>(6 * p.a, 6 * p.a) += p.ja.transpose() * s * p.ja;
        if (p.b >= 0) h.block<6, 6>(6 * p.b, 6 * p.b) += p.jb.transpose() * s * p.jb;
        if (p.a >= 0 && p.b >= 0) {
          const Eigen::Matrix<double, 6, 6> x = p.ja.transpose() * s * p.jb;
          h.block<6, 6>(6 * p.a, 6 * p.b) += x;
          h.block<6, 6>(6 * p.b, 6 * p.a) += x.transpose();
        }
      }
      dense_.compute(h);
      if (dense_.info() != Eigen::Success) return false;
      d = dense_.solve(-g);
    } else {
      std::vector<Eigen::Triplet<double>> entries;
      entries.reserve(size_t(36 * (nb + 4 * static_cast<long>(point_.size()))));
      auto add = [&](long r, long c, const Eigen::Matrix<double, 6, 6>& x) {
        for (int j = 0; j < 6; ++j)
          for (int i = 0; i < 6; ++i)
            if (6 * r + i >= 6 * c + j) entries.emplace_back(6 * r + i, 6 * c + j, x(i, j));
      };
      for (long k = 0; k < nb; ++k) add(k, k, mass_block(k));
      for (const Point& p : point_) {
        if (!p.active) continue;
        // Every coupling, acting or not, so that the pattern stays the same.
        const Eigen::Matrix3d s = p.dpi / p.r;
        if (p.a >= 0) add(p.a, p.a, p.ja.transpose() * s * p.ja);
        if (p.b >= 0) add(p.b, p.b, p.jb.transpose() * s * p.jb);
        if (p.a >= 0 && p.b >= 0) {
          if (p.a > p.b)
            add(p.a, p.b, p.ja.transpose() * s * p.jb);
          else
            add(p.b, p.a, p.jb.transpose() * s * p.ja);
        }
      }
      Eigen::SparseMatrix<double> h(6 * nb, 6 * nb);
      h.setFromTriplets(entries.begin(), entries.end());
      if (!analyzed_) {
        sparse_.analyzePattern(h);
        analyzed_ = true;
      }
      sparse_.factorize(h);
      if (sparse_.info() != Eigen::Success) return false;
      d = sparse_.solve(-g);
    }
    return d.allFinite();
  }

  // The minimum of φ(α) = E(v + α d) over α > 0: a safeguarded Newton
  // iteration on φ', which is piecewise linear and increasing.
  double LineSearch(const Eigen::VectorXd& v, const Eigen::VectorXd& d) {
    const Eigen::VectorXd md = MassTimes(d);
    const double dmd = d.dot(md), slope0 = md.dot(v - v0_);
    for (Point& p : point_) {
      if (!p.active) continue;
      p.jd.setZero();
      if (p.a >= 0) p.jd += p.ja * d.segment<6>(6 * p.a);
      if (p.b >= 0) p.jd += p.jb * d.segment<6>(6 * p.b);
      p.now_w = Relative(p, v);
    }
    auto slope = [&](double alpha, double& curvature) {
      double s = slope0 + alpha * dmd;
      curvature = dmd;
      for (const Point& p : point_) {
        if (!p.active) continue;
        Eigen::Vector3d lambda;
        Eigen::Matrix3d dpi;
        Impulse(p, p.now_w + alpha * p.jd, lambda, dpi);
        s -= p.jd.dot(lambda);
        curvature += p.jd.dot(dpi * p.jd) / p.r;
      }
      return s;
    };
    double curvature = 0.0;
    const double s0 = slope(0.0, curvature);
    if (!(s0 < 0.0)) return 0.0;
    double lo = 0.0, hi = -1.0, alpha = 1.0;
    for (int i = 0; i < 50; ++i) {
      const double s = slope(alpha, curvature);
      if (std::abs(s) <= 1e-12 * -s0) return alpha;
      if (s < 0.0)
        lo = alpha;
      else
        hi = alpha;
      double next = curvature > 0.0 ? alpha - s / curvature : -1.0;
      const bool inside = next > lo && (hi < 0.0 || next < hi);
      if (!inside) next = hi < 0.0 ? 2.0 * alpha : 0.5 * (lo + hi);
      if (hi >= 0.0 && hi - lo <= 1e-14 * hi) return lo > 0.0 ? lo : hi;
      alpha = next;
    }
    return lo > 0.0 ? lo : alpha;
  }

  std::vector<BodyState>& bodies_;
  std::vector<SolverContact>& contacts_;
  std::vector<Row>& rows_;
  BodyState world_;  // immovable
  double tolerance_;
  std::vector<long> block_;  // per body: its block of unknowns, −1: not movable
  std::vector<int> movable_;
  Eigen::VectorXd mass_, v0_;
  std::vector<Eigen::Matrix3d> inertia_;
  std::vector<Point> point_;
  Eigen::LLT<Eigen::MatrixXd> dense_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> sparse_;
  bool analyzed_ = false;
};

#undef ASGARD_INLINE

}  // namespace

int SolveContacts(std::vector<BodyState>& bodies, std::vector<SolverContact>& contacts,
                  int max_sweeps, double tolerance, bool settled) {
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
    row.target_t = {c.target_tangent.dot(row.t1), c.target_tangent.dot(row.t2)};
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
      const Direct outcome = NewtonStep(bodies, contacts, rows, tolerance).Run();
      // Sliding twice, or no solution: the sweeps go on alone.
      if (outcome == Direct::kUnsolved || (outcome == Direct::kSlides && ++slid == 2)) {
        direct_steps = kDirectSteps;
        if (!settled) max_sweeps = std::min(max_sweeps, sweep + kSlidingSweeps);
      }
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
        const Eigen::Vector2d ut = Eigen::Vector2d(u.dot(row.t1), u.dot(row.t2)) - row.target_t;
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
