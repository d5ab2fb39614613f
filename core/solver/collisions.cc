// The collision monitor (design note in collisions.h).
//
// Stages per window: Boxes → BroadPhase → FirstImpact per pair (TimeOfImpact
// per piece pair) → Respond to the earliest → (truncations) → AfterTruncate
// invalidates what depended on truncated data.
#include "core/solver/collisions.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/solver/hermite_range.h"

namespace asgard::solver {
namespace {

constexpr long kEpochs = 1024;
constexpr double kHopHeight = 1e-3;       // of the body's size: resting hops rise less
constexpr double kMarginRelative = 0.02;  // contact points kept up to this gap (of size)
constexpr int kSleepEvents = 12;          // resting events at rest in a row before sleep
constexpr double kSleepSpan = 0.25;       // seconds at rest before sleep, at least
constexpr double kSleepDrift = 0.1;       // hop heights a body at rest may turn by
constexpr int kSweeps = 200;              // contact solver sweeps at most
constexpr int kJamEvents = 50;            // impacts at one instant before they count as a jam
constexpr double kHoldTurn = 8.0;         // hop heights a held pair's bodies may turn by
constexpr double kLongestHop = 0.1;       // seconds: a resting contact's hop at most
// The landing gap: at least this fraction of the smallest body's radius
// (double precision cannot place bodies closer meaningfully).
constexpr double kMinSeparation = 1e-8;
// Patch features within this fraction of the larger radius count as touching.
constexpr double kPatchTolerance = 1e-6;
// A rise after an impact below this fraction of the radius is resting
// contact (further bounces would be invisible and infinitely many).
constexpr double kRestingRise = 1e-6;
// A graze of a pair's smaller body by at most this fraction of its radius
// may go unseen by the time-of-impact search (collide::TimeOfImpact): it
// bounds that search's steps per window whatever the landing gap.
constexpr double kGraze = 1e-3;
// Loose boxes (CheckEpoch) take in a body's new range while each side stays
// within kLooseGrowth radii, and reach kLooseMargin radii, or the way the
// body goes in kLooseWindows windows at its window's pace, beyond the range;
// more than kLooseSweep refits in one check find every body's neighbours in
// one sweep instead of one pass over the bodies per refit.
constexpr double kLooseGrowth = 8.0;
constexpr double kLooseMargin = 0.25;
constexpr double kLooseWindows = 8.0;
constexpr size_t kLooseSweep = 8;
// A window in which fewer than an eighth of kLooseCrowd or more moving
// bodies are lone leaves loose boxes aside for kLooseBackoff windows,
// doubling up to kLooseBackoffMax while they keep not paying.
// (CollisionMonitor::kLooseBackoff, kLooseBackoffMax.)
constexpr size_t kLooseCrowd = 16;
// Approach speeds within this many roundings of the speeds are no approach.
constexpr double kApproachRoundOff = 1e-12;
// A pair touching at a window's start whose points approach slower than
// this fraction of the landing gap per window is touching, not landing.
constexpr double kCreep = 1e-3;
// The conservative-advancement search starts with a step of this fraction
// of the time (round-off) plus kSearchStartWindow of the interval.
constexpr double kSearchStartTime = 1e-12, kSearchStartWindow = 1e-9;

// Impacts in time order; at one instant by pair.
bool ImpactOrder(const Impact& x, const Impact& y) {
  return x.t != y.t ? x.t < y.t : std::tie(x.a, x.b) < std::tie(y.a, y.b);
}

// Every body an event involves, once: its pair and its island.
std::vector<int> Participants(const Impact& x) {
  std::vector<int> out = {x.a, x.b};
  for (int b : x.bodies)
    if (std::find(out.begin(), out.end(), b) == out.end()) out.push_back(b);
  return out;
}
constexpr double kInf = std::numeric_limits<double>::infinity();

// Points of a piece's support feature in direction n (world): the vertices
// within `tol` of the extreme, or a sphere's single support point.
std::vector<Eigen::Vector3d> SupportFeature(const collide::Piece& piece, const collide::Pose& pose,
                                            const Eigen::Vector3d& n, double tol) {
  if (piece.is_sphere) return {pose.p + pose.R * piece.center + piece.radius * n};
  double best = -kInf;
  std::vector<Eigen::Vector3d> world;
  for (const auto& v : piece.vertices) {
    world.push_back(pose.p + pose.R * v);
    best = std::max(best, world.back().dot(n));
  }
  std::vector<Eigen::Vector3d> out;
  for (const auto& w : world)
    if (w.dot(n) >= best - tol) out.push_back(w);
  return out;
}

// Convex polygon (2D, counter-clockwise) of a point set: Andrew's monotone
// chain over the points sorted by x then y, collinear points dropped.
std::vector<Eigen::Vector2d> ConvexPolygon(std::vector<Eigen::Vector2d> pts) {
  std::sort(pts.begin(), pts.end(), [](const auto& a, const auto& b) {
    return a.x() != b.x() ? a.x() < b.x() : a.y() < b.y();
  });
  if (pts.size() < 3) return pts;
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> hull(2 * pts.size());
  size_t k = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], pts[i - 1]) <= 0) --k;
    hull[k++] = pts[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

// Clips polygon `subject` by convex CCW polygon `clip` (Sutherland–Hodgman).
std::vector<Eigen::Vector2d> Clip(std::vector<Eigen::Vector2d> subject,
                                  const std::vector<Eigen::Vector2d>& clip) {
  for (size_t i = 0; i < clip.size() && !subject.empty(); ++i) {
    const Eigen::Vector2d a = clip[i], b = clip[(i + 1) % clip.size()];
    auto side = [&](const Eigen::Vector2d& p) {
      return (b - a).x() * (p - a).y() - (b - a).y() * (p - a).x();
    };
    std::vector<Eigen::Vector2d> out;
    for (size_t j = 0; j < subject.size(); ++j) {
      const Eigen::Vector2d p = subject[j], q = subject[(j + 1) % subject.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0) out.push_back(p);
      if ((sp >= 0) != (sq >= 0)) out.push_back(p + (q - p) * (sp / (sp - sq)));
    }
    subject = std::move(out);
  }
  return subject;
}

// Where the impulse acts: the centre of the contact patch — the overlap of
// the two support features (face, edge or vertex) seen along the normal.
// GJK's closest points are one arbitrary pair when faces or edges are
// parallel; pushing there would spin two cubes that meet face to face.
Eigen::Vector3d ContactPoint(const collide::Piece& a, const collide::Pose& pa,
                             const collide::Piece& b, const collide::Pose& pb,
                             const collide::DistanceResult& c, double tol) {
  const Eigen::Vector3d mid = 0.5 * (c.point_a + c.point_b);
  if (a.is_sphere || b.is_sphere) return mid;
  const Eigen::Vector3d n = c.normal;
  const auto fa = SupportFeature(a, pa, n, tol);
  const auto fb = SupportFeature(b, pb, -n, tol);
  if (fa.size() == 1) return fa[0] + 0.5 * (c.point_b - c.point_a);
  if (fb.size() == 1) return fb[0] - 0.5 * (c.point_b - c.point_a);
  // Plane coordinates.
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  auto flat = [&](const std::vector<Eigen::Vector3d>& pts) {
    std::vector<Eigen::Vector2d> out;
    for (const auto& p : pts) out.emplace_back((p - mid).dot(u), (p - mid).dot(v));
    return ConvexPolygon(out);
  };
  const auto pa2 = flat(fa), pb2 = flat(fb);
  std::vector<Eigen::Vector2d> patch;
  if (pb2.size() >= 3)
    patch = Clip(pa2, pb2);
  else if (pa2.size() >= 3)
    patch = Clip(pb2, pa2);
  else {
    // Two segments: the centre of their overlap, or the closest points' midpoint.
    return mid;
  }
  if (patch.empty()) return mid;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const auto& p : patch) centre += p;
  centre /= static_cast<double>(patch.size());
  // The vertex average is the centroid for the symmetric patches that matter
  // (face on face, edge on face); area weighting is not needed for the
  // direction of the push.
  return mid + centre.x() * u + centre.y() * v;
}

}  // namespace

CollisionMonitor::CollisionMonitor(Simulation& sim, double separation)
    : sim_(sim), sys_(sim.system()), separation_(separation) {
  epoch_length_ = (sys_.t1 - sys_.t0) / kEpochs;
  bodies_.resize(sys_.bodies.size());
  recent_.resize(sys_.bodies.size());
  spans_.resize(sys_.bodies.size());
  open_.Reset(sys_.bodies.size());
  bodies_of_component_.resize(sim.component_count());
  version_.assign(sys_.bodies.size(), 0);
  double min_radius = kInf;
  for (size_t b = 0; b < sys_.bodies.size(); ++b) {
    const physics::BodyModel& m = sys_.bodies[b];
    BodyInfo& info = bodies_[b];
    info.infinite = m.is_static;
    for (const auto& piece : m.pieces) {
      if (piece.is_sphere) {
        info.pieces.push_back(collide::Piece::Sphere(piece.center, piece.radius));
      } else {
        std::vector<std::vector<int>> faces;
        for (const auto& f : piece.hull.faces) faces.push_back(f.vertices);
        info.pieces.push_back(collide::Piece::Polytope(piece.hull.vertices, faces));
      }
      info.radius = std::max(info.radius, info.pieces.back().bound_radius);
    }
    info.collidable = !info.pieces.empty();
    if (info.collidable) min_radius = std::min(min_radius, info.radius);
    if (m.first_var < 0 && info.collidable) {
      // A static body's own box, exact: a wall is a candidate only for what
      // comes near it, not for everything inside its bounding sphere.
      const collide::Pose pose = PoseAt(static_cast<int>(b), sys_.t0);
      info.lo = Eigen::Vector3d::Constant(kInf);
      info.hi = Eigen::Vector3d::Constant(-kInf);
      for (const auto& piece : info.pieces) {
        if (piece.is_sphere) {
          const Eigen::Vector3d c = pose.p + pose.R * piece.center;
          info.lo = info.lo.cwiseMin(c - Eigen::Vector3d::Constant(piece.radius));
          info.hi = info.hi.cwiseMax(c + Eigen::Vector3d::Constant(piece.radius));
        }
        for (const auto& v : piece.vertices) {
          info.lo = info.lo.cwiseMin(pose.p + pose.R * v);
          info.hi = info.hi.cwiseMax(pose.p + pose.R * v);
        }
      }
    }
    if (m.first_var >= 0) {
      for (int s = 0; s < physics::kBodySlots; ++s)
        info.components.push_back(sim.component_of(m.first_var + s));
      std::sort(info.components.begin(), info.components.end());
      info.components.erase(std::unique(info.components.begin(), info.components.end()),
                            info.components.end());
      for (int c : info.components) bodies_of_component_[c].push_back(static_cast<int>(b));
    }
    UpdateEnd(static_cast<int>(b));
  }
  const size_t n = bodies_.size();
  box_version_.assign(n, -1);
  box_lo_.resize(n);
  box_hi_.resize(n);
  rest_from_.assign(n, -kInf);
  rest_until_.assign(n, kInf);
  window_stamp_.assign(n, 0);
  loose_lo_.resize(n);
  loose_hi_.resize(n);
  loose_from_.assign(n, kInf);
  loose_until_.assign(n, -kInf);
  loose_scanned_.assign(n, -kInf);
  loose_version_.assign(n, -1);
  near_.resize(n);
  near_static_.assign(n, 0);
  carried_until_.assign(n, -kInf);
  carried_times_.resize(n);
  found_times_.resize(n);
  held_aside_.Reset(n);
  for (size_t b = 0; b < n; ++b)
    if (bodies_[b].collidable && sys_.bodies[b].first_var >= 0)
      moving_all_.push_back(static_cast<int>(b));
  moving_.Reset(n);
  for (size_t b = 0; b < n; ++b)
    if (bodies_[b].collidable && sys_.bodies[b].first_var >= 0) moving_.Insert(static_cast<int>(b));
  // The static bodies' boxes, widened by the landing gap, in the broad
  // phase's tree for the whole run.
  for (size_t b = 0; b < bodies_.size(); ++b)
    if (bodies_[b].collidable && sys_.bodies[b].first_var < 0)
      for (collide::BroadPhase* phase : {&broad_, &loose_broad_})
        phase->AddStatic(static_cast<int>(b),
                         bodies_[b].lo - Eigen::Vector3d::Constant(separation_),
                         bodies_[b].hi + Eigen::Vector3d::Constant(separation_));
  // Bodies land this close before an impact.  Positions are only as exact as
  // the solver's tolerance, and after an impact the components re-step to it,
  // so the gap must exceed that error or the re-stepped bodies would overlap.
  if (separation_ <= 0) {
    const double r = std::isfinite(min_radius) ? min_radius : 1.0;
    separation_ = std::max(kMinSeparation * r, sim.options().rtol * r + sim.options().atol);
  }
  for (auto [a, b] : sys_.body_links) {
    const auto& ma = sys_.bodies[a];
    const auto& mb = sys_.bodies[b];
    if (!ma.artbody.empty() && ma.artbody == mb.artbody)
      excluded_.insert({std::min(a, b), std::max(a, b)});
  }
  // A scene in which no pair can collide (every body -ct 0, or joined in
  // one articulated body) needs no windows at all.
  idle_ = true;
  for (size_t a = 0; a < bodies_.size() && idle_; ++a)
    for (size_t b = a + 1; b < bodies_.size() && idle_; ++b)
      if (Tested(static_cast<int>(a), static_cast<int>(b))) idle_ = false;
  sim.after_step = [this](Simulation&, int c) { AfterStep(c); };
  sim.on_truncate = [this](Simulation&, int c, double kept) { OnTruncate(c, kept); };
  sim.after_truncate = [this](Simulation&) { AfterTruncate(); };
  StartEpoch(0);
}

