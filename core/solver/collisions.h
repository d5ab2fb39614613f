// Collisions inside the event-driven solution (seed 5.2.2, 5.2.3, 5.3).
//
// The monitor watches a Simulation through its hooks.  Time is cut into
// fixed windows ("epochs") of span/1024; a window is checked once every
// collidable body has been computed past its end — so a pair is only ever
// checked over an interval both bodies are known over (seed 5.2.3):
//
//   epoch k  [E0 ──────────────── E1]
//     broad phase   each moving body's box over the window → sweep and prune; static
//                   bodies' exact boxes in a tree of their own (never paired).  A body
//                   also keeps a loose box over many windows with the bodies it
//                   overlaps (its neighbours): one with none is not boxed, sampled
//                   or swept for the window at all
//     narrow phase  per candidate pair and piece pair: TimeOfImpact from the pair's
//                   start (E0, or the last impact of either body inside the window)
//     response      the earliest impact (ties: lowest pair) gets an impulse; the
//                   bodies' velocity variables jump there (Simulation::ApplyAt, all of a
//                   response's changes at once), which truncates their components
//                   and, transitively, their readers
//
// Why fixed windows and not "as soon as both bodies are computed": the time
// an impact is found at must depend only on the two bodies' waveforms, never
// on how far the scheduler happened to have run — otherwise a re-simulation
// after an edit could not reproduce a from-scratch run bit for bit.  The cost
// is a little lag (at most one window) before an impact is seen, i.e. a few
// discarded steps of the bodies involved.  Checking all pairs of a window at
// once also lets one sweep-and-prune serve N bodies in ~N log N.
//
// Invalidation (seed 5.2.3, "all components that contain state equations for
// objects that have collided with objects that have state equations in C after
// time t"): when a component is truncated to t, every recorded impact after t
// involving one of its bodies is dropped, and the other body's components are
// truncated to just before that impact — recursively.
//
// Rules: a pair is tested when at least one body has -ct 1; bodies of one
// -artbody joined directly by a link are not tested; static bodies and bodies
// whose motion a trajectory prescribes at the impact time have infinite mass
// (seed 4.1.4); two such bodies are not tested.  Restitution of a pair is the
// product of the bodies' coefficients, friction the geometric mean.  A pair that separates is never
// re-detected: after an impact its threshold shrinks below the gap it left.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/collide/collide.h"
#include "core/scene/scene.h"
#include "core/solver/indexed_set.h"
#include "core/solver/simulation.h"

namespace asgard::solver {

struct CollisionCounters {
  long windows = 0;               // epochs checked
  long boxes = 0;                 // bodies boxed for a window (resting and lone ones are not)
  long loose_boxes = 0;           // loose boxes set (CheckEpoch: a body's refit)
  long broad_phase_pairs = 0;     // candidate pairs from sweep and prune
  long narrow_phase_queries = 0;  // time-of-impact searches
  long distance_queries = 0;      // distance evaluations inside them
  long impacts = 0;               // impulses applied (including later undone ones)
  long invalidated_impacts = 0;   // impacts undone by an earlier truncation
  long resting_events = 0;        // island solves of slow contacts (included in impacts)
  long contacts_solved = 0;       // contact points in those solves
  long impacts_absorbed = 0;      // points landing within the hop, solved there (AbsorbGap)
  long overlaps_resolved = 0;     // overlapping pairs pushed apart
  long sleeps = 0;                // bodies put to sleep
  long wakes = 0;                 // sleeping bodies woken
};

struct Impact {
  double t = 0.0;
  int a = -1, b = -1;    // body indices, a < b
  double impulse = 0.0;  // normal impulse magnitude
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  // Every body whose variables jump at t (a and b, and the rest of a
  // resting island); an edit or truncation of any of them voids the event.
  std::vector<int> bodies;
  std::vector<int> slow;  // bodies of the island moving no faster than its hop
  // Resting events: where each of `bodies` is after the event (its overlap
  // push included); a body is at rest only where its points stay put from
  // event to event (StillSince).
  std::vector<collide::Pose> place;
  bool resting = false;  // a simultaneous solve of slow contacts, not an impact
  // Resting events: the island's held contact pairs, as positions in
  // `bodies` (which then also lists the static bodies the island touches),
  // sorted, each held until its `held_until`: the time the island's hop
  // lands again, or sooner where its bodies turn (RespondResting).  A held
  // pair is not searched before then while no later event involves either
  // of its moving bodies: one event per hop for the island, not one per
  // contact landing.
  std::vector<std::pair<int, int>> held;
  std::vector<double> held_until;
  // Resting events: the hop they were solved for, and each solved contact's
  // impulses — the next resting event of the island starts from them
  // (SolveContacts' warm start).
  struct Contact {
    int a = -1, b = -1;  // body indices, a < b
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
    double normal_impulse = 0.0;
    Eigen::Vector3d tangent_impulse = Eigen::Vector3d::Zero();
  };
  double hop = 0.0;
  std::vector<Contact> contacts;
};

class CollisionMonitor {
 public:
  // Attaches to `sim` (sets its after_step, on_truncate and after_truncate
  // hooks).  The monitor must outlive the simulation's run.
  explicit CollisionMonitor(Simulation& sim, double separation = 0.0);

