// Simultaneous contact impulses over an island: projected Gauss–Seidel.
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
  int sweep = 0;
  while (sweep < max_sweeps) {
    ++sweep;
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
