// Time of impact by conservative advancement (seed 5.3.1: "lower bounds on
// the first intersection time" from the objects' speeds and separation).
//
// Design
// ------
// Over an interval where the linear speeds are at most v_a, v_b and the
// angular speeds at most ω_a, ω_b, every point of a piece moves no faster than
// v + ω r (r = the piece's bound radius about its body origin), so the
// distance shrinks no faster than B = v_a + v_b + ω_a r_a + ω_b r_b.  For a
// sphere r is the distance of its centre from the body origin: the distance
// to a sphere is the distance to its centre minus the radius, so the radius
// itself never enters the bound (a ball spinning about its centre does not
// slow the search down).  From a
// time t with distance d > s (s = separation) the step (d − s/2)/B therefore
// cannot bring the distance below s/2: the search never passes a contact
// when the bounds are honest.  Each step calls Distance with the shared cache,
// so the closest-feature simplex carries over and most queries cost one GJK
// iteration.  The first sample with distance ≤ s is returned; since the
// distance was ≥ s/2 over all earlier steps, it lies in (s/2, s] up to the
// distance tolerance.
//
// Fallback: advancement is slow when B overestimates the closing speed by a
// lot (spinning bodies sliding past each other) and stalls when steps drop
// below 1e-15 of the time scale.  After kMaxAdvances steps, or on a stall, the
// step aims at touching instead ((d − 0)/B, at least the time resolution);
// a sample that then overlaps (or comes within s/2, or any sample when the
// bounds were not honest) brackets the contact between the last safe time and
// itself, and bisection on the sign of (distance − s/2) narrows the bracket
// to kBisectRelative of the time scale, stopping early at any sample in
// (s/2, s] and otherwise returning the safe side.
//
// With a graze tolerance g > 0 every step is at least g/B: a window of span
// T then takes at most B T / g advancement steps, whatever the separation
// (pairs sliding in contact search below a gap of a few ulps); a sample
// past the contact is bisected back as above, so only a dip of at most g
// that recovers between two samples is missed.
//
// Termination: every advancement step is at least s/(2B) (or the time
// resolution), so the number of steps is bounded by 2B(t1 − t0)/s; as a safety
// net kMaxQueries caps the total.  When the cap is hit the last safe time is
// returned (its distance exceeds s): the caller sees a possible contact
// instead of a skipped one, and can resume from there.
//
// Rejected alternatives:
//   * Fixed-step sampling plus bisection (the seed's description): a step
//     larger than s/B can tunnel through thin objects.
//   * Root finding on a swept-volume or interval-arithmetic distance: much
//     more code, and needs motion models beyond "pose at time t".
#include <algorithm>
#include <cmath>

#include "core/collide/collide.h"

namespace asgard::collide {
namespace {

constexpr int kMaxAdvances = 200;
constexpr int kMaxQueries = 100000;
constexpr int kMaxBisections = 200;
constexpr double kStallRelative = 1e-15;
constexpr double kBisectRelative = 1e-12;

// Radius about the body origin whose motion bounds the change of distance: a
// sphere's distance to anything depends only on its centre, so spinning
// about its own centre does not count.
double ReachRadius(const Piece& piece) {
  return piece.is_sphere ? piece.center.norm() : piece.bound_radius;
}

}  // namespace

std::optional<ImpactResult> TimeOfImpact(const Piece& a, const Motion& ma, const Piece& b,
                                         const Motion& mb, double t0, double t1, double separation,
                                         DistanceCache* cache, double graze) {
  DistanceCache local;
  DistanceCache* c = cache != nullptr ? cache : &local;
  ImpactResult out;
  auto query = [&](double t) {
    ++out.iterations;
    return Distance(a, ma.pose(t), b, mb.pose(t), c);
  };
  auto land = [&](double t, const DistanceResult& r) {
    out.time = t;
    out.contact = r;
    return std::optional<ImpactResult>(out);
  };

  DistanceResult r = query(t0);
  if (r.overlapping || r.distance <= separation) return land(t0, r);
  if (!(t1 > t0)) return std::nullopt;
  const double bound = std::abs(ma.max_linear_speed) + std::abs(mb.max_linear_speed) +
                       std::abs(ma.max_angular_speed) * ReachRadius(a) +
                       std::abs(mb.max_angular_speed) * ReachRadius(b);
  if (!(bound > 0.0)) return std::nullopt;  // nothing moves: the distance stays > separation
  const double span = t1 - t0;
  auto resolution = [&](double t) { return kStallRelative * std::max(std::abs(t), span); };

  // Closing-speed bound along the normal of the latest query (see Motion):
  // the gap along a fixed axis is a lower bound of the distance and equals
  // it at the query, so stepping by it is as safe as by `bound`.
  const double ra = ReachRadius(a), rb = ReachRadius(b);
  auto closing = [&](const DistanceResult& q) {
    const Eigen::Vector3d& n = q.normal;
    const double along = std::abs(n.dot(mb.v0 - ma.v0)) + ma.dv + mb.dv +
                         (ma.w0.cross(n).norm() + ma.dw) * ra +
                         (mb.w0.cross(n).norm() + mb.dw) * rb;
    return std::isfinite(along) && along > 0.0 ? std::min(bound, along) : bound;
  };
  double t = t0;  // safe: distance > separation
  int advances = 0;
  while (true) {
    if (out.iterations >= kMaxQueries) return land(t, r);
    const double speed = closing(r);
    const double step = std::max(r.distance - 0.5 * separation, graze) / speed;
    const bool slow = advances >= kMaxAdvances || step < resolution(t);
    const double t_next = std::min(
        t1, slow ? t + std::max(std::max(r.distance, graze) / speed, resolution(t)) : t + step);
    ++advances;
    const DistanceResult rn = query(t_next);
    if (!rn.overlapping && rn.distance <= separation && rn.distance > 0.5 * separation) {
      return land(t_next, rn);
    }
    if (!rn.overlapping && rn.distance > separation) {
      if (t_next >= t1) return std::nullopt;
      t = t_next;
      r = rn;
      continue;
    }
    // rn overlaps or came within s/2: bisect [t, t_next] on distance − s/2.
    double lo = t;
    double hi = t_next;
    DistanceResult r_lo = r;
    DistanceResult r_hi = rn;
    for (int k = 0; k < kMaxBisections; ++k) {
      if (hi - lo <= kBisectRelative * std::max({std::abs(lo), std::abs(hi), span})) break;
      const double mid = lo + 0.5 * (hi - lo);
      if (!(mid > lo && mid < hi)) break;
      const DistanceResult rm = query(mid);
      if (rm.overlapping || rm.distance <= 0.5 * separation) {
        hi = mid;
        r_hi = rm;
      } else if (rm.distance <= separation) {
        return land(mid, rm);
      } else {
        lo = mid;
        r_lo = rm;
      }
    }
    // The unsafe end is returned only when it still has a positive distance
    // within the separation (a jump past s/2 that bisection cannot resolve).
    if (!r_hi.overlapping && r_hi.distance > 0.0 && r_lo.distance > separation &&
        r_hi.distance <= separation) {
      return land(hi, r_hi);
    }
    return land(lo, r_lo);
  }
}

}  // namespace asgard::collide