void CollisionMonitor::AdoptImpacts(const std::vector<Impact>& impacts,
                                    const std::vector<char>& carried) {
  if (idle_) {
    // No window is checked: the events stand as they are.
    for (const Impact& x : impacts) NoteFound(x, true);
    impacts_.insert(impacts_.end(), impacts.begin(), impacts.end());
    std::stable_sort(impacts_.begin(), impacts_.end(), ImpactOrder);
    return;
  }
  adopted_ = true;
  for (size_t b = 0; b < bodies_.size() && b < carried.size(); ++b) {
    if (!carried[b]) continue;
    carried_until_[b] = ComputedUntil(static_cast<int>(b));  // a static body: for all time
  }
  // Latest first, so that the earliest is taken from the back; stable, so
  // that events of one pair at one instant (a jam, a resting island) are
  // reached in the order they happened in, which SlowEvents reads.
  carried_ = impacts;
  std::stable_sort(carried_.begin(), carried_.end(), ImpactOrder);
  std::reverse(carried_.begin(), carried_.end());
  for (const Impact& x : carried_) NoteHeldAside(x, true);
  // The windows the carried bodies alone decide are checked now: a run in
  // which every body was carried over takes no step, and steps are what
  // bring windows up for checking.
  for (size_t b = 0; b < bodies_.size(); ++b) UpdateEnd(static_cast<int>(b));
  StartEpoch(0);
  CheckReadyWindows();
}

void CollisionMonitor::Reopen(double t) {
  adopted_ = true;
  // What the windows checked so far established: every body's motion up to
  // the first window not complete (a body cut back, up to where it was cut).
  const double checked = epoch_ >= kEpochs ? sys_.t1 : EpochStart(epoch_);
  for (size_t b = 0; b < bodies_.size(); ++b) {
    carried_until_[b] =
        std::max(carried_until_[b], std::min(ComputedUntil(static_cast<int>(b)), checked));
  }
  // The events found after t are reached again, in time order.
  const auto after = std::upper_bound(impacts_.begin(), impacts_.end(), t,
                                      [](double time, const Impact& x) { return time < x.t; });
  if (after == impacts_.end()) return;
  for (auto it = after; it != impacts_.end(); ++it) {
    NoteHeldAside(*it, true);
    NoteFound(*it, false);
  }
  std::reverse(carried_.begin(), carried_.end());
  carried_.insert(carried_.end(), std::make_move_iterator(after),
                  std::make_move_iterator(impacts_.end()));
  impacts_.erase(after, impacts_.end());
  std::stable_sort(carried_.begin(), carried_.end(), ImpactOrder);
  std::reverse(carried_.begin(), carried_.end());
  // Impacts at one instant count from the latest event still found.
  same_instant_ = 0;
  last_impact_time_ = impacts_.empty() ? -1e300 : impacts_.back().t;
  for (size_t i = impacts_.size(); i-- > 1 && impacts_[i - 1].t == last_impact_time_;)
    ++same_instant_;
}

void CollisionMonitor::NoteFound(const Impact& x, bool add) {
  for (int body : Participants(x)) {
    auto& times = found_times_[static_cast<size_t>(body)];
    if (add)
      times.insert(x.t);
    else
      times.erase(times.find(x.t));
  }
}

void CollisionMonitor::NoteHeldAside(const Impact& x, bool add) {
  for (int body : Participants(x)) {
    auto& times = carried_times_[static_cast<size_t>(body)];
    if (add) {
      times.insert(x.t);
      if (!held_aside_.Contains(body)) held_aside_.Insert(body);
    } else {
      times.erase(times.find(x.t));
      if (times.empty()) held_aside_.Erase(body);
    }
  }
}

void CollisionMonitor::ReachCarried() {
  Impact x = std::move(carried_.back());
  carried_.pop_back();
  NoteHeldAside(x, false);
  // As a response to it would have: its hop is looked back over for holds,
  // and it counts towards impacts at one instant.
  longest_hop_ = std::max(longest_hop_, x.hop);
  same_instant_ = x.t == last_impact_time_ ? same_instant_ + 1 : 0;
  last_impact_time_ = x.t;
  NoteFound(x, true);
  const auto pos = std::upper_bound(impacts_.begin(), impacts_.end(), x, ImpactOrder);
  impacts_.insert(pos, std::move(x));
}

double CollisionMonitor::LandingStart(int body, double u) const {
  double start = kInf;
  for (int c : bodies_[static_cast<size_t>(body)].components) {
    const Waveform& w = sim_.component(c).waveform();
    int k = w.KeepIndex(u);
    while (k > 0 && w.time(k) >= u) --k;
    start = std::min(start, w.time(k));
  }
  return start;
}

double CollisionMonitor::ComputedUntil(int body) const {
  double until = kInf;
  for (int c : bodies_[static_cast<size_t>(body)].components)
    until = std::min(until, sim_.component(c).t_end());
  return until;
}

std::optional<double> CollisionMonitor::ExposedFrom(int body, double e1) const {
  // The run from scratch has not found the body's next event held aside
  // yet, and its step there went on unbroken: where the step landing the
  // body on that event starts before e1, the body's motion in the window is
  // not the one that run has at this point.
  if (!held_aside_.Contains(body) || bodies_[static_cast<size_t>(body)].components.empty())
    return std::nullopt;
  const double start = LandingStart(body, *carried_times_[static_cast<size_t>(body)].begin());
  if (start < e1) return start;
  return std::nullopt;
}

bool CollisionMonitor::CutExposed(std::vector<int> bodies, double e1) {
  std::sort(bodies.begin(), bodies.end());
  bodies.erase(std::unique(bodies.begin(), bodies.end()), bodies.end());
  bool cut = false;
  for (int body : bodies) {
    const std::optional<double> start = ExposedFrom(body, e1);
    if (!start) continue;
    // Back to the landing step's start: the event and what followed from it
    // are forgotten (AfterTruncate), and the body steps on as the run from
    // scratch does until it finds what comes next.
    cutting_ = true;
    for (int c : bodies_[static_cast<size_t>(body)].components) sim_.Truncate(c, *start);
    cutting_ = false;
    cut = true;
  }
  return cut;
}

std::vector<int> CollisionMonitor::IslandReach(int a, int b, double e0, double e1) {
  // Every body an island grown from a and b in the window could take in:
  // boxes of the bodies' range over the window, widened by the contact
  // margin (how far apart an island's members may be), overlapping in a
  // chain from a or b through moving bodies.
  const size_t n = bodies_.size();
  std::vector<Eigen::Vector3d> lo(n), hi(n);
  std::vector<char> boxed(n, 0), in(n, 0);
  auto box = [&](int body) {
    const size_t i = static_cast<size_t>(body);
    if (boxed[i]) return;
    boxed[i] = 1;
    if ((window_stamp_[i] == window_serial_ && box_version_[i] == version_[i]) ||
        broad_.Resting(body)) {
      lo[i] = box_lo_[i];
      hi[i] = box_hi_[i];
    } else {
      PositionRange(body, e0, e1, lo[i], hi[i]);
      const Eigen::Vector3d r = Eigen::Vector3d::Constant(bodies_[i].radius + separation_);
      lo[i] -= r;
      hi[i] += r;
    }
    const Eigen::Vector3d m =
        Eigen::Vector3d::Constant(std::max(4.0 * separation_, kMarginRelative * bodies_[i].radius));
    lo[i] -= m;
    hi[i] += m;
  };
  std::vector<int> reach;
  for (int body : {a, b})
    if (!bodies_[static_cast<size_t>(body)].components.empty() && !in[static_cast<size_t>(body)]) {
      in[static_cast<size_t>(body)] = 1;
      reach.push_back(body);
    }
  for (size_t q = 0; q < reach.size(); ++q) {
    const int x = reach[q];
    box(x);
    for (int y : moving_all_) {
      if (in[static_cast<size_t>(y)]) continue;
      box(y);
      if (!collide::BoxesOverlap(lo[static_cast<size_t>(x)], hi[static_cast<size_t>(x)],
                                 lo[static_cast<size_t>(y)], hi[static_cast<size_t>(y)]))
        continue;
      in[static_cast<size_t>(y)] = 1;
      reach.push_back(y);
    }
  }
  return reach;
}

bool CollisionMonitor::Tested(int a, int b) const {
  if (a == b) return false;
  const auto& A = bodies_[a];
  const auto& B = bodies_[b];
  if (!A.collidable || !B.collidable || (A.infinite && B.infinite)) return false;
  if (!sys_.bodies[a].collision_test && !sys_.bodies[b].collision_test) return false;
  return !excluded_.count({std::min(a, b), std::max(a, b)});
}

double CollisionMonitor::EpochStart(long k) const {
  return k >= kEpochs ? sys_.t1 : sys_.t0 + static_cast<double>(k) * epoch_length_;
}

void CollisionMonitor::UpdateEnd(int b) {
  BodyInfo& info = bodies_[b];
  const double end = info.components.empty() ? sys_.t1 : ComputedUntil(b);  // static: all time
  info.end = end;
  // Keep open_ the collidable bodies computed short of the end.
  if (info.collidable && end < sys_.t1)
    open_.Insert(b);
  else
    open_.Erase(b);
}

void CollisionMonitor::StartEpoch(long k) {
  epoch_ = idle_ ? kEpochs : k;
  pending_ = 0;
  if (epoch_ >= kEpochs) return;
  // Only bodies computed short of the end can be short of this window's
  // end: a thousand bodies resting to the end cost nothing per window.
  const double e1 = EpochStart(epoch_ + 1);
  for (int b : open_)
    if (bodies_[static_cast<size_t>(b)].end < e1) ++pending_;
}

void CollisionMonitor::AfterStep(int component) {
  if (epoch_ >= kEpochs) return;
  const double e1 = EpochStart(epoch_ + 1);
  for (int b : bodies_of_component_[component]) {
    const double old = bodies_[b].end;
    UpdateEnd(b);
    if (!bodies_[b].collidable) continue;
    FollowLoose(b);
    if (old < e1 && bodies_[b].end >= e1) --pending_;
  }
  CheckReadyWindows();
}

void CollisionMonitor::CheckReadyWindows() {
  while (pending_ == 0 && epoch_ < kEpochs) {
    if (!CheckEpoch()) break;
    StartEpoch(epoch_ + 1);
  }
}

// ---- the window check ----------------------------------------------------------

// Calls f(cubic, s0, s1, h) for each piece of a variable's playback
// interpolant over [t0, t1], restricted to the window (s in [s0, s1]).
template <typename F>
void CollisionMonitor::ForEachSegment(int var, double t0, double t1, F&& f) const {
  const Waveform& w = sim_.component(sim_.component_of(var)).waveform();
  const int i = sim_.local_index(var);
  for (int k = w.KeepIndex(t0); k + 1 < w.size() && w.time(k) < t1; ++k) {
    const double h = w.time(k + 1) - w.time(k);
    if (h <= 0) continue;
    const Cubic p =
        HermiteCubic(w.x(k)[i], w.f(k)[i], w.x(k + 1)[i], w.f(k + 1)[i], h, w.bubble(k + 1)[i]);
    f(p, std::max(0.0, (t0 - w.time(k)) / h), std::min(1.0, (t1 - w.time(k)) / h), h);
  }
}

void CollisionMonitor::Rest(int b) {
  const size_t i = static_cast<size_t>(b);
  broad_.AddResting(b, box_lo_[i], box_hi_[i]);
  rest_by_from_.insert({rest_from_[i], b});
  rest_by_until_.insert({rest_until_[i], b});
  moving_.Erase(b);
}

void CollisionMonitor::Unrest(int b) {
  const size_t i = static_cast<size_t>(b);
  broad_.RemoveResting(b);
  // Others found their neighbours against its resting box: it finds its
  // own again (CheckEpoch) before it counts as lone.
  loose_version_[i] = -1;
  rest_by_from_.erase({rest_from_[i], b});
  rest_by_until_.erase({rest_until_[i], b});
  moving_.Insert(b);
}

std::optional<std::pair<double, double>> CollisionMonitor::HeldSpan(int b, double t0,
                                                                    double t1) const {
  const physics::BodyModel& m = sys_.bodies[b];
  if (m.first_var < 0) return std::nullopt;
  double from = -kInf, until = kInf;
  for (int slot : {physics::kX, physics::kY, physics::kZ, physics::kQw, physics::kQx, physics::kQy,
                   physics::kQz}) {
    const int var = m.first_var + slot;
    const Waveform& w = sim_.component(sim_.component_of(var)).waveform();
    const int i = sim_.local_index(var);
    const int k = w.KeepIndex(t0);
    const double x = w.x(k)[i];
    if (w.f(k)[i] != 0) return std::nullopt;
    int j = k;
    while (j + 1 < w.size() && w.x(j + 1)[i] == x && w.f(j + 1)[i] == 0 && w.bubble(j + 1)[i] == 0)
      ++j;
    if (w.time(j) < t1) return std::nullopt;
    from = std::max(from, w.time(k));
    until = std::min(until, w.time(j));
  }
  return std::pair{from, until};
}