  const std::vector<Impact>& impacts() const { return impacts_; }
  const CollisionCounters& counters() const { return counters_; }
  const std::vector<scene::Diagnostic>& warnings() const { return warnings_; }
  // Gap at which bodies land before an impact.
  double separation() const { return separation_; }
  // Takes over the events of an earlier run between bodies whose results
  // were carried over (indices already mapped to this run's bodies);
  // `carried` marks those bodies, by this run's index (a static one: the
  // same body as before).  Each event counts as found only when the window
  // check reaches it in time order (see "Re-simulation after an edit"
  // below).
  void AdoptImpacts(const std::vector<Impact>& impacts, const std::vector<char>& carried);
  // Whether bodies a and b are ever tested against each other.
  bool Tested(int a, int b) const;

 private:
  struct BodyInfo {
    bool collidable = false;
    bool infinite = false;  // static
    std::vector<collide::Piece> pieces;
    double radius = 0.0;                           // max piece bound radius
    Eigen::Vector3d lo = Eigen::Vector3d::Zero();  // static: world box of its pieces
    Eigen::Vector3d hi = Eigen::Vector3d::Zero();
    std::vector<int> components;  // components holding its variables
    double end = 0.0;             // time all its variables are computed to
  };

  void AfterStep(int component);
  void OnTruncate(int component, double kept);
  void AfterTruncate();
  void UpdateEnd(int body);
  void StartEpoch(long epoch);
  // Checks windows while every collidable body is computed past the end of
  // the current one.
  void CheckReadyWindows();
  // Checks the current epoch; returns true when it is complete.
  bool CheckEpoch();
  std::optional<Impact> FirstImpact(int a, int b, double start, double end);
  // The time until which the pair is held by its island's latest resting
  // event (Impact::hold), or -inf: the latest event of either body on
  // record before the current window's end, back to the longest hop before
  // the window (CheckEpoch's pass).
  double HeldUntil(int a, int b) const;
  void Respond(const Impact& impact);
  struct PairContact {
    int a = -1, b = -1;
    std::vector<collide::ContactPoint> points;
    double min_gap = 0.0;
  };
  // Contact points of every piece pair of bodies a, b within `margin` at t
  // (overlapping pieces through MPR penetration).
  PairContact ContactsAt(int a, int b, double t, double margin) const;
  std::vector<collide::ContactPoint> PieceContacts(
      const collide::Piece& pa, const collide::Pose& xa, const collide::Piece& pb,
      const collide::Pose& xb, const collide::DistanceResult& d, double margin) const;
  // Largest approach speed (−normal relative velocity) over the points.
  double Approach(int a, int b, double t, const std::vector<collide::ContactPoint>& points) const;
  Eigen::Vector3d PointVelocity(int body, double t, const Eigen::Vector3d& point,
                                Side side = Side::kRight) const;
  Eigen::Vector3d Acceleration(int body, double t) const;
  // Acceleration under the body's own forces at t: its velocity rows' rates,
  // or, where a hold of those rows ended at t (it slept until an event woke
  // it there, and its held rates read zero), their equations evaluated at t
  // (an exact joint's reaction is not in them: a woken jointed body's hop is
  // judged by its applied forces alone).
  Eigen::Vector3d FreeAcceleration(int body, double t);
  // Acceleration of the body's material point at `point` (world) at t.
  Eigen::Vector3d PointAcceleration(int body, double t, const Eigen::Vector3d& point) const;
  bool Asleep(int body, double t) const;
  bool Movable(int body, double t) const;
  collide::BodyState StateAt(int body, double t, bool movable) const;
  double ContactMargin(int a, int b) const;
  // The hop period of resting contact (see collisions.cc).
  double HopPeriod(double accel, double radius) const;
  // The landing speed below which a pair's touch rests instead of bouncing,
  // and (optional) the pair's hop period.
  double SlowSpeed(int a, int b, double t, const std::vector<collide::ContactPoint>& points,
                   double* hop = nullptr) const;
  double Restitution(int a, int b) const;
  // How near touching an island's point lands to be answered at its event.
  double AbsorbGap(int a, int b) const;
  void RespondResting(const Impact& impact);
  // The latest event before t that moved `body`, when it was a resting one.
  const Impact* PreviousResting(int body, double t) const;
  // Sets c's warm start from the matching contact of the pair (a, b) in
  // `previous` (same pair, point and normal), scaled to the hop.
  void WarmStart(collide::SolverContact& c, int a, int b, const Impact* previous, double hop) const;
  // WriteVelocities and Sleep queue their changes in edits_ (values read
  // now, before any component is cut back to t), applied at once by
  // ApplyEdits at the end of the response; Wake applies its own at once.
  void WriteVelocities(int body, double t, const collide::BodyState& state);
  void Wake(int body, double t);
  // Holds every variable of the body (its position moved by `shift`).
  void Sleep(int body, double t, const Eigen::Vector3d& shift);
  void QueueSet(int var, double value) {
    edits_.push_back({Simulation::Edit::Kind::kSet, var, value});
  }
  void QueueHold(int var, double value) {
    edits_.push_back({Simulation::Edit::Kind::kHold, var, value});
  }
  void QueueRelease(int var) { edits_.push_back({Simulation::Edit::Kind::kRelease, var}); }
  void ApplyEdits(double t);
  // Whether `body`, found slow at a resting event at t where it is placed
  // at `now`, is at rest: slow at each of its events back over at least
  // kSleepEvents of them and kSleepSpan of time, and at each placed where
  // it is now: its centre within a hop height, its turn (times its radius)
  // within kSleepDrift of one, both plus the landing gap.  The hop moves a
  // body up and down by its height, and where it lands varies with the
  // solve's accuracy, a fraction of that; a body at rest does not turn.
  bool StillSince(int body, double t, const collide::Pose& now) const;
  static bool Involves(const Impact& impact, int body);
  std::vector<int> RestingAxes(int body, const Eigen::Vector3d& n_into, bool partner_movable,
                               double t, Eigen::Vector3d& v);
  collide::Motion MotionOf(int body, double t0, double t1) const;
  // What a time-of-impact search over [t0, t1] reads of one body: its
  // motion bounds, its acceleration at t0 and its bound over the interval,
  // its velocity and pose at t0.  Kept per body while the interval and the
  // body's version stay the same (a body is searched against each of its
  // neighbours from the same start: two thirds of a pile's searches).
  struct SearchSpan {
    bool valid = false;
    double t0 = 0.0, t1 = 0.0;
    long version = 0;
    collide::Motion motion;
    Eigen::Vector3d accel = Eigen::Vector3d::Zero(), velocity = Eigen::Vector3d::Zero();
    double accel_bound = 0.0;
    collide::Pose pose;
  };
  const SearchSpan& SpanOf(int body, double t0, double t1);
  // The longest interval [from, until] ∋ [t0, t1] over which the body's pose
  // is exactly constant in its waveforms (every interval from its sample at
  // t0 on has equal values, zero rates and no bubble), or nothing when it
  // moves within [t0, t1].
  std::optional<std::pair<double, double>> HeldSpan(int body, double t0, double t1) const;
  // The body's position range over [t0, t1] (the three axes' Hermite
  // pieces, exactly), not padded.
  void PositionRange(int body, double t0, double t1, Eigen::Vector3d& lo,
                     Eigen::Vector3d& hi) const;
  // Sets the body's loose box from its range over the window [e0, e1]
  // (grown from the previous one while that stays small), finds how long
  // its motion stays inside from e0 on, and its neighbours' list (Near).
  void Loosen(int body, double e0, double e1);
  // Extends the check that the body stays inside its loose box to the end
  // of its computed motion (after each step of its components).
  void FollowLoose(int body);
  // Whether the body's loose box holds its motion over [e0, e1].
  bool LooseHolds(int body, double e0, double e1) const;
  // Whether loose boxes are in use (not left aside where they do not pay).
  bool LooseOn() const { return counters_.windows >= loose_resume_; }
  // Recomputes the neighbours of the bodies in `refit` (of every body, in
  // one sweep, when they are many): the bodies each is tested with whose
  // loose boxes, or static boxes, overlap its own.
  void Near(const std::vector<int>& refit);
  // Moves a body's box (box_lo_, box_hi_) among the resting ones, and back.
  void Rest(int body);
  void Unrest(int body);
  // Bound on |a(t) − ref| over [t0, t1] for the position interpolant's
  // acceleration a; AccelAt is that acceleration at t (the segment after t,
  // up to t1).
  double AccelBound(int body, double t0, double t1,
                    const Eigen::Vector3d& ref = Eigen::Vector3d::Zero()) const;
  Eigen::Vector3d AccelAt(int body, double t, double t1) const;
  // The right limit at t (an event at t has moved it), or the left one.
  collide::Pose PoseAt(int body, double t, Side side = Side::kRight) const;
  // The pose a search up to t1 reads at t: the left limit at t1.
  collide::Pose SearchPose(int body, double t, double t1) const;
  // The body's velocity and body-frame angular velocity variables at t
  // (dx, dy, dz, w1, w2, w3).
  void ReadVelocities(int body, double t, Side side, double* out) const;
  bool Prescribed(int body, double t) const;
  template <typename F>
  void ForEachSegment(int var, double t0, double t1, F&& f) const;
  double EpochStart(long k) const;
  // Whether the body's motion over the window ending at e1 is the one
  // checked before (carried over, or checked before a cut back) and not cut
  // back before e1 since.
  bool AsCarried(int body, double e1) const {
    return carried_until_[static_cast<size_t>(body)] >= e1;
  }
  // After a cut back to t that no response made (an edit; not CutExposed):
  // the events found after t are held aside to be reached again in time
  // order, and the bodies' motion over the windows checked so far counts
  // as checked (AsCarried).
  void Reopen(double t);
  // Records the event as found (in impacts_; add), or no longer.
  void NoteFound(const Impact& x, bool add);
  // Records the event as held aside in carried_ (add), or no longer.
  void NoteHeldAside(const Impact& x, bool add);
  // Takes the earliest carried event as found (carried_.back()).
  void ReachCarried();
  // The time the step that lands the body's components on its event at u
  // starts from (the last sample before u; the earliest of its components).
  double LandingStart(int body, double u) const;
  // The time every component of the body is computed to (infinite for a
  // static body).
  double ComputedUntil(int body) const;
  // Where the body's motion in the window ending at e1 is not the one a run
  // from scratch has at this point, the start of the step landing it on its
  // next event held aside (which starts before e1); nothing otherwise.
  std::optional<double> ExposedFrom(int body, double e1) const;
  // Cuts back each of `bodies` that is exposed (ExposedFrom) to its landing
  // step's start; whether any was.
  bool CutExposed(std::vector<int> bodies, double e1);
  // The moving bodies an island grown from a and b in the window [e0, e1]
  // could take in (a chain of boxes widened by the contact margin).
  std::vector<int> IslandReach(int a, int b, double e0, double e1);

