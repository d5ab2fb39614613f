// Collision geometry: distance between convex pieces, broad phase, time of
// impact and impulse response (seed 5.3).  Pure functions of geometry and
// motion; the solver decides when to call them (seed 5.2.3).
//
//   Piece (sphere | polytope, body coordinates)
//     │  Distance(a, pose_a, b, pose_b, &cache)   closest points, normal; the
//     │                                           cache (last simplex / feature
//     │                                           pair) makes coherent queries
//     │                                           cost about one iteration
//     │  OverlapMpr(...)                          libccd MPR: start-overlap
//     │                                           check and test oracle only
//   BroadPhase                                    sweep and prune on boxes
//   TimeOfImpact(pieces, motions, [t0, t1])       conservative advancement
//   Impulse(bodies, contact, e, μ)                new velocities
#pragma once

#include <Eigen/Dense>
#include <array>
#include <functional>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace asgard::collide {

// A convex piece in its body's coordinates (origin at the body's centre of
// mass).  Spheres are a centre and a radius; polytopes are their hull
// vertices with face and edge adjacency for feature walks.
struct Piece {
  bool is_sphere = false;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // sphere
  double radius = 0.0;                               // sphere
  std::vector<Eigen::Vector3d> vertices;             // polytope
  std::vector<std::vector<int>> faces;               // polytope: CCW from outside
  std::vector<Eigen::Vector3d> normals;              // polytope: outward, per face
  double bound_radius = 0.0;  // max distance of any point of the piece from the body origin
  std::vector<std::vector<int>> neighbors;  // polytope: vertex adjacency (sorted, from faces)

  static Piece Sphere(const Eigen::Vector3d& center, double radius);
  // From hull vertices and CCW faces (as geometry::ConvexHull gives them).
  // Normals are recomputed (Newell) from the faces.  Throws
  // std::invalid_argument for an empty vertex list or an out-of-range index.
  static Piece Polytope(std::vector<Eigen::Vector3d> vertices, std::vector<std::vector<int>> faces);
  // Support point in direction d (body coordinates).  For a sphere this is
  // the point of the sphere surface (the centre when d = 0).
  Eigen::Vector3d Support(const Eigen::Vector3d& d) const;
  // Index of a support vertex of the piece's core in direction d: a polytope
  // vertex (ties go to the lowest index reached; hill climbing from `hint`
  // for large polytopes), or 0 for a sphere, whose core is its centre.
  int SupportIndex(const Eigen::Vector3d& d, int hint = 0) const;
  // Core point of an index from SupportIndex (body coordinates).
  const Eigen::Vector3d& CorePoint(int index) const {
    return is_sphere ? center : vertices[static_cast<size_t>(index)];
  }
  // Radius added to the core (the sphere radius; 0 for polytopes).
  double CoreRadius() const { return is_sphere ? radius : 0.0; }
};

// Rigid placement: x_world = p + R x_body.
struct Pose {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
};

// Warm start carried between queries of the same pair of pieces.
struct DistanceCache {
  int count = 0;
  std::array<std::pair<int, int>, 4> simplex{};  // support vertex indices (a, b)
  Eigen::Vector3d last_direction = Eigen::Vector3d::UnitX();
  bool valid = false;
};

struct DistanceResult {
  double distance = 0.0;     // ≥ 0: separation; 0 when touching or overlapping
  bool overlapping = false;  // the pieces intersect (distance 0, beyond tolerance)
  Eigen::Vector3d point_a = Eigen::Vector3d::Zero();  // closest point on a, world
  Eigen::Vector3d point_b = Eigen::Vector3d::Zero();  // closest point on b, world
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  // unit, from a towards b
  int iterations = 0;
};

// Distance between two convex pieces (GJK with exact sub-simplex solution;
// spheres are handled as points whose radius is subtracted afterwards, seed
// 5.3.1).  Deterministic: the same inputs and cache give the same result.
DistanceResult Distance(const Piece& a, const Pose& pa, const Piece& b, const Pose& pb,
                        DistanceCache* cache = nullptr);

// libccd MPR intersection test with tight tolerances and an iteration cap.
// Returns nullopt when libccd gives no usable answer (non-finite output).
std::optional<bool> OverlapMpr(const Piece& a, const Pose& pa, const Piece& b, const Pose& pb);

// Penetration of two overlapping pieces by libccd's MPR: translating b by
// depth × normal separates them (normal unit, from a towards b).  nullopt when
// they do not overlap or libccd gives no usable answer.
struct Penetration {
  double depth = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // world, inside the overlap
};
std::optional<Penetration> PenetrationMpr(const Piece& a, const Pose& pa, const Piece& b,
                                          const Pose& pb);

// One point of a contact manifold, world frame.
struct ContactPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    // midway between the surfaces
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  // unit, from a towards b
  double gap = 0.0;                                   // signed; < 0 overlaps
};