void CollisionMonitor::PositionRange(int b, double t0, double t1, Eigen::Vector3d& lo,
                                     Eigen::Vector3d& hi) const {
  const physics::BodyModel& m = sys_.bodies[static_cast<size_t>(b)];
  for (int a = 0; a < 3; ++a) {
    const int var = m.first_var + physics::kX + a;
    lo[a] = hi[a] = sim_.Value(var, t0);
    ForEachSegment(var, t0, t1, [&](const Cubic& p, double s0, double s1, double) {
      ValueRange(p, s0, s1, lo[a], hi[a]);
    });
  }
}

// ---- loose boxes --------------------------------------------------------------------
//
// Boxing every moving body for every window costs bodies × windows even
// where nothing is near anything (a thousand swinging pendulums: a million
// boxes, each sampled from its waveform, and a sweep of a thousand boxes per
// window).  Each body instead keeps a loose box that holds its motion for
// as long as it stays inside — checked step by step as its components
// advance, on the newest pieces of its waveform — and its neighbours, the
// bodies it is tested with whose loose boxes (or static boxes) overlap it.
// Only bodies with neighbours are boxed for a window.  A box that grows from
// its previous one while small takes in a periodic motion (a swing) after a
// few refits and then holds for good; a body travelling far starts again
// from its window's range.

void CollisionMonitor::Loosen(int b, double e0, double e1) {
  const size_t i = static_cast<size_t>(b);
  Eigen::Vector3d lo, hi;
  PositionRange(b, e0, e1, lo, hi);
  // A quarter radius beyond the range, or the way it moved in
  // kLooseWindows windows at its speed in this one.
  const double margin =
      std::max(kLooseMargin * bodies_[i].radius, kLooseWindows * (hi - lo).maxCoeff());
  if (loose_version_[i] >= 0) {
    const Eigen::Vector3d plo = loose_lo_[i].array() + margin, phi = loose_hi_[i].array() - margin;
    const Eigen::Vector3d glo = lo.cwiseMin(plo), ghi = hi.cwiseMax(phi);
    if ((ghi - glo).maxCoeff() <= kLooseGrowth * bodies_[i].radius) lo = glo, hi = ghi;
  }
  loose_lo_[i] = lo.array() - margin;
  loose_hi_[i] = hi.array() + margin;
  loose_from_[i] = e0;
  loose_until_[i] = kInf;
  loose_scanned_[i] = e0;
  loose_version_[i] = version_[i];
  ++counters_.loose_boxes;
  FollowLoose(b);
}

void CollisionMonitor::FollowLoose(int b) {
  const size_t i = static_cast<size_t>(b);
  if (!LooseOn() || loose_version_[i] != version_[i] || loose_until_[i] < kInf) return;
  const double t0 = loose_scanned_[i], t1 = bodies_[i].end;
  if (!(t1 > t0)) return;
  const physics::BodyModel& m = sys_.bodies[i];
  for (int a = 0; a < 3; ++a) {
    const int var = m.first_var + physics::kX + a;
    const Waveform& w = sim_.component(sim_.component_of(var)).waveform();
    const int li = sim_.local_index(var);
    // The pieces since the last check: the newest few, found from the end.
    int k = w.size() - 1;
    while (k > 0 && w.time(k) > t0) --k;
    for (; k + 1 < w.size() && w.time(k) < t1; ++k) {
      const double h = w.time(k + 1) - w.time(k);
      if (h <= 0) continue;
      const Cubic p = HermiteCubic(w.x(k)[li], w.f(k)[li], w.x(k + 1)[li], w.f(k + 1)[li], h,
                                   w.bubble(k + 1)[li]);
      // The piece in spans of a window (a ballistic piece or a rest step
      // may last the whole run): the body leaves no earlier than the first
      // span that leaves.
      const double s0 = std::max(0.0, (t0 - w.time(k)) / h);
      const double s1 = std::min(1.0, (t1 - w.time(k)) / h);
      const double leave =
          FirstSpanLeaving(p, s0, s1, epoch_length_ / h, loose_lo_[i][a], loose_hi_[i][a]);
      if (leave >= 0) {
        loose_until_[i] = std::min(loose_until_[i], w.time(k) + leave * h);
        break;
      }
    }
  }
  loose_scanned_[i] = t1;
}

bool CollisionMonitor::LooseHolds(int b, double e0, double e1) const {
  const size_t i = static_cast<size_t>(b);
  return loose_version_[i] == version_[i] && loose_from_[i] <= e0 && e1 <= loose_until_[i] &&
         e1 <= loose_scanned_[i];
}

void CollisionMonitor::Near(const std::vector<int>& refit) {
  const size_t n = bodies_.size();
  // What a body can reach: a static body's box, a resting body's box (it
  // does not move while it rests), a moving body's loose box.
  auto reach = [&](size_t c, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
    if (!bodies_[c].collidable) return false;
    if (bodies_[c].infinite) {
      lo = bodies_[c].lo - Eigen::Vector3d::Constant(separation_);
      hi = bodies_[c].hi + Eigen::Vector3d::Constant(separation_);
    } else if (broad_.Resting(static_cast<int>(c))) {
      lo = box_lo_[c];
      hi = box_hi_[c];
    } else if (loose_version_[c] >= 0) {
      const Eigen::Vector3d r = Eigen::Vector3d::Constant(bodies_[c].radius + separation_);
      lo = loose_lo_[c] - r;
      hi = loose_hi_[c] + r;
    } else {
      return false;
    }
    return true;
  };
  auto link = [&](int a, int b) {
    if (!Tested(a, b)) return;
    if (bodies_[static_cast<size_t>(a)].infinite) std::swap(a, b);
    if (bodies_[static_cast<size_t>(b)].infinite) {
      near_static_[static_cast<size_t>(a)] = 1;
      return;
    }
    near_[static_cast<size_t>(a)].push_back(b);
    near_[static_cast<size_t>(b)].push_back(a);
  };
  if (refit.size() > kLooseSweep) {
    loose_broad_.Clear();  // its static boxes stay
    for (size_t c = 0; c < n; ++c) {
      near_[c].clear();
      near_static_[c] = 0;
      Eigen::Vector3d lo, hi;
      if (!bodies_[c].infinite && reach(c, lo, hi)) loose_broad_.Add(static_cast<int>(c), lo, hi);
    }
    for (auto [a, b] : loose_broad_.Pairs()) link(a, b);
    return;
  }
  std::vector<char> done(n, 0);
  for (int b : refit) {
    const size_t i = static_cast<size_t>(b);
    for (int c : near_[i]) std::erase(near_[static_cast<size_t>(c)], b);
    near_[i].clear();
    near_static_[i] = 0;
  }
  for (int b : refit) {
    const size_t i = static_cast<size_t>(b);
    Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = lo, clo = lo, chi = lo;
    if (!reach(i, lo, hi)) continue;  // a moving body refit here always has its loose box
    for (size_t c = 0; c < n; ++c)
      if (c != i && !done[c] && reach(c, clo, chi) && collide::BoxesOverlap(lo, hi, clo, chi))
        link(b, static_cast<int>(c));
    done[i] = 1;
  }
}

void CollisionMonitor::ReadVelocities(int body, double t, Side side, double* out) const {
  const int v = sys_.bodies[static_cast<size_t>(body)].first_var;
  const int vars[6] = {v + physics::kDx, v + physics::kDy, v + physics::kDz,
                       v + physics::kW1, v + physics::kW2, v + physics::kW3};
  sim_.Values(vars, 6, t, out, side);
}

collide::Pose CollisionMonitor::PoseAt(int b, double t, Side side) const {
  const physics::BodyModel& m = sys_.bodies[b];
  collide::Pose pose;
  if (m.first_var < 0) {
    pose.p = m.x0;
    pose.R = m.q0.toRotationMatrix();
    return pose;
  }
  const int v = m.first_var;
  const int vars[7] = {v + physics::kX,  v + physics::kY,  v + physics::kZ, v + physics::kQw,
                       v + physics::kQx, v + physics::kQy, v + physics::kQz};
  double x[7];
  sim_.Values(vars, 7, t, x, side);
  pose.p = {x[0], x[1], x[2]};
  Eigen::Quaterniond q(x[3], x[4], x[5], x[6]);
  pose.R = q.normalized().toRotationMatrix();
  return pose;
}

// A search over [t0, t1] sees the bodies as they reach t1, not as an event
// at t1 leaves them: an edited run carries over events that lie on a
// window's end, which the run from scratch had not found when it searched
// that window (an overlap pushed apart there moved the pose).
collide::Pose CollisionMonitor::SearchPose(int b, double t, double t1) const {
  return PoseAt(b, t, t < t1 ? Side::kRight : Side::kLeft);
}

collide::Motion CollisionMonitor::MotionOf(int b, double t0, double t1) const {
  collide::Motion motion;
  motion.pose = [this, b, t1](double t) { return SearchPose(b, t, t1); };
  const physics::BodyModel& m = sys_.bodies[b];
  if (m.first_var < 0) {
    motion.dv = motion.dw = 0.0;  // static
    return motion;
  }
  // Rates at t0 of x, y, z, the quaternion and the spins, and values at t0
  // (quaternion, spins) and t1 (quaternion), each read once.
  const int v = m.first_var;
  const int rated[10] = {v + physics::kX,  v + physics::kY,  v + physics::kZ,  v + physics::kQw,
                         v + physics::kQx, v + physics::kQy, v + physics::kQz, v + physics::kW1,
                         v + physics::kW2, v + physics::kW3};
  double rate0[10], value0[7], value1[4];
  sim_.Rates(rated, 10, t0, rate0);
  sim_.Values(rated + 3, 7, t0, value0);
  sim_.Values(rated + 3, 4, t1, value1, Side::kLeft);
  // Bounds on the rates of the interpolated position and orientation: the
  // exact maxima of the Hermite derivatives over the window.
  auto rate_max = [&](int k) {
    double r = std::abs(rate0[k]);
    ForEachSegment(rated[k], t0, t1, [&](const Cubic& p, double s0, double s1, double h) {
      r = std::max(r, RateMax(p, s0, s1, h));
    });
    return r;
  };
  double v2 = 0, q2 = 0, qmin2 = kInf;
  for (int a = 0; a < 3; ++a) v2 += std::pow(rate_max(a), 2);
  for (int a = 0; a < 4; ++a) q2 += std::pow(rate_max(3 + a), 2);
  // |q| over the window is at least its smallest sampled norm minus the drift
  // the rate allows; quaternion norms stay near 1.
  for (const double* q : {value0, value1}) {
    double n2 = 0;
    for (int a = 0; a < 4; ++a) n2 += std::pow(q[a], 2);
    qmin2 = std::min(qmin2, n2);
  }
  const double qmin = std::max(1e-3, std::sqrt(qmin2) - std::sqrt(q2) * (t1 - t0));
  motion.max_linear_speed = std::sqrt(v2);
  motion.max_angular_speed = 2.0 * std::sqrt(q2) / qmin;
  // Start values and change bounds (collide::Motion): dω_world/dt = R dω_body/dt.
  double wdot2 = 0;
  for (int a = 0; a < 3; ++a) {
    motion.v0[a] = rate0[a];
    const double wdot = rate_max(7 + a);
    wdot2 += wdot * wdot;
  }
  motion.w0 = PoseAt(b, t0).R * Eigen::Vector3d(value0[4], value0[5], value0[6]);
  motion.dv = AccelBound(b, t0, t1) * (t1 - t0);
  // The orientation interpolant turns at R ω only up to the solver's error.
  motion.dw = std::sqrt(wdot2) * (t1 - t0) + 1e-3 * motion.max_angular_speed;
  return motion;
}

bool CollisionMonitor::Prescribed(int b, double t) const {
  const physics::BodyModel& m = sys_.bodies[b];
  if (m.first_var < 0) return false;
  for (int s = 0; s < physics::kBodySlots; ++s)
    for (const auto& o : sys_.variables[m.first_var + s].overrides)
      if (o.from <= t && t < o.to) return true;
  return false;
}