  Simulation& sim_;
  const physics::EquationSystem& sys_;
  double separation_;
  double epoch_length_;
  // The longest hop of any resting event so far: the window check looks
  // this far back for the holds that still apply (CheckEpoch, HeldUntil).
  double longest_hop_ = 0.0;
  long epoch_ = 0;     // current epoch
  bool idle_ = false;  // no pair can collide: no windows are checked
  long pending_ = 0;   // collidable bodies not yet computed past its end
  // The collidable bodies whose motion is computed short of the run's end
  // (BodyInfo::end < t1).
  IndexedSet open_;
  std::vector<BodyInfo> bodies_;
  collide::BroadPhase broad_;  // the static bodies' boxes, and each window's moving ones
  // The current window's boxes (per body, with the version they were
  // computed at) and candidate pairs, for checking it again after an impact.
  long boxes_epoch_ = -1;
  std::vector<long> box_version_;
  std::vector<Eigen::Vector3d> box_lo_, box_hi_;
  std::vector<std::pair<int, int>> window_pairs_;
  // The collidable bodies that are not static and not resting (their boxes
  // are computed per window).
  IndexedSet moving_;
  // Bodies whose boxes were computed for the current window, and the
  // window's serial number each was last boxed in.
  std::vector<int> window_moving_;
  std::vector<long> window_stamp_;
  long window_serial_ = 0;
  // A body that holds still (asleep, or at rest where nothing moves it) has
  // its box among broad_'s resting ones and is not boxed again while every
  // window checked lies within [rest_from_, rest_until_]; a truncation of
  // its components (OnTruncate) ends that.
  std::vector<double> rest_from_, rest_until_;
  std::set<std::pair<double, int>> rest_by_from_, rest_by_until_;
  // Loose boxes.  Each collidable body that is not static has a box that
  // holds it (padded like a window's box) over every window from
  // loose_from_ to loose_until_, known from its waveform up to
  // loose_scanned_ (FollowLoose), valid while loose_version_ is its
  // version_.  A body whose loose box overlaps no tested body's loose box
  // and no static box (near_ empty, near_static_ 0) cannot collide in those
  // windows: it is not boxed, sampled or swept there (CheckEpoch).
  std::vector<Eigen::Vector3d> loose_lo_, loose_hi_;
  std::vector<double> loose_from_, loose_until_, loose_scanned_;
  std::vector<long> loose_version_;
  std::vector<std::vector<int>> near_;
  std::vector<char> near_static_;
  collide::BroadPhase loose_broad_;  // the static boxes, and every loose box on a full rebuild
  long loose_resume_ = 0;            // loose boxes are left aside until this window count
  static constexpr long kLooseBackoff = 16, kLooseBackoffMax = 1024;  // windows (CheckEpoch)
  long loose_backoff_ = kLooseBackoff;  // for how many windows next time
  std::vector<std::vector<int>> bodies_of_component_;
  std::set<std::pair<int, int>> excluded_;    // directly linked parts of one artbody
  std::vector<Impact> impacts_;               // sorted by time
  std::vector<std::multiset<double>> found_times_;  // per body: its events' times in impacts_
  // Re-simulation after an edit (or any cut back that no response made).
  // The run from scratch finds its events one by one, in time order, each
  // from the motion as it is at that point: no event later than the window
  // being checked is on record, and a body's motion after its latest event
  // goes on unbroken.  An edited run starts with the events of the bodies it
  // carries over (AdoptImpacts), and a cut back to t keeps those found after
  // t that do not involve the bodies cut (Reopen).  Such events are held
  // aside in carried_ (latest first) until the window check reaches them:
  // one is taken as found (ReachCarried) when no search finds an earlier
  // impact, which would void it first.  A pair of two bodies whose motion
  // over the window is the one checked before (AsCarried) is not searched:
  // it was searched with the same motion, and its events are those held.
  // A body with an event held aside has the motion of a run that found it,
  // which differs from the run from scratch's where the step landing it
  // there starts before the window's end: before it is searched against a
  // recomputed body, or may join an island with one, it is cut back to that
  // step's start (CutExposed).  The run from scratch never cuts back before
  // the window it checks, so none of this happens there.
  bool adopted_ = false;
  bool cutting_ = false;  // inside CutExposed's truncations
  std::vector<Impact> carried_;
  std::vector<std::multiset<double>> carried_times_;  // per body: its events in carried_
  IndexedSet held_aside_;                             // the bodies with events in carried_
  std::vector<int> moving_all_;                       // the collidable bodies that are not static
  std::vector<double> carried_until_;  // per body: motion checked before up to here (AsCarried)
  std::set<std::pair<int, int>> overlap_warned_;
  std::vector<std::pair<int, double>> truncated_;  // (body, kept) awaiting AfterTruncate
  std::vector<scene::Diagnostic> warnings_;
  // Last search of each pair in the current window, valid while neither
  // body changed (version_ counts truncations of a body's components).
  struct PairMemo {
    bool valid = false;
    double start = 0.0, end = 0.0;
    long version_a = 0, version_b = 0;
    std::optional<Impact> result;
  };
  std::unordered_map<uint64_t, PairMemo> memo_;  // by the pair (a < b) as a << 32 | b
  // Per body, from CheckEpoch's pass over the recent events (valid where
  // `pass` is recent_pass_): its latest event in the window (from e0), its
  // last event before the window's end, back to the longest hop before the
  // window (index in impacts_, HeldUntil) and its place in that event's
  // bodies.
  struct RecentEvents {
    long pass = -1;
    double window = 0.0;
    long last = -1;
    int place = 0;
  };
  std::vector<RecentEvents> recent_;
  long recent_pass_ = 0;
  // Per body, made on first use (FreeAcceleration): its velocity rows'
  // equations as one tape, and the variables they read.
  struct ForceTape {
    expr::Tape tape;
    std::vector<int> reads;
    int offset = 0;
    std::vector<double> x;
  };
  std::map<int, ForceTape> force_tapes_;
  std::vector<SearchSpan> spans_;                // per body (SpanOf)
  std::vector<long> version_;
  CollisionCounters counters_;
  bool responding_ = false;
  std::vector<Simulation::Edit> edits_;  // the response's changes at respond_time_
  double last_impact_time_ = -1e300;
  int same_instant_ = 0;  // impacts in a row at last_impact_time_
  double respond_time_ = 0.0;
  bool in_after_truncate_ = false;
};

}  // namespace asgard::solver