// Contact manifold of two pieces near contact: when a face of one is
// parallel to the normal (within ~3°) the other's most opposed face is
// clipped against it (Sutherland–Hodgman) and every clipped point within
// `margin` of the reference plane is a contact point (face–face: up to 8,
// edge–face: 2, vertex–face: 1); otherwise (edge–edge, spheres) the single
// closest point pair.  `closest` is the pair's Distance result, or for
// overlapping pieces a result whose normal and distance come from the
// penetration (distance = −depth).
std::vector<ContactPoint> Manifold(const Piece& a, const Pose& pa, const Piece& b, const Pose& pb,
                                   const DistanceResult& closest, double signed_distance,
                                   double margin);

// Whether two closed axis-aligned boxes overlap (touching counts).
inline bool BoxesOverlap(const Eigen::Vector3d& a_lo, const Eigen::Vector3d& a_hi,
                         const Eigen::Vector3d& b_lo, const Eigen::Vector3d& b_hi) {
  return (a_lo.array() <= b_hi.array()).all() && (b_lo.array() <= a_hi.array()).all();
}

// Sweep and prune over axis-aligned boxes (the solver passes boxes that
// bound a body's bounding sphere over a time interval).  Pairs are reported
// once, as (smaller id, larger id), sorted.  Cost ~ N log N + overlaps.
//
// Static boxes (AddStatic) stay across Clear and live in their own tree: a
// moving box is tested against the statics it overlaps (log S + hits), and
// two statics never pair, so a closed box of walls adds nothing per window.
//
// Resting boxes (AddResting, bodies that hold still for a while) also stay
// across Clear, until RemoveResting: they pair with moving boxes only, never
// with statics or one another.  They live in a second tree, updated
// incrementally: a removal marks its leaf dead, an addition goes to a short
// list scanned linearly, and the tree is rebuilt (at the next Pairs) only
// when that list or the dead leaves outgrow a fraction of the live ones
// (amortised O(log R) per change), so bodies falling asleep and waking cost
// nothing per window.
class BroadPhase {
 public:
  // Drops the moving boxes (static and resting ones stay).
  void Clear();
  void Add(int id, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
  void AddStatic(int id, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
  // Adds (or replaces) the resting box of `id` (id >= 0).
  void AddResting(int id, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
  // Drops the resting box of `id`, if any.
  void RemoveResting(int id);
  bool Resting(int id) const {
    return id >= 0 && static_cast<size_t>(id) < resting_gen_.size() &&
           resting_gen_[static_cast<size_t>(id)] != 0;
  }
  std::vector<std::pair<int, int>> Pairs() const;

 private:
  struct Box {
    int id;
    Eigen::Vector3d lo, hi;
    long gen = 0;  // resting boxes: live while resting_gen_[id] == gen
  };
  // Node of a tree: a leaf holds boxes[first], an inner node its two
  // children (left = this + 1, right = `right`).
  struct Node {
    Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
    int first = -1;  // leaf: index into boxes; inner: -1
    int right = -1;
  };
  // Bounding-box tree over `boxes` (reordered by Build: median splits on
  // the longest axis of the centres' extent).
  struct Tree {
    std::vector<Box> boxes;
    std::vector<Node> nodes;
    void Build() {
      nodes.clear();
      if (!boxes.empty()) Build(0, static_cast<int>(boxes.size()));
    }
    // Calls f(box) for every box overlapping [lo, hi].
    template <typename F>
    void Query(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, F&& f) const;

   private:
    int Build(int begin, int end);
  };
  // Rebuilds the resting tree when the additions or dead leaves since the
  // last build call for it (on each Pairs).
  void RebuildResting() const;
  std::vector<Box> boxes_;
  // Built on the first Pairs after AddStatic.
  mutable Tree statics_;
  mutable bool statics_built_ = false;
  mutable Tree resting_;                  // live and dead resting boxes as of the last rebuild
  mutable std::vector<Box> resting_new_;  // added since
  std::vector<long> resting_gen_;         // per id: its live resting box's generation, 0: none
  long resting_live_ = 0, next_gen_ = 1;
  mutable long resting_dead_ = 0;
};

// Motion of a body over an interval: its pose at any time in the interval,
// and bounds on its speeds there.
struct Motion {
  std::function<Pose(double t)> pose;
  double max_linear_speed = 0.0;   // bound on |v| of the centre of mass
  double max_angular_speed = 0.0;  // bound on |ω|
  // Optional, tighter: velocity and world angular velocity at the start of
  // the interval and bounds on how far they change over it.  With these the
  // distance along the current contact normal n closes no faster than
  //   |n·(v_b − v_a)| + Δv_a + Δv_b + (|ω_a × n| + Δω_a) r_a + (|ω_b × n| + Δω_b) r_b,
  // which for bodies sliding or spinning on a contact is far below the
  // speed bound.
  Eigen::Vector3d v0 = Eigen::Vector3d::Zero();
  Eigen::Vector3d w0 = Eigen::Vector3d::Zero();
  double dv = std::numeric_limits<double>::infinity();
  double dw = std::numeric_limits<double>::infinity();
};

struct ImpactResult {
  double time = 0.0;       // first time the pieces come within `separation`
  DistanceResult contact;  // the query at `time`
  int iterations = 0;
};

// First time in [t0, t1] at which the distance between the pieces falls to
// `separation` (> 0, small), by conservative advancement: from t, the
// distance d can shrink at most as fast as
//   |v_a| + |v_b| + |ω_a| r_a + |ω_b| r_b   (r = the piece's bound_radius;
//                                            for a sphere |center|, since
//                                            only its centre's motion matters),
// so t advances by (d − separation/2) / that bound, never passing the
// contact.  Lands at a distance in (0, separation]; falls back to bisection on
// distance when advancement stalls.  Returns nullopt when no contact occurs in
// [t0, t1].  If the pieces already overlap at t0 it reports t0 with
// contact.overlapping set.  Deterministic for the same inputs.
//
// `graze` (a distance, ≥ 0) trades exactness for speed where the bound
// crawls: every advancement step is long enough to close `graze` at the
// bound's speed.  A contact is then still never passed by more than `graze`
// (a sample that overlaps or comes within separation/2 is bisected back), but
// a graze that dips below separation/2 and recovers between two samples can
// go unseen — by at most `graze` of overlap.  Without it (0) the number of
// steps grows as the bound over the separation, without limit as the
// separation shrinks.
std::optional<ImpactResult> TimeOfImpact(const Piece& a, const Motion& ma, const Piece& b,
                                         const Motion& mb, double t0, double t1, double separation,
                                         DistanceCache* cache = nullptr, double graze = 0.0);

// Rigid body state for the impulse computation, world frame.
struct BodyState {
  double inv_mass = 0.0;                                  // 0: infinite mass
  Eigen::Matrix3d inv_inertia = Eigen::Matrix3d::Zero();  // world frame; 0: infinite
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
};

// Instantaneous impulse at `point` along `normal` (unit, from a to b) with
// restitution e (1: elastic) and Coulomb friction μ (0: frictionless),
// including angular terms.  Updates a and b.  Returns the normal impulse
// magnitude (0 when the bodies are already separating at the point).
double ApplyImpulse(BodyState& a, BodyState& b, const Eigen::Vector3d& point,
                    const Eigen::Vector3d& normal, double restitution, double friction);

// A contact for the simultaneous solve: bodies by index into the solver's
// body list (−1: the immovable world), point and normal (from a to b).
struct SolverContact {
  int a = -1, b = -1;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  double friction = 0.0;
  double target = 0.0;  // least normal relative velocity after the solve
  // The tangential relative velocity (b − a, world; its normal part is
  // dropped) that a sticking contact is brought to, and that a sliding one's
  // kinetic friction opposes the slip from: zero but where the contact is
  // pressed along a slope over a hop (collisions.cc, RespondResting).
  Eigen::Vector3d target_tangent = Eigen::Vector3d::Zero();
  // In: a guess of the solution (warm start), applied before the first
  // sweep — the normal impulse clamped at 0, the tangential one (world,
  // its normal part dropped) to the Coulomb disc.
  double warm_normal = 0.0;
  Eigen::Vector3d warm_tangent = Eigen::Vector3d::Zero();
  // Out: the accumulated impulses.
  double normal_impulse = 0.0;
  Eigen::Vector3d tangent_impulse = Eigen::Vector3d::Zero();
};

// Projected Gauss–Seidel ("sequential impulses") over the contacts of an
// island: normal impulses ≥ 0 bring each contact's normal relative velocity
// up to its target, friction impulses stay inside the Coulomb disc
// |P_t| ≤ μ P_n (static while inside, kinetic on its rim).  Deterministic:
// contacts in the given order, from their warm start, a fixed number of
// sweeps or until the largest impulse change is below `tolerance` (an
// impulse).  Where the sweeps stall (a stack), the island is solved at once
// by Newton's method in the bodies' velocities, friction cone included, and
// the sweeps go on from there; an island that slides (where that step does
// not apply) gets a few dozen sweeps more at most (contact_solver.cc),
// unless it is `settled` (every body in it moving no faster than resting
// contact hops): then its sweeps go on to `max_sweeps` or the tolerance.
// Returns the sweeps taken.
int SolveContacts(std::vector<BodyState>& bodies, std::vector<SolverContact>& contacts,
                  int max_sweeps, double tolerance, bool settled = false);

}  // namespace asgard::collide