bool CollisionMonitor::CheckEpoch() {
  const double e0 = EpochStart(epoch_), e1 = EpochStart(epoch_ + 1);
  ++counters_.windows;
  // Boxes bounding each moving body over the window.  A check of the same
  // window again (after an impact in it) recomputes only the boxes of the
  // bodies that changed since (a truncation bumps version_) and only their
  // pairs: the rest are the same boxes, so the same pairs.
  const bool again = boxes_epoch_ == epoch_;
  boxes_epoch_ = epoch_;
  const size_t n = bodies_.size();
  if (!again) {
    ++window_serial_;
    window_moving_.clear();
    // Resting bodies whose span of rest does not cover this window (it ran
    // out, or the check went back before it) are boxed again.
    while (!rest_by_until_.empty() && rest_by_until_.begin()->first < e1)
      Unrest(rest_by_until_.begin()->second);
    while (!rest_by_from_.empty() && rest_by_from_.rbegin()->first > e0)
      Unrest(rest_by_from_.rbegin()->second);
  }
  // Loose boxes that do not hold this window are set again (Loosen), and
  // their neighbours found: only bodies with neighbours are boxed below.
  // The pairs found are those of boxing every body (each window box lies in
  // its body's loose box), so the impacts are too.
  // Where they do not pay (bodies crowded together, every one near another:
  // a box full of balls), they are left for a while, longer each time.
  // A body refit here is boxed once whether lone or not, so that one
  // holding still joins the resting boxes and leaves the per-window loops.
  const bool loose = LooseOn();
  std::vector<int> refit;
  if (loose)
    for (int b : moving_)
      if (!LooseHolds(b, e0, e1)) {
        Loosen(b, e0, e1);
        refit.push_back(b);
        box_version_[static_cast<size_t>(b)] = -1;
      }
  if (!refit.empty()) Near(refit);
  size_t lone = 0;
  // A body holding still is not boxed again: its box is the one it had when
  // it came to rest, among the broad phase's resting boxes, which pair only
  // with moving ones — two bodies that do not move cannot collide (the pair
  // was tested at these poses in the window the later one came to rest).
  // Only the moving bodies are visited; a truncation wakes a resting one.
  std::vector<int> changed, resting;
  for (int b : moving_) {
    const size_t i = static_cast<size_t>(b);
    if (again && window_stamp_[i] == window_serial_ && box_version_[i] == version_[i]) continue;
    // A lone body (its loose box near nothing it is tested with) cannot
    // collide in this window.
    if (loose && !near_static_[i] && near_[i].empty()) {
      ++lone;
      if (box_version_[i] >= 0) continue;
    }
    Eigen::Vector3d lo, hi;
    PositionRange(b, e0, e1, lo, hi);
    const Eigen::Vector3d r = Eigen::Vector3d::Constant(bodies_[i].radius + separation_);
    box_lo_[i] = lo - r;
    box_hi_[i] = hi + r;
    box_version_[i] = version_[i];
    ++counters_.boxes;
    changed.push_back(b);
    if (window_stamp_[i] != window_serial_) {
      window_stamp_[i] = window_serial_;
      window_moving_.push_back(b);
    }
    if (const auto span = HeldSpan(b, e0, e1)) {
      rest_from_[i] = span->first;
      rest_until_[i] = span->second;
      resting.push_back(b);
    }
  }
  if (loose && !again) {
    if (moving_.size() >= kLooseCrowd && lone * 8 < moving_.size()) {
      loose_resume_ = counters_.windows + loose_backoff_;
      loose_backoff_ = std::min(2 * loose_backoff_, kLooseBackoffMax);
      std::fill(loose_version_.begin(), loose_version_.end(), -1);  // set again on resuming
    } else {
      loose_backoff_ = kLooseBackoff;
    }
  }
  // The changed bodies' pairs: among themselves, with the statics and with
  // the resting bodies (the broad phase), and with the unchanged moving
  // bodies (their boxes, one by one).  A body that has come to rest joins
  // the resting boxes after its pairs are found.
  broad_.Clear();  // the static and resting bodies' boxes stay
  for (int b : changed) broad_.Add(b, box_lo_[b], box_hi_[b]);
  std::vector<std::pair<int, int>> found = broad_.Pairs();
  for (int b : resting) Rest(b);
  if (again) {
    std::vector<char> is_changed(n, 0);
    for (int b : changed) is_changed[static_cast<size_t>(b)] = 1;
    std::erase_if(window_pairs_,
                  [&](const auto& p) { return is_changed[p.first] || is_changed[p.second]; });
    for (int c : changed)
      for (int o : window_moving_) {
        if (is_changed[static_cast<size_t>(o)]) continue;
        if (collide::BoxesOverlap(box_lo_[c], box_hi_[c], box_lo_[o], box_hi_[o]))
          found.emplace_back(std::min(c, o), std::max(c, o));
      }
  } else {
    window_pairs_.clear();
  }
  counters_.broad_phase_pairs += static_cast<long>(found.size());
  window_pairs_.insert(window_pairs_.end(), found.begin(), found.end());
  std::sort(window_pairs_.begin(), window_pairs_.end());
  window_pairs_.erase(std::unique(window_pairs_.begin(), window_pairs_.end()), window_pairs_.end());
  // (Incremental runs: events held aside are reached one by one, in time
  // order, as found ones; ReachCarried.)
  std::optional<Impact> best;
  for (;;) {
    // A body that is searched against a recomputed one must have the motion
    // the run from scratch has at this point (ExposedFrom).
    if (!held_aside_.empty()) {
      std::vector<int> searched;
      for (auto [a, b] : window_pairs_)
        if (Tested(a, b) && !(AsCarried(a, e1) && AsCarried(b, e1))) {
          searched.push_back(a);
          searched.push_back(b);
        }
      if (CutExposed(std::move(searched), e1)) return false;
    }
    // Each body's latest event in this window, from e0: a pair is searched
    // from the later of its bodies'.  Only impacts inside the window count:
    // after a rollback, later impacts of other pairs may still be on record.
    // And each body's last event before the window's end, back to the longest
    // hop before the window (its index; HeldUntil).  One pass over those
    // events, not one per pair: a pile's window holds hundreds of pairs and,
    // between its islands' events, dozens of events of up to a hundred bodies
    // each.  (Entries are stamped with the pass, so that a pass costs the
    // events it reads, not the bodies: a thousand bodies at rest have no
    // events.)  Events at or after the window's end are passed over: a hold
    // comes from the latest event before it, as when the window was first
    // checked.  An edit elsewhere carries a stack's whole train of events over
    // into the new run (and a rollback may leave later ones on record): its
    // holds were once read from events later in the run, a pair the scratch
    // run held was searched, and the edited run struck the stack where the
    // scratch run did not.
    const double held_from = e0 - longest_hop_;
    ++recent_pass_;
    const size_t before_end =
        static_cast<size_t>(std::lower_bound(impacts_.begin(), impacts_.end(), e1,
                                             [](const Impact& x, double t) { return x.t < t; }) -
                            impacts_.begin());
    for (size_t i = before_end; i-- > 0 && impacts_[i].t >= held_from;) {
      const Impact& x = impacts_[i];
      const int listed = static_cast<int>(x.bodies.size());
      // Its place in the event's list of bodies (`listed`: not in it).
      auto note = [&](int body, int place) {
        if (body < 0 || static_cast<size_t>(body) >= n) return;
        RecentEvents& r = recent_[static_cast<size_t>(body)];
        if (r.pass != recent_pass_) {
          r = RecentEvents{recent_pass_, e0, static_cast<long>(i), place};
        }
        if (x.t >= e0 && x.t < e1) r.window = std::max(r.window, x.t);
      };
      for (int k = 0; k < listed; ++k) note(x.bodies[static_cast<size_t>(k)], k);
      note(x.a, listed);
      note(x.b, listed);
    }
    // A static body's events do not move it: a pair with one is searched from
    // its moving body's latest event.  (From the static body's latest event,
    // a floor's pair with one cube was searched from wherever another cube's
    // landing on the floor had last fallen in the window — a start that
    // depends on the order the window's events were found in, so an edited
    // run, which carries them over all at once, searched it from another
    // start and found a landing the run from scratch had found a window late.)
    auto window_event = [&](int body) {
      const RecentEvents& r = recent_[static_cast<size_t>(body)];
      return r.pass == recent_pass_ && sys_.bodies[body].first_var >= 0 ? r.window : e0;
    };
    for (auto [a, b] : window_pairs_) {
      if (!Tested(a, b)) continue;
      // Two bodies carried over: the earlier run searched them with the same
      // motion, and their events over the window are the carried ones.
      if (adopted_ && AsCarried(a, e1) && AsCarried(b, e1)) continue;
      double start = std::max(window_event(a), window_event(b));
      // A contact its island holds is looked at again when the hop lands.
      start = std::max(start, HeldUntil(a, b));
      if (start >= e1) continue;
      // Two bodies that cannot move (static or asleep) cannot collide; a
      // sleeping body is woken only by an event, which restarts the window.
      auto still = [&](int body) { return sys_.bodies[body].first_var < 0 || Asleep(body, start); };
      if (still(a) && still(b)) continue;
      // A pair whose bodies have not changed since it was last searched over
      // the same interval gives the same answer (an event elsewhere in the
      // window restarts the check of every pair).
      PairMemo& memo = memo_[static_cast<uint64_t>(a) << 32 | static_cast<uint32_t>(b)];
      std::optional<Impact> impact;
      if (memo.valid && memo.start == start && memo.end == e1 && memo.version_a == version_[a] &&
          memo.version_b == version_[b]) {
        impact = memo.result;
      } else {
        impact = FirstImpact(a, b, start, e1);
        memo = PairMemo{true, start, e1, version_[a], version_[b], impact};
      }
      // Windows are half-open, [e0, e1): an impact exactly at e1 belongs to
      // the next window, which finds it at its start.  Answered here, its jumps
      // would not show yet — the bodies' components end at e1 and apply them
      // only when they next step — so this window would find it again, and
      // again.  At the run's very end (e1 = t1) it changes nothing the run
      // computes (velocities after t1 are never used) and is not answered.
      if (impact && impact->t < e1 && (!best || impact->t < best->t)) best = impact;
    }
    // A carried event before every impact found (or tied with it, in a pair
    // before its pair) is reached first.
    if (!carried_.empty() && carried_.back().t < e1 &&
        (!best || !ImpactOrder(*best, carried_.back()))) {
      ReachCarried();
      best.reset();
      continue;
    }
    break;
  }
  if (!best) return true;
  // So must every body the response's island may take in.
  if (!held_aside_.empty() && CutExposed(IslandReach(best->a, best->b, e0, e1), e1)) return false;
  // Impacts that keep coming at one instant (a body jammed between others,
  // or positions too loose for the contacts to separate): past kJamEvents they are
  // made perfectly inelastic, past 1000 the run stops with a report.
  same_instant_ = best->t == last_impact_time_ ? same_instant_ + 1 : 0;
  last_impact_time_ = best->t;
  if (same_instant_ > 1000) {
    sim_.Fail("collisions between " + sys_.bodies[best->a].name + " and " +
              sys_.bodies[best->b].name + " do not resolve at t=" + std::to_string(best->t) +
              " (over 1000 impacts at that instant); a tighter tolerance usually helps");
    epoch_ = kEpochs;
    return false;
  }
  Respond(*best);
  return false;
}

double CollisionMonitor::AccelBound(int body, double t0, double t1,
                                    const Eigen::Vector3d& ref) const {
  const physics::BodyModel& m = sys_.bodies[body];
  if (m.first_var < 0) return ref.norm();
  double sum2 = 0;
  for (int axis = 0; axis < 3; ++axis) {
    double amax = 0;
    ForEachSegment(m.first_var + physics::kX + axis, t0, t1,
                   [&](const Cubic& p, double s0, double s1, double h) {
                     amax = std::max(amax, SecondBound(p, s0, s1, h, ref[axis]));
                   });
    sum2 += amax * amax;
  }
  return std::sqrt(sum2);
}

Eigen::Vector3d CollisionMonitor::AccelAt(int body, double t, double t1) const {
  const physics::BodyModel& m = sys_.bodies[body];
  Eigen::Vector3d acc = Eigen::Vector3d::Zero();
  if (m.first_var < 0) return acc;
  for (int axis = 0; axis < 3; ++axis) {
    bool first = true;
    ForEachSegment(m.first_var + physics::kX + axis, t, t1,
                   [&](const Cubic& p, double s0, double, double h) {
                     if (first) acc[axis] = p.Second(s0) / (h * h);
                     first = false;
                   });
  }
  return acc;
}

double CollisionMonitor::HeldUntil(int a, int b) const {
  // The latest event of either moving body (the later in order of their
  // last events before the window's end, back to the longest hop; CheckEpoch).
  auto last_of = [&](int body) {
    const RecentEvents& r = recent_[static_cast<size_t>(body)];
    return r.pass == recent_pass_ ? r.last : -1L;
  };
  auto last = [&](int body) { return sys_.bodies[body].first_var >= 0 ? last_of(body) : -1L; };
  const long i = std::max(last(a), last(b));
  if (i < 0) return -kInf;
  const Impact& x = impacts_[static_cast<size_t>(i)];
  // Only a resting one holds.
  if (!x.resting || x.held.empty()) return -kInf;
  // Nor one of several events of either body at one instant: their order in
  // the record (by pair) need not be the order they were answered in, and a
  // pair struck after its island's solve at the same instant (answered on
  // its own, the island's other contacts left out) has moved the body the
  // hold assumed still.  A cube pushed that way from its neighbour towards
  // the floor fell 3 mm into it while the island's hold of its floor contact
  // stood.
  auto moving = [&](int body) { return sys_.bodies[body].first_var >= 0; };
  auto also = [&](size_t j) {
    const Impact& y = impacts_[j];
    return (moving(a) && Involves(y, a)) || (moving(b) && Involves(y, b));
  };
  size_t first = static_cast<size_t>(i);
  while (first > 0 && impacts_[first - 1].t == x.t) --first;
  for (size_t j = first; j < impacts_.size() && impacts_[j].t == x.t; ++j)
    if (j != static_cast<size_t>(i) && also(j)) return -kInf;
  // The pair's places in its list of bodies: a moving body whose last
  // event is an earlier one is not in it; a static one may be in the lists
  // of later events too, and is looked for.
  const int listed = static_cast<int>(x.bodies.size());
  auto place = [&](int body) {
    if (last_of(body) == i) return recent_[static_cast<size_t>(body)].place;
    if (sys_.bodies[body].first_var >= 0) return listed;
    return static_cast<int>(std::find(x.bodies.begin(), x.bodies.end(), body) - x.bodies.begin());
  };
  const std::pair<int, int> key = std::minmax(place(a), place(b));
  const auto at = std::lower_bound(x.held.begin(), x.held.end(), key);
  return at != x.held.end() && *at == key ? x.held_until[at - x.held.begin()] : -kInf;
}

