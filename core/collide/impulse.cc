// Collision response: an instantaneous impulse at the contact point (seed
// 5.3.2: new velocities from momentum conservation, an energy condition and
// the reaction's direction along the contact normal).
//
// Design
// ------
// With r_a, r_b the contact point relative to the centres of mass and P the
// impulse applied to b (−P to a), the relative contact velocity
// u = (v_b + ω_b × r_b) − (v_a + ω_a × r_a) changes by K P, where
//   K = (1/m_a + 1/m_b) 𝟙 − [r_a]× I_a⁻¹ [r_a]× − [r_b]× I_b⁻¹ [r_b]×
// is symmetric positive (semi)definite.  Frictionless: P = j n with
//   j = −(1 + e) u_n / (nᵀ K n),
// which reverses the normal relative velocity (scaled by e); for e = 1 this
// is the seed's solution (momentum and energy conserved, the reaction along
// the normal) without forming its 6×6 system.
//
// Friction (μ > 0) follows the usual single-impulse Coulomb model:
//   * sticking: P = K⁻¹(−e u_n n − u) makes the tangential contact velocity
//     vanish and the normal one −e u_n; it is used when it lies in the friction
//     cone (n·P > 0 and |P_t| ≤ μ n·P);
//   * sliding: P = j (n − μ t) with t the unit tangential relative velocity
//     (or, when that is zero, opposite to the sticking impulse's tangential
//     part) and j from the normal condition n·(u + K P) = −e u_n.
// If the sliding system degenerates (nᵀK(n − μ t) ≤ 0, only for extreme
// geometry) the frictionless impulse is used.
//
// Infinite mass is inv_mass = 0 with a zero inverse inertia: its K term
// vanishes and its velocities are left untouched.  Two infinite masses, a
// zero normal, or bodies already separating at the point give 0 and change
// nothing.
//
// Rejected alternatives:
//   * Solving the seed's 6×6 system (momentum, energy, two tangency
//     conditions) per collision: same answer for translating bodies, but it
//     has no rotational terms and needs a quadratic; the K-matrix form covers
//     rotation and restitution directly.
//   * Stronge's energetically consistent friction (integrating the impulse
//     through compression and restitution phases): correct for sliding
//     reversal during impact, but far more machinery than the seed's elastic
//     collisions call for.
#include <cmath>

#include "core/collide/collide.h"

namespace asgard::collide {
namespace {

Eigen::Matrix3d Cross(const Eigen::Vector3d& r) {
  Eigen::Matrix3d m;
  m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return m;
}

bool Infinite(const BodyState& body) {
  return body.inv_mass == 0.0 && body.inv_inertia.isZero(0.0);
}

}  // namespace

double ApplyImpulse(BodyState& a, BodyState& b, const Eigen::Vector3d& point,
                    const Eigen::Vector3d& normal, double restitution, double friction) {
  const bool a_infinite = Infinite(a);
  const bool b_infinite = Infinite(b);
  if (a_infinite && b_infinite) return 0.0;
  const double length = normal.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return 0.0;
  const Eigen::Vector3d n = normal / length;
  const Eigen::Vector3d ra = point - a.com;
  const Eigen::Vector3d rb = point - b.com;
  const Eigen::Vector3d u = (b.v + b.w.cross(rb)) - (a.v + a.w.cross(ra));
  const double un = n.dot(u);
  if (!(un < 0.0)) return 0.0;  // separating or resting at the point

  const Eigen::Matrix3d ca = Cross(ra);
  const Eigen::Matrix3d cb = Cross(rb);
  const Eigen::Matrix3d k = (a.inv_mass + b.inv_mass) * Eigen::Matrix3d::Identity() -
                            ca * a.inv_inertia * ca - cb * b.inv_inertia * cb;
  const double knn =
      a.inv_mass + b.inv_mass +
      n.dot((a.inv_inertia * ra.cross(n)).cross(ra) + (b.inv_inertia * rb.cross(n)).cross(rb));
  if (!(knn > 0.0)) return 0.0;

  auto apply = [&](const Eigen::Vector3d& p) {
    if (!a_infinite) {
      a.v -= a.inv_mass * p;
      a.w -= a.inv_inertia * ra.cross(p);
    }
    if (!b_infinite) {
      b.v += b.inv_mass * p;
      b.w += b.inv_inertia * rb.cross(p);
    }
  };

  const double e = restitution;
  if (friction > 0.0) {
    const Eigen::Vector3d target = -e * un * n;
    const Eigen::Vector3d ut = u - un * n;
    Eigen::Vector3d stick_t = Eigen::Vector3d::Zero();
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(k);
    if (ldlt.info() == Eigen::Success && ldlt.isPositive()) {
      const Eigen::Vector3d p = ldlt.solve(target - u);
      const double jn = n.dot(p);
      stick_t = p - jn * n;
      const bool exact = (k * p - (target - u)).norm() <= 1e-9 * (target - u).norm();
      if (p.allFinite() && exact && jn > 0.0 && stick_t.norm() <= friction * jn) {
        apply(p);
        return jn;
      }
    }
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    const double ut_norm = ut.norm();
    if (ut_norm > 0.0) {
      t = ut / ut_norm;
    } else if (stick_t.norm() > 0.0) {
      t = -stick_t.normalized();
    }
    const Eigen::Vector3d dir = n - friction * t;
    const double denominator = n.dot(k * dir);
    if (denominator > 0.0) {
      const double jn = -(1.0 + e) * un / denominator;
      apply(jn * dir);
      return jn;
    }
  }
  const double j = -(1.0 + e) * un / knn;
  apply(j * n);
  return j;
}

}  // namespace asgard::collide