const CollisionMonitor::SearchSpan& CollisionMonitor::SpanOf(int body, double t0, double t1) {
  SearchSpan& s = spans_[static_cast<size_t>(body)];
  const long version = version_[static_cast<size_t>(body)];
  if (s.valid && s.t0 == t0 && s.t1 == t1 && s.version == version) return s;
  s.valid = true;
  s.t0 = t0;
  s.t1 = t1;
  s.version = version;
  s.motion = MotionOf(body, t0, t1);
  s.accel = AccelAt(body, t0, t1);
  s.accel_bound = AccelBound(body, t0, t1, s.accel);
  const physics::BodyModel& m = sys_.bodies[body];
  s.velocity.setZero();
  if (m.first_var >= 0)
    for (int k = 0; k < 3; ++k) s.velocity[k] = sim_.Rate(m.first_var + physics::kX + k, t0);
  s.pose = PoseAt(body, t0);
  return s;
}

std::optional<Impact> CollisionMonitor::FirstImpact(int a, int b, double start, double end) {
  const SearchSpan& sa = SpanOf(a, start, end);
  const SearchSpan& sb = SpanOf(b, start, end);
  collide::Motion ma = sa.motion, mb = sb.motion;
  // Distance changes at most as fast as the relative velocity: bound it by
  // its value at the start plus both bodies' largest accelerations over the
  // window (two balls moving together close at 0, not at |v_a| + |v_b|).
  {
    // |Δa(t)| ≤ |Δa(start)| + both bodies' deviations from their start
    // accelerations: two bodies falling together close at nothing.
    const double dv =
        ((sb.accel - sa.accel).norm() + sa.accel_bound + sb.accel_bound) * (end - start);
    const double relative = (sa.velocity - sb.velocity).norm() + dv;
    const double sum = ma.max_linear_speed + mb.max_linear_speed;
    if (relative < sum) {
      ma.max_linear_speed = relative;
      mb.max_linear_speed = 0.0;
    }
    ma.dv = dv;
    mb.dv = 0.0;
  }
  // Every distance evaluation in the search places both bodies once.
  ma.pose = [this, a, end](double t) {
    ++counters_.distance_queries;
    return SearchPose(a, t, end);
  };
  std::optional<Impact> first;
  const double graze = kGraze * std::min(bodies_[a].radius, bodies_[b].radius);
  const collide::Pose pa0 = sa.pose, pb0 = sb.pose;
  auto take = [&](double t, const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
    if (first && first->t <= t) return;
    Impact imp;
    imp.t = t;
    imp.a = a;
    imp.b = b;
    imp.point = point;
    imp.normal = normal;
    first = imp;
  };
  for (const auto& piece_a : bodies_[a].pieces) {
    for (const auto& piece_b : bodies_[b].pieces) {
      collide::DistanceCache cache;
      const auto d0 = collide::Distance(piece_a, pa0, piece_b, pb0, &cache);
      ++counters_.distance_queries;
      double from = start;
      double threshold = separation_;
      if (d0.overlapping || d0.distance <= separation_) {
        // In contact at the start.  Overlapping by more than the separation,
        // or approaching at any contact point: respond now (never ignore an
        // overlap).  Otherwise look on from the moment they are clear.
        const auto points = PieceContacts(piece_a, pa0, piece_b, pb0, d0, separation_);
        double min_gap = kInf;
        // Only touching points (within the separation) must not approach;
        // a point of the patch further away may close on its gap (the
        // resting solve lets it, speculatively), and the search below finds
        // it landing.  They may creep (kCreep): a resting solve meets its
        // targets to its tolerance, and a pair it left approaching at 1e-10
        // of a metre per second was found again at the same instant, its
        // island of 51 cubes solved again each time, 200 times over while
        // the remainder shrank by 3% a solve.  Creeping closes less than a
        // thousandth of the landing gap in a window; a touching pair that
        // overlaps deeper than the gap is answered whatever its speed.
        const double creep = kCreep * separation_ / epoch_length_;
        std::vector<collide::ContactPoint> touching;
        for (const auto& p : points) {
          min_gap = std::min(min_gap, p.gap);
          if (p.gap <= separation_) touching.push_back(p);
        }
        if (min_gap < -separation_ || Approach(a, b, start, touching) > creep) {
          take(start, points.front().point, points.front().normal);
          continue;
        }
        double step =
            kSearchStartTime * std::max(1.0, std::abs(start)) + kSearchStartWindow * (end - start);
        bool clear = false;
        for (from = start + step; from < end; from = std::min(end, from + step), step *= 2) {
          const auto d =
              collide::Distance(piece_a, PoseAt(a, from), piece_b, PoseAt(b, from), &cache);
          ++counters_.distance_queries;
          if (!d.overlapping && d.distance > separation_) {
            clear = true;
            break;
          }
        }
        if (!clear) {
          // Sliding in contact for the whole window: an approach shows as
          // the gap closing to half of what it is now.
          if (d0.overlapping || !(d0.distance > 0)) continue;
          from = start;
          threshold = 0.5 * d0.distance;
        }
      }
      for (int round = 0; round < 8 && from < end; ++round) {
        ++counters_.narrow_phase_queries;
        auto hit =
            collide::TimeOfImpact(piece_a, ma, piece_b, mb, from, end, threshold, &cache, graze);
        if (!hit) break;
        if (first && hit->time >= first->t) break;
        const auto& c = hit->contact;
        const collide::Pose xa = PoseAt(a, hit->time), xb = PoseAt(b, hit->time);
        const auto points = PieceContacts(piece_a, xa, piece_b, xb, c, threshold);
        // An overlap within the separation that does not approach is
        // touching, not an impact: distance queries disagree on a touch of a
        // few ulps (with and without a warm cache), and answering it would
        // change nothing, so the same window would find it again.
        double hit_gap = kInf;
        for (const auto& p : points) hit_gap = std::min(hit_gap, p.gap);
        const bool deep = c.overlapping && (points.empty() || hit_gap < -separation_);
        if (deep || Approach(a, b, hit->time, points) > 0) {
          // The impulse of an impact acts at the centre of the contact patch.
          const Eigen::Vector3d point =
              c.overlapping && !points.empty()
                  ? points.front().point
                  : ContactPoint(piece_a, xa, piece_b, xb, c,
                                 kPatchTolerance * std::max(bodies_[a].radius, bodies_[b].radius));
          take(hit->time, point,
               c.overlapping && !points.empty() ? points.front().normal : c.normal);
          break;
        }
        // Grazing or separating: look further, below the current gap.
        from = hit->time;
        threshold = 0.5 * std::max(c.distance, 1e-300);
        if (c.distance <= 0) break;
      }
    }
  }
  return first;
}

// ---- contact geometry and state --------------------------------------------------

std::vector<collide::ContactPoint> CollisionMonitor::PieceContacts(
    const collide::Piece& pa, const collide::Pose& xa, const collide::Piece& pb,
    const collide::Pose& xb, const collide::DistanceResult& d, double margin) const {
  if (!d.overlapping) return collide::Manifold(pa, xa, pb, xb, d, d.distance, margin);
  collide::DistanceResult c = d;
  double signed_distance = 0.0;
  if (const auto pen = collide::PenetrationMpr(pa, xa, pb, xb)) {
    c.normal = pen->normal;
    c.point_a = pen->point + 0.5 * pen->depth * pen->normal;
    c.point_b = pen->point - 0.5 * pen->depth * pen->normal;
    signed_distance = -pen->depth;
  }
  return collide::Manifold(pa, xa, pb, xb, c, signed_distance, margin);
}

CollisionMonitor::PairContact CollisionMonitor::ContactsAt(int a, int b, double t,
                                                           double margin) const {
  PairContact out;
  out.a = a;
  out.b = b;
  out.min_gap = kInf;
  const collide::Pose xa = PoseAt(a, t), xb = PoseAt(b, t);
  for (const auto& pa : bodies_[a].pieces) {
    for (const auto& pb : bodies_[b].pieces) {
      const auto d = collide::Distance(pa, xa, pb, xb);
      if (!d.overlapping && d.distance > margin) continue;
      for (const auto& p : PieceContacts(pa, xa, pb, xb, d, margin)) {
        out.points.push_back(p);
        out.min_gap = std::min(out.min_gap, p.gap);
      }
    }
  }
  return out;
}

Eigen::Vector3d CollisionMonitor::PointVelocity(int body, double t, const Eigen::Vector3d& point,
                                                Side side) const {
  const physics::BodyModel& m = sys_.bodies[body];
  if (m.first_var < 0) return Eigen::Vector3d::Zero();
  const collide::Pose pose = PoseAt(body, t);
  double x[6];
  ReadVelocities(body, t, side, x);
  const Eigen::Vector3d v(x[0], x[1], x[2]);
  const Eigen::Vector3d w = pose.R * Eigen::Vector3d(x[3], x[4], x[5]);
  return v + w.cross(point - pose.p);
}

// Approach speed beyond the round-off of the speeds involved (after an
// inelastic impact the normal speed is 0 up to a few ulps); > 0 approaches.
double CollisionMonitor::Approach(int a, int b, double t,
                                  const std::vector<collide::ContactPoint>& points) const {
  double most = -kInf;
  for (const auto& p : points) {
    const Eigen::Vector3d va = PointVelocity(a, t, p.point), vb = PointVelocity(b, t, p.point);
    most = std::max(most,
                    -(vb - va).dot(p.normal) - kApproachRoundOff * (1.0 + va.norm() + vb.norm()));
  }
  return most;
}

Eigen::Vector3d CollisionMonitor::Acceleration(int body, double t) const {
  const physics::BodyModel& m = sys_.bodies[body];
  Eigen::Vector3d acc = Eigen::Vector3d::Zero();
  if (m.first_var < 0) return acc;
  for (int k = 0; k < 3; ++k) acc[k] = sim_.Rate(m.first_var + physics::kDx + k, t, Side::kLeft);
  return acc;
}

Eigen::Vector3d CollisionMonitor::FreeAcceleration(int body, double t) {
  const physics::BodyModel& m = sys_.bodies[body];
  if (m.first_var < 0) return Eigen::Vector3d::Zero();
  const int dx = m.first_var + physics::kDx;
  const double before = std::nextafter(t, -kInf);
  bool released = false;
  for (int k = 0; k < 3; ++k) released |= sim_.Held(dx + k, before) && !sim_.Held(dx + k, t);
  if (!released) return Acceleration(body, t);
  auto [it, fresh] = force_tapes_.try_emplace(body);
  ForceTape& f = it->second;
  if (fresh) {
    const expr::NodeId rows[3] = {sys_.variables[dx].rhs, sys_.variables[dx + 1].rhs,
                                  sys_.variables[dx + 2].rhs};
    f.tape = expr::Tape::Compile(sys_.pool, rows);
    f.reads = sys_.pool.Variables(std::span<const expr::NodeId>(rows));
    if (!f.reads.empty()) {
      f.offset = f.reads.front();
      f.x.assign(static_cast<size_t>(f.reads.back() - f.offset + 1), 0.0);
    }
  }
  // The state the body slept in (its held values are those of before).
  for (int v : f.reads) f.x[static_cast<size_t>(v - f.offset)] = sim_.Value(v, t, Side::kLeft);
  Eigen::Vector3d acc;
  f.tape.Evaluate(t, f.x.data(), acc.data(), &sim_.externs(), f.offset);
  return acc;
}

Eigen::Vector3d CollisionMonitor::PointAcceleration(int body, double t,
                                                    const Eigen::Vector3d& point) const {
  const physics::BodyModel& m = sys_.bodies[body];
  if (m.first_var < 0) return Eigen::Vector3d::Zero();
  const collide::Pose pose = PoseAt(body, t);
  Eigen::Vector3d w_body, dw_body;
  for (int k = 0; k < 3; ++k) {
    w_body[k] = sim_.Value(m.first_var + physics::kW1 + k, t, Side::kLeft);
    dw_body[k] = sim_.Rate(m.first_var + physics::kW1 + k, t, Side::kLeft);
  }
  // d(R ω_b)/dt = R dω_b/dt (the ω × ω term vanishes).
  const Eigen::Vector3d w = pose.R * w_body, alpha = pose.R * dw_body, r = point - pose.p;
  return Acceleration(body, t) + alpha.cross(r) + w.cross(w.cross(r));
}

bool CollisionMonitor::Asleep(int body, double t) const {
  const physics::BodyModel& m = sys_.bodies[body];
  return m.first_var >= 0 && sim_.Held(m.first_var + physics::kQw, t);
}

bool CollisionMonitor::Movable(int body, double t) const {
  return sys_.bodies[body].first_var >= 0 && !Prescribed(body, t) && !Asleep(body, t);
}

collide::BodyState CollisionMonitor::StateAt(int body, double t, bool movable) const {
  const physics::BodyModel& m = sys_.bodies[body];
  const collide::Pose pose = PoseAt(body, t);
  collide::BodyState st;
  st.com = pose.p;
  if (m.first_var >= 0) {
    // Right limits: an earlier event at this instant has already jumped them.
    double x[6];
    ReadVelocities(body, t, Side::kRight, x);
    st.v = {x[0], x[1], x[2]};
    st.w = pose.R * Eigen::Vector3d(x[3], x[4], x[5]);
  }
  if (movable) {
    st.inv_mass = 1.0 / m.mass;
    st.inv_inertia = pose.R * m.inertia.inverse() * pose.R.transpose();
  }
  return st;
}

double CollisionMonitor::ContactMargin(int a, int b) const {
  return std::max(4.0 * separation_,
                  kMarginRelative * std::min(bodies_[a].radius, bodies_[b].radius));
}

// Resting contact is a train of small hops: a contact pressed together by
// an acceleration a leaves at a Δ/2 and lands again Δ later, so the average
// impulse is the force that holds it (and friction, μ times that, the
// kinetic or static friction force).  The hop rises a Δ²/8, kept below
// kHopHeight of the body's size, and Δ is at most kLongestHop (a contact
// pressed by round-off, or not at all, is looked at again ten times a
// second).  The hop is the body's and the acceleration's, not the run's:
// it was once at most one collision window (a 1024th of the run), so that
// the same pile hopped every 4.9 ms when simulated for 5 s and every 27 ms
// when simulated for a minute.
double CollisionMonitor::HopPeriod(double accel, double radius) const {
  if (!(accel > 0)) return kLongestHop;
  return std::min(kLongestHop, std::sqrt(8.0 * kHopHeight * radius / accel));
}

// Within an island, contact is resolved at the hop's scale (HopPeriod): a
// point that lands within the island's hop and within the hop's height of
// touching is answered at the island's event, with its restitution.
double CollisionMonitor::AbsorbGap(int a, int b) const {
  return kHopHeight * std::min(bodies_[a].radius, bodies_[b].radius);
}

bool CollisionMonitor::Involves(const Impact& impact, int body) {
  return impact.a == body || impact.b == body ||
         std::find(impact.bodies.begin(), impact.bodies.end(), body) != impact.bodies.end();
}

// ---- response ----------------------------------------------------------------------

void CollisionMonitor::ApplyEdits(double t) {
  std::vector<Simulation::Edit> edits;
  edits.swap(edits_);
  sim_.ApplyAt(t, edits);
}

void CollisionMonitor::WriteVelocities(int body, double t, const collide::BodyState& state) {
  const physics::BodyModel& m = sys_.bodies[body];
  // A body resting on something was held there; the impact releases it.
  for (int a = 0; a < 3; ++a)
    for (int slot : {physics::kX + a, physics::kDx + a})
      if (sim_.Held(m.first_var + slot, t)) QueueRelease(m.first_var + slot);
  const Eigen::Vector3d w_body = PoseAt(body, t).R.transpose() * state.w;
  for (int a = 0; a < 3; ++a) {
    QueueSet(m.first_var + physics::kDx + a, state.v[a]);
    QueueSet(m.first_var + physics::kW1 + a, w_body[a]);
  }
}

void CollisionMonitor::Wake(int body, double t) {
  if (!Asleep(body, t)) return;
  const physics::BodyModel& m = sys_.bodies[body];
  // Applied at once: whoever asks next whether it sleeps must hear no.  Its
  // values are held, so reading them after the cut is reading them before.
  std::vector<Simulation::Edit> releases;
  for (int s = 0; s < physics::kBodySlots; ++s)
    if (sim_.Held(m.first_var + s, t))
      releases.push_back({Simulation::Edit::Kind::kRelease, m.first_var + s});
  sim_.ApplyAt(t, releases);
  ++counters_.wakes;
  // Whatever sleeps on it wakes too: its support may be about to move.
  const collide::Pose x = PoseAt(body, t);
  for (size_t y = 0; y < bodies_.size(); ++y) {
    const int other = static_cast<int>(y);
    if (other == body || !bodies_[y].collidable || !Asleep(other, t)) continue;
    const double margin = ContactMargin(body, other);
    if ((PoseAt(other, t).p - x.p).norm() > bodies_[body].radius + bodies_[y].radius + margin)
      continue;
    if (!ContactsAt(body, other, t, margin).points.empty()) Wake(other, t);
  }
}

void CollisionMonitor::Sleep(int body, double t, const Eigen::Vector3d& shift) {
  const physics::BodyModel& m = sys_.bodies[body];
  for (int s = 0; s < physics::kBodySlots; ++s)
    if (sim_.Held(m.first_var + s, t)) QueueRelease(m.first_var + s);
  for (int s = 0; s < physics::kBodySlots; ++s) {
    const int var = m.first_var + s;
    const bool rate =
        (s >= physics::kDx && s < physics::kDx + 3) || (s >= physics::kW1 && s < physics::kW1 + 3);
    if (rate) {
      QueueSet(var, 0.0);
      QueueHold(var, 0.0);
    } else {
      const bool position = s >= physics::kX && s < physics::kX + 3;
      QueueHold(var, sim_.Value(var, t) + (position ? shift[s - physics::kX] : 0.0));
    }
  }
  ++counters_.sleeps;
}

// How far a body has moved between two of its places: its centre's
// distance, and its turn (the angle, from the sine and cosine of the
// relative rotation: exact for small turns) times its radius.
namespace {
std::pair<double, double> PlaceDistance(const collide::Pose& a, const collide::Pose& b,
                                        double radius) {
  const Eigen::Matrix3d turn = a.R.transpose() * b.R;
  const Eigen::Vector3d axis(turn(2, 1) - turn(1, 2), turn(0, 2) - turn(2, 0),
                             turn(1, 0) - turn(0, 1));
  const double angle = std::atan2(0.5 * axis.norm(), 0.5 * (turn.trace() - 1.0));
  return {(b.p - a.p).norm(), radius * angle};
}
}  // namespace

bool CollisionMonitor::StillSince(int body, double t, const collide::Pose& now) const {
  const double radius = bodies_[static_cast<size_t>(body)].radius;
  const double height = kHopHeight * radius;  // the hop's (AbsorbGap)
  // The body's own event times, latest first (found_times_, as
  // PreviousResting): how many other bodies had events meanwhile does not
  // matter.  Every event at one instant counts, once.
  const auto& times = found_times_[static_cast<size_t>(body)];
  int count = 1;  // this event
  for (auto next = times.upper_bound(t); next != times.begin();) {
    const double when = *std::prev(next);
    next = times.lower_bound(when);
    auto at = std::upper_bound(impacts_.begin(), impacts_.end(), when,
                               [](double time, const Impact& x) { return time < x.t; });
    for (; at != impacts_.begin() && std::prev(at)->t == when; --at) {
      const Impact& e = *std::prev(at);
      if (!Involves(e, body)) continue;
      if (!e.resting || std::find(e.slow.begin(), e.slow.end(), body) == e.slow.end()) return false;
      const size_t i =
          static_cast<size_t>(std::find(e.bodies.begin(), e.bodies.end(), body) - e.bodies.begin());
      if (i >= e.place.size()) return false;
      const auto [moved, turned] = PlaceDistance(e.place[i], now, radius);
      if (moved > height + separation_ || turned > kSleepDrift * height + separation_) return false;
    }
    if (++count >= kSleepEvents && when <= t - kSleepSpan) return true;
  }
  return false;
}

// The landing speed below which a pair's touch is resting contact, not an
// impact; `hop` (optional) receives the pair's hop period.
double CollisionMonitor::SlowSpeed(int a, int b, double t,
                                   const std::vector<collide::ContactPoint>& points,
                                   double* hop_out) const {
  // Relative acceleration where they touch: a body tipping about an edge
  // presses with its angular acceleration (α × r), which its centre's
  // acceleration does not show.
  Eigen::Vector3d acc_rel = Acceleration(b, t) - Acceleration(a, t);
  for (const auto& p : points) {
    const Eigen::Vector3d at = PointAcceleration(b, t, p.point) - PointAcceleration(a, t, p.point);
    if (at.norm() > acc_rel.norm()) acc_rel = at;
  }
  const double radius = std::min(bodies_[a].radius, bodies_[b].radius);
  const double hop = HopPeriod(acc_rel.norm(), radius);
  if (hop_out != nullptr) *hop_out = hop;
  // Slow: what the hop itself reaches, and never less than a touch whose
  // bounce would rise under 1e-6 of the radius in a hop of either body —
  // two bodies of a stack fall together between hops (no relative
  // acceleration), and their grazes of 1e-11 m/s are not impacts.
  const double own_hop =
      HopPeriod(std::max(Acceleration(a, t).norm(), Acceleration(b, t).norm()), radius);
  return std::max(2.0 * acc_rel.norm() * hop, 1e-6 * radius / own_hop);
}

// A pair's restitution: the product of its bodies', and none in a jam
// (impacts that keep coming at one instant are made perfectly inelastic).
double CollisionMonitor::Restitution(int a, int b) const {
  return same_instant_ > kJamEvents ? 0.0 : sys_.bodies[a].restitution * sys_.bodies[b].restitution;
}

void CollisionMonitor::Respond(const Impact& impact) {
  const double t = impact.t;
  // Every change a response makes (wakes, jumps, holds, sleep, here and in
  // RespondResting) is at t and changes nothing before it (AfterTruncate).
  responding_ = true;
  respond_time_ = t;
  struct Done {
    bool& flag;
    ~Done() { flag = false; }
  } done{responding_};
  const int ids[2] = {impact.a, impact.b};
  const double margin = ContactMargin(impact.a, impact.b);
  const PairContact pc = ContactsAt(impact.a, impact.b, t, margin);
  double hop = 0.0;
  const double slow_speed = SlowSpeed(impact.a, impact.b, t, pc.points, &hop);
  const double approach = pc.points.empty() ? kInf : Approach(impact.a, impact.b, t, pc.points);
  // A lone ball on something immovable keeps the seed's bouncing and comes to
  // rest by the hold below; everything else that arrives slowly rests.
  auto balls_only = [&](int b) {
    for (const auto& p : bodies_[b].pieces)
      if (!p.is_sphere) return false;
    return true;
  };
  const bool ball_on_immovable =
      pc.points.size() == 1 && ((balls_only(impact.a) && !Movable(impact.b, t)) ||
                                (balls_only(impact.b) && !Movable(impact.a, t)));
  // Impacts that keep coming at one instant (a jam) are solved together too,
  // whatever their speed: one pair at a time only passes the push around.
  // So is a pair struck again at the instant it already had its impact:
  // its restitution was applied then, and what approaches now is pushed by
  // its neighbours (a stack, where single-pair impulses ping-ponged up and
  // down the column, thousands of events at a few instants).
  auto same_t = std::equal_range(impacts_.begin(), impacts_.end(), impact,
                                 [](const Impact& x, const Impact& y) { return x.t < y.t; });
  const bool again = std::any_of(same_t.first, same_t.second, [&](const Impact& x) {
    return x.a == impact.a && x.b == impact.b;
  });
  if ((approach <= slow_speed || same_instant_ > kJamEvents || again) && !ball_on_immovable) {
    RespondResting(impact);
    return;
  }
  for (int b : ids)
    if (Asleep(b, t)) Wake(b, t);
  collide::BodyState state[2];
  bool movable[2];
  for (int s = 0; s < 2; ++s) {
    movable[s] = Movable(ids[s], t);
    state[s] = StateAt(ids[s], t, movable[s]);
  }
  const double e = Restitution(impact.a, impact.b);
  const double mu = std::sqrt(sys_.bodies[impact.a].friction * sys_.bodies[impact.b].friction);
  Impact recorded = impact;
  recorded.bodies = {impact.a, impact.b};
  recorded.impulse = collide::ApplyImpulse(state[0], state[1], impact.point, impact.normal, e, mu);
  // Points of the patch other than its centre may still approach (an edge
  // landing with a spin): they are brought to rest along the normal.
  Eigen::Vector3d shift[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  if (!pc.points.empty()) {
    std::vector<collide::BodyState> bodies = {state[0], state[1]};
    std::vector<collide::SolverContact> contacts;
    for (const auto& p : pc.points) {
      collide::SolverContact c;
      c.a = 0;
      c.b = 1;
      c.point = p.point;
      c.normal = p.normal;
      c.friction = mu;
      c.target = std::max(0.0, (separation_ - std::max(p.gap, 0.0)) / hop);
      contacts.push_back(c);
    }
    collide::SolveContacts(bodies, contacts, kSweeps, 1e-12 * (1.0 + recorded.impulse));
    state[0] = bodies[0];
    state[1] = bodies[1];
    if (pc.min_gap < -separation_) {
      // Overlapping anyway: pushed apart along the penetration normal.
      const Eigen::Vector3d n = pc.points.front().normal;
      const double wa = state[0].inv_mass, wb = state[1].inv_mass;
      if (wa + wb > 0) {
        const double depth = separation_ - pc.min_gap;
        shift[0] = -depth * wa / (wa + wb) * n;
        shift[1] = depth * wb / (wa + wb) * n;
      }
      ++counters_.overlaps_resolved;
    }
  }
  ++counters_.impacts;
  NoteFound(recorded, true);
  auto pos = std::upper_bound(impacts_.begin(), impacts_.end(), recorded, ImpactOrder);
  impacts_.insert(pos, recorded);
  for (int s = 0; s < 2; ++s) {
    if (!movable[s]) continue;
    const physics::BodyModel& m = sys_.bodies[ids[s]];
    WriteVelocities(ids[s], t, state[s]);
    if (shift[s].squaredNorm() > 0)
      for (int a = 0; a < 3; ++a)
        QueueSet(m.first_var + physics::kX + a,
                 sim_.Value(m.first_var + physics::kX + a, t, Side::kRight) + shift[s][a]);
    if (!ball_on_immovable) continue;
    const std::vector<int> held =
        RestingAxes(ids[s], s == 0 ? impact.normal : -impact.normal, movable[1 - s], t, state[s].v);
    for (int a = 0; a < 3; ++a)
      if (std::find(held.begin(), held.end(), a) != held.end())
        QueueSet(m.first_var + physics::kDx + a, state[s].v[a]);
    for (int a : held) {
      QueueHold(m.first_var + physics::kX + a, sim_.Value(m.first_var + physics::kX + a, t));
      QueueHold(m.first_var + physics::kDx + a, 0.0);
    }
  }
  ApplyEdits(t);
}

// Slow contacts are solved together: every body in contact with the pair,
// and transitively with those (through movable bodies only — static,
// sleeping and prescribed bodies end the island), gets one simultaneous
// solve of all its contact points (SolveContacts) with the hop target of
// HopPeriod.  Bodies found at rest kSleepEvents times in a row go to sleep
// together: all their variables are held, and they cost nothing until an
// impact wakes them.
void CollisionMonitor::RespondResting(const Impact& impact) {
  const double t = impact.t;
  std::vector<int> members;
  std::map<int, int> index;  // body → row in `states`
  std::vector<collide::BodyState> states;
  auto add = [&](int body) {
    if (index.count(body)) return;
    const bool movable = Movable(body, t);
    index[body] = static_cast<int>(states.size());
    states.push_back(StateAt(body, t, movable));
    if (movable) members.push_back(body);
  };
  // Sleeping bodies that the event touches wake (the event's own pair, and
  // any the island reaches within the landing gap): a domino that leans on a
  // sleeping one pushes it over instead of meeting a wall.
  for (int body : {impact.a, impact.b})
    if (Asleep(body, t)) Wake(body, t);
  add(impact.a);
  add(impact.b);
  std::vector<PairContact> pairs;
  std::set<std::pair<int, int>> seen;
  // Every body's centre at t, read once: the island's search below looks at
  // each body once per member.  (Waking a body releases its holds at t and
  // moves nothing there.)
  std::vector<Eigen::Vector3d> centre(bodies_.size());
  std::vector<char> centre_known(bodies_.size(), 0);
  auto centre_of = [&](int body) -> const Eigen::Vector3d& {
    if (!centre_known[static_cast<size_t>(body)]) {
      centre[static_cast<size_t>(body)] = PoseAt(body, t).p;
      centre_known[static_cast<size_t>(body)] = 1;
    }
    return centre[static_cast<size_t>(body)];
  };
  for (size_t q = 0; q < members.size(); ++q) {
    const int x = members[q];
    const Eigen::Vector3d px = centre_of(x);
    for (size_t y = 0; y < bodies_.size(); ++y) {
      const int other = static_cast<int>(y);
      if (other == x || !bodies_[y].collidable || !Tested(x, other)) continue;
      const auto key = std::minmax(x, other);
      if (seen.count(key)) continue;
      const double margin = ContactMargin(x, other);
      if ((centre_of(other) - px).norm() > bodies_[x].radius + bodies_[y].radius + margin) continue;
      PairContact pc = ContactsAt(key.first, key.second, t, margin);
      if (pc.points.empty()) continue;
      seen.insert(key);
      // A sleeping body the island approaches within the margin wakes too:
      // held as immovable, it would stop the approaching body like a wall (a
      // domino toppling onto a sleeping one lost its speed over a few hops
      // and struck it at 1e-5 of it).
      if (!index.count(other) && Asleep(other, t) &&
          (pc.min_gap <= separation_ || Approach(key.first, key.second, t, pc.points) > 0))
        Wake(other, t);
      add(other);
      pairs.push_back(std::move(pc));
    }
  }
  // Overlaps are pushed apart first (positions): Gauss–Seidel sweeps over
  // the overlapping pairs on their gaps as the shifts so far change them, so
  // that a stack pressed into the floor rises as a whole (one pass, pair by
  // pair, would push each body back into the one below, at every event).
  std::map<int, Eigen::Vector3d> shift;
  auto shift_of = [&](int body) -> Eigen::Vector3d& {
    return shift.try_emplace(body, Eigen::Vector3d::Zero()).first->second;
  };
  std::set<std::pair<int, int>> pushed_pairs;
  for (int sweep = 0; sweep < kSweeps; ++sweep) {
    bool moved = false;
    for (const PairContact& pc : pairs) {
      if (pc.points.empty()) continue;
      const double wa = states[static_cast<size_t>(index[pc.a])].inv_mass;
      const double wb = states[static_cast<size_t>(index[pc.b])].inv_mass;
      if (!(wa + wb > 0)) continue;
      const Eigen::Vector3d n = pc.points.front().normal;
      const double gap = pc.min_gap + n.dot(shift_of(pc.b) - shift_of(pc.a));
      if (!(gap < -separation_)) continue;
      const double depth = separation_ - gap;
      if (wa > 0) shift_of(pc.a) -= depth * wa / (wa + wb) * n;
      if (wb > 0) shift_of(pc.b) += depth * wb / (wa + wb) * n;
      pushed_pairs.insert({pc.a, pc.b});
      moved = true;
    }
    if (!moved) break;
  }
  counters_.overlaps_resolved += static_cast<long>(pushed_pairs.size());
  // A body this event woke reads its forces' acceleration, not the zero
  // rate of its held rows: read as zero, a cube woken by a neighbour's push
  // was solved as weightless, given nothing to rise on, and its contact with
  // the floor held for a hop while it fell 6 mm into it.
  std::map<int, Eigen::Vector3d> acc;
  for (const auto& [body, row] : index)
    acc[body] = states[static_cast<size_t>(row)].inv_mass > 0 || Prescribed(body, t)
                    ? FreeAcceleration(body, t)
                    : Eigen::Vector3d::Zero();
  double press = 0.0, radius = kInf;
  for (const PairContact& pc : pairs) {
    radius = std::min({radius, bodies_[pc.a].radius, bodies_[pc.b].radius});
    for (const auto& p : pc.points) press = std::max(press, -p.normal.dot(acc[pc.b] - acc[pc.a]));
  }
  const double hop = HopPeriod(press, std::isfinite(radius) ? radius : 1.0);
  longest_hop_ = std::max(longest_hop_, hop);
  std::vector<collide::SolverContact> contacts;
  std::vector<size_t> contact_pair;       // per contact: its pair's index
  std::map<int, const Impact*> previous;  // per body: PreviousResting
  auto previous_of = [&](int body) {
    auto [it, fresh] = previous.try_emplace(body, nullptr);
    if (fresh) it->second = PreviousResting(body, t);
    return it->second;
  };
  double scale = 0.0;
  std::vector<char> skipped(pairs.size(), 0);            // pairs with an impact to come
  std::vector<double> landing_slow(pairs.size(), -1.0);  // SlowSpeed of the pair, once
  for (size_t k = 0; k < pairs.size(); ++k) {
    const PairContact& pc = pairs[k];
    const bool pushed = pc.min_gap < -separation_;
    const double mu = std::sqrt(sys_.bodies[pc.a].friction * sys_.bodies[pc.b].friction);
    for (const auto& p : pc.points) {
      const double pressed = std::max(0.0, -p.normal.dot(acc[pc.b] - acc[pc.a]));
      // A point not yet touching that arrives faster than a hop lands, and
      // lands within this hop, is an impact.  Within the hop's height of
      // touching it is answered here, with its restitution: at the island's
      // scale (AbsorbGap) it is touching, and answered at its own landing it
      // would solve the whole island again for each such point (a toppling
      // column of seven cubes was solved every 20 µs).  Further away, the
      // search finds it, with its restitution; held to its gap here, it
      // would be caught inelastically over a few hops.  A point that does
      // not land within the hop is held to its gap (a constraint that does
      // not act) and its pair with it, until the island's next event.
      double bounce = -kInf;
      const double closing =
          pushed
              ? 0.0
              : -(PointVelocity(pc.b, t, p.point) - PointVelocity(pc.a, t, p.point)).dot(p.normal);
      if (!pushed && p.gap <= separation_ && closing > 0) {
        // A touching point that closes faster than a landing rests is an
        // impact too, answered in this solve with its restitution: the
        // middle ball of three struck at one instant passes the second
        // strike on as the pairwise impacts would (held to rest, that pair
        // lost half the energy).  Every approach is answered at once, so
        // the instant has no further events.
        if (landing_slow[k] < 0) landing_slow[k] = SlowSpeed(pc.a, pc.b, t, pc.points);
        if (closing > landing_slow[k]) bounce = Restitution(pc.a, pc.b) * closing;
      } else if (!pushed) {
        const double to_close = p.gap - separation_;
        const bool lands = to_close < closing * hop + 0.5 * pressed * hop * hop;
        const double slow = 2.0 * pressed * hop + 1e-6 * radius / hop;
        if (lands && closing > slow) {
          if (to_close > AbsorbGap(pc.a, pc.b)) {
            skipped[k] = 1;
            continue;
          }
          const double e = Restitution(pc.a, pc.b);
          // Its restitution as an impact would have it, when it would land
          // faster than resting contact does (SlowSpeed, as Respond judges a
          // landing); slower, it is caught, as Respond would rest it.
          const double landing = std::sqrt(closing * closing + 2.0 * pressed * to_close);
          if (landing_slow[k] < 0) landing_slow[k] = SlowSpeed(pc.a, pc.b, t, pc.points);
          if (landing > landing_slow[k]) bounce = e * landing;
          ++counters_.impacts_absorbed;
        }
      }
      collide::SolverContact c;
      c.a = index[pc.a];
      c.b = index[pc.b];
      c.point = p.point;
      c.normal = p.normal;
      c.friction = mu;
      const double gap = pushed ? separation_ : p.gap;
      const double rest = 0.5 * pressed * hop + (separation_ - gap) / hop;
      c.target = std::max(bounce, rest);
      // Along a slope the hop is centred too: a point pressed with a
      // tangential relative acceleration a_t is brought to −a_t Δ/2, so that
      // over the hop it ends at +a_t Δ/2 and comes back to where it was.
      // Otherwise a box held by static friction on an incline slid a_t Δ²/2
      // down it at every hop (2 cm before it slept, with hops of 27 ms), and
      // a sliding one ran μ g_n Δ/2 too fast all the way (its friction
      // lagging half a hop: 2% of the distance).  Slopes below 1e-6 rad
      // (the round-off of the accelerations and of a manifold's normal) are
      // level: their creep, g Δ²/2 · 1e-6 < 4e-6 of the hop's height, is
      // far below the landing gap.
      if (pressed > 0.0 && rest >= bounce) {
        const Eigen::Vector3d along = acc[pc.b] - acc[pc.a];
        const Eigen::Vector3d slope = along - p.normal.dot(along) * p.normal;
        if (slope.norm() > 1e-6 * std::max(acc[pc.a].norm(), acc[pc.b].norm()))
          c.target_tangent = -0.5 * hop * slope;
      }
      WarmStart(c, pc.a, pc.b, previous_of(Movable(pc.a, t) ? pc.a : pc.b), hop);
      contacts.push_back(c);
      contact_pair.push_back(k);
    }
  }
  for (int body : members)
    scale = std::max(
        scale, sys_.bodies[body].mass *
                   (acc[body].norm() * hop + states[static_cast<size_t>(index[body])].v.norm()));
  // Moving no faster than the island's hop: at this event's start, an
  // island that is settled gets the full sweeps (SolveContacts); their
  // residual is the spin noise its bodies keep from solve to solve.
  auto slow_now = [&](int body, const collide::BodyState& st) {
    const double r = bodies_[body].radius;
    const double limit = acc[body].norm() * hop + 1e-6 * r / hop;
    return st.v.norm() <= limit && st.w.norm() * r <= limit;
  };
  const bool settled = std::all_of(members.begin(), members.end(), [&](int body) {
    return slow_now(body, states[static_cast<size_t>(index[body])]);
  });
  collide::SolveContacts(states, contacts, kSweeps, 1e-9 * scale + 1e-300, settled);
  // A pair is held (not searched until its hop lands) only where the hop
  // alone can bring its points together again.  A point leaving at its
  // target lands at the hop's end, one slower by δ lands δ·hop deeper: the
  // solve must have met every target to within the hop's height over the
  // hop, or the pair is not held.  A translation cannot bring two convex
  // bodies that separate at their contact points together, a turn of one
  // against the other can: a tumbling cube's next corner swings in.  Only
  // the relative turn counts: relative to a, b's points move at the contact
  // point's relative velocity plus (ω_b − ω_a) × their offset from it, and
  // the points that may meet lie within the smaller body's reach.  Bodies
  // turning together (a cluster of a pile tumbling as one) keep their pair.
  // A pair is held until that turn could have moved its points by kHoldTurn
  // hop heights, if that comes before the hop lands.
  // Per pair: how long it is held (NaN: no contact of it solved, not held).
  std::vector<double> hold_for(pairs.size(), std::numeric_limits<double>::quiet_NaN());
  for (size_t k = 0; k < contacts.size(); ++k) {
    const collide::SolverContact& c = contacts[k];
    const collide::BodyState& sa = states[static_cast<size_t>(c.a)];
    const collide::BodyState& sb = states[static_cast<size_t>(c.b)];
    const Eigen::Vector3d va = sa.v + sa.w.cross(c.point - sa.com);
    const Eigen::Vector3d vb = sb.v + sb.w.cross(c.point - sb.com);
    const size_t pk = contact_pair[k];
    const int a = pairs[pk].a, b = pairs[pk].b;
    const double height = AbsorbGap(a, b);
    double& held_for = hold_for[pk];
    if (std::isnan(held_for)) {
      held_for = hop;
      const double speed = std::min(bodies_[a].radius, bodies_[b].radius) * (sb.w - sa.w).norm();
      if (speed * hop > kHoldTurn * height) held_for = kHoldTurn * height / speed;
    }
    if ((vb - va).dot(c.normal) < c.target - height / hop) held_for = -kInf;
  }
  Impact recorded = impact;
  recorded.resting = true;
  recorded.hop = hop;
  for (size_t k = 0; k < contacts.size(); ++k)
    recorded.contacts.push_back({pairs[contact_pair[k]].a, pairs[contact_pair[k]].b,
                                 contacts[k].point, contacts[k].normal, contacts[k].normal_impulse,
                                 contacts[k].tangent_impulse});
  recorded.bodies = {impact.a, impact.b};
  for (int body : members)
    if (body != impact.a && body != impact.b) recorded.bodies.push_back(body);
  for (const auto& c : contacts) recorded.impulse += c.normal_impulse;
  auto place_of = [&](int body) {  // after the overlap push
    collide::Pose place = PoseAt(body, t);
    if (const auto it = shift.find(body); it != shift.end()) place.p += it->second;
    return place;
  };
  for (int body : recorded.bodies) recorded.place.push_back(place_of(body));
  // At rest: moving no faster than the hop, and not turning faster, at this
  // event and at each of the body's events back over kSleepEvents of them
  // and kSleepSpan of time, and in the same place at each (StillSince).
  // Where it is, not how it spins: a large island's sweeps leave its
  // bodies' spins noisy from solve to solve though they stay put (the pile
  // of 100, at rest from 7 s, hopped on to 13.6 s while sleep asked for a
  // spin steady to 2·gap/(K²Δ)), and a cube tipping off an edge at α turns
  // by ½ α T² over the span T.
  bool all_asleep = !members.empty();
  for (int body : members) {
    const bool slow = slow_now(body, states[static_cast<size_t>(index[body])]);
    if (slow) recorded.slow.push_back(body);
    all_asleep = all_asleep && slow && StillSince(body, t, place_of(body));
  }
  // The island's contacts are held until its hop lands again: its pairs
  // that were solved whole (none with an impact to come) between bodies of
  // the event — its members and the static bodies it touches.
  if (!all_asleep) {
    auto position = [&](int body) {
      auto it = std::find(recorded.bodies.begin(), recorded.bodies.end(), body);
      if (it == recorded.bodies.end() && sys_.bodies[body].first_var < 0)
        it = recorded.bodies.insert(it, body);
      return it == recorded.bodies.end() ? -1 : static_cast<int>(it - recorded.bodies.begin());
    };
    std::vector<std::pair<std::pair<int, int>, double>> held;
    for (size_t k = 0; k < pairs.size(); ++k) {
      if (skipped[k] || !(hold_for[k] > 0)) continue;  // NaN: not held
      const int ia = position(pairs[k].a), ib = position(pairs[k].b);
      if (ia >= 0 && ib >= 0) held.push_back({std::minmax(ia, ib), t + hold_for[k]});
    }
    std::sort(held.begin(), held.end());
    for (const auto& [key, until] : held) {
      recorded.held.push_back(key);
      recorded.held_until.push_back(until);
    }
  }
  ++counters_.impacts;
  ++counters_.resting_events;
  counters_.contacts_solved += static_cast<long>(contacts.size());
  NoteFound(recorded, true);
  auto pos = std::upper_bound(impacts_.begin(), impacts_.end(), recorded, ImpactOrder);
  impacts_.insert(pos, recorded);
  for (int body : members) {
    const physics::BodyModel& m = sys_.bodies[body];
    const auto it = shift.find(body);
    const Eigen::Vector3d moved = it != shift.end() ? it->second : Eigen::Vector3d::Zero();
    if (it != shift.end())
      for (int a = 0; a < 3; ++a)
        QueueSet(m.first_var + physics::kX + a,
                 sim_.Value(m.first_var + physics::kX + a, t, Side::kRight) + moved[a]);
    if (all_asleep) {
      Sleep(body, t, moved);
    } else {
      WriteVelocities(body, t, states[static_cast<size_t>(index[body])]);
    }
  }
  ApplyEdits(t);
}

const Impact* CollisionMonitor::PreviousResting(int body, double t) const {
  // The body's latest event at or before t.  One at t itself means the
  // body's velocities were solved at this instant already (an island struck
  // again): they hold that solution, and a guess would add it a second time.
  // Found through the body's own event times, not by a bounded scan of
  // everyone's: how many events other bodies had since must not decide
  // whether an island starts from its previous solve (an edit elsewhere in a
  // pile changed the count, and with it the solve).
  const auto& times = found_times_[static_cast<size_t>(body)];
  auto latest = times.upper_bound(t);
  if (latest == times.begin()) return nullptr;
  --latest;
  const double when = *latest;
  auto to = std::upper_bound(impacts_.begin(), impacts_.end(), when,
                             [](double time, const Impact& x) { return time < x.t; });
  for (auto it = to; it != impacts_.begin() && std::prev(it)->t == when;) {
    --it;
    if (Involves(*it, body)) return it->resting && it->t < t ? &*it : nullptr;
  }
  return nullptr;
}

// A resting event's impulses are its hop's share of the holding force, so a
// guess from the event before is scaled by the ratio of the hops.  It is
// taken only from an event at most two hops back (the island's previous
// one, not a configuration it has left), for the same pair at the same
// point (within the contact margin's share of the radius) and normal.
void CollisionMonitor::WarmStart(collide::SolverContact& c, int a, int b, const Impact* previous,
                                 double hop) const {
  if (previous == nullptr || !(previous->hop > 0) ||
      respond_time_ - previous->t > 2.0 * std::max(hop, previous->hop))
    return;
  const double near = kMarginRelative * std::min(bodies_[a].radius, bodies_[b].radius);
  const Impact::Contact* best = nullptr;
  double best_distance = near;
  for (const Impact::Contact& p : previous->contacts) {
    if (p.a != a || p.b != b || p.normal.dot(c.normal) < 0.99) continue;
    const double d = (p.point - c.point).norm();
    if (d <= best_distance) {
      best_distance = d;
      best = &p;
    }
  }
  if (best == nullptr) return;
  const double ratio = hop / previous->hop;
  c.warm_normal = ratio * best->normal_impulse;
  c.warm_tangent = ratio * best->tangent_impulse;
}

// Resting contact: against an immovable partner, an impact after which the
// body would rise less than 1e-6 of its radius before falling back ends the
// bouncing (otherwise an inelastic bounce repeats ever faster, without end,
// before the time it should come to rest).  The body's motion along the
// normal stops and is held: along that axis when the normal is a coordinate
// axis, in all three translations otherwise.  Returns the held axes.
std::vector<int> CollisionMonitor::RestingAxes(int body, const Eigen::Vector3d& n_into,
                                               bool partner_movable, double t, Eigen::Vector3d& v) {
  if (partner_movable) return {};
  const physics::BodyModel& m = sys_.bodies[body];
  Eigen::Vector3d a;
  for (int k = 0; k < 3; ++k) a[k] = sim_.Rate(m.first_var + physics::kDx + k, t, Side::kLeft);
  const double push = a.dot(n_into);   // acceleration into the partner
  const double rise = -v.dot(n_into);  // speed leaving it
  if (push <= 0 || rise * rise / (2 * push) >= kRestingRise * bodies_[body].radius) return {};
  v -= v.dot(n_into) * n_into;
  int axis = 0;
  n_into.cwiseAbs().maxCoeff(&axis);
  if (std::abs(n_into[axis]) > 1 - 1e-9) {
    v[axis] = 0.0;
    return {axis};
  }
  v.setZero();
  return {0, 1, 2};
}

// ---- invalidation ------------------------------------------------------------------

void CollisionMonitor::OnTruncate(int component, double kept) {
  for (int b : bodies_of_component_[component]) {
    truncated_.push_back({b, kept});
    ++version_[static_cast<size_t>(b)];
    carried_until_[static_cast<size_t>(b)] = std::min(carried_until_[static_cast<size_t>(b)], kept);
    if (broad_.Resting(b)) Unrest(b);
  }
}

void CollisionMonitor::AfterTruncate() {
  if (in_after_truncate_) return;
  in_after_truncate_ = true;
  double earliest = kInf;
  while (!truncated_.empty()) {
    auto work = std::move(truncated_);
    truncated_.clear();
    for (auto [b, kept] : work) {
      UpdateEnd(b);
      // Impacts after `kept` involving b were computed from data that is gone.
      const double limit = responding_ ? std::max(kept, respond_time_) : kept;
      // The windows to check again start at the first change.  A response's
      // jump at t changes nothing before t: the components re-step from
      // their last sample up to t through the same motion (a ballistic ball
      // may have its last sample seconds back), and checking every window
      // since that sample again after each impact made the checks grow with
      // impacts × span × pairs.
      earliest = std::min(earliest, limit);
      // Every body's jumps at a voided event are void; the others' data after
      // it must be recomputed.
      auto void_event = [&](const Impact& imp) {
        for (int body : imp.bodies.empty() ? std::vector<int>{imp.a, imp.b} : imp.bodies)
          for (int c : bodies_[body].components) sim_.Truncate(c, imp.t, /*strict=*/true);
      };
      // Its events found after `limit`, through its own event times, in
      // time order (impacts_ is sorted by time).
      const auto& found = found_times_[static_cast<size_t>(b)];
      for (auto next = found.upper_bound(limit); next != found.end();
           next = found.upper_bound(limit)) {
        auto at = std::lower_bound(impacts_.begin(), impacts_.end(), *next,
                                   [](const Impact& x, double t) { return x.t < t; });
        while (!Involves(*at, b)) ++at;
        const Impact imp = std::move(*at);
        impacts_.erase(at);
        NoteFound(imp, false);
        ++counters_.invalidated_impacts;
        void_event(imp);
      }
      // Its events held aside after `limit`, found through its own event
      // times (carried_ is latest first).
      const auto& held = carried_times_[static_cast<size_t>(b)];
      while (!held.empty() && *held.rbegin() > limit) {
        const double when = *held.rbegin();
        auto at = std::lower_bound(carried_.begin(), carried_.end(), when,
                                   [](const Impact& x, double t) { return x.t > t; });
        while (!Involves(*at, b)) ++at;
        const Impact imp = std::move(*at);
        carried_.erase(at);
        NoteHeldAside(imp, false);
        void_event(imp);
      }
    }
  }
  in_after_truncate_ = false;
  if (std::isfinite(earliest) && !responding_ && !cutting_) Reopen(earliest);
  // A cut of CutExposed changes motion that no check has read (the body
  // was not searched against a recomputed one, nor in reach of a response,
  // in the windows before, or it would have been cut there): the current
  // window is checked again, not the windows since the cut.
  if (cutting_) earliest = std::max(earliest, EpochStart(epoch_));
  if (std::isfinite(earliest) && (earliest < EpochStart(epoch_ + 1) || epoch_ >= kEpochs)) {
    const long k = static_cast<long>(std::floor((earliest - sys_.t0) / epoch_length_));
    StartEpoch(std::clamp(std::min(k, epoch_), 0L, kEpochs));
  }
}

}  // namespace asgard::solver
