// Distance between convex pieces: GJK with a signed-volume sub-simplex solver.
//
// Design
// ------
// GJK works on the Minkowski difference C = A − B of the pieces' cores (a
// sphere's core is its centre, seed 5.3.1): the distance is min |w| over
// w ∈ C.  Each iteration asks for the support point w = s_C(−v) of C in the
// direction opposite to the current closest point v of the simplex, adds it,
// and replaces the simplex by the smallest face containing the new closest
// point.  The lower bound v·w / |v| and the upper bound |v| on the distance
// close in from both sides; the loop stops when their gap is below
// kGapTolerance × scale (scale = largest |w| met, i.e. the size of the
// configuration), when the new support vertex is already in the simplex (no
// further progress is possible with exact vertices), when |v| stops
// decreasing (rounding), or after kMaxIterations.
//
// Sub-simplex solver: signed volumes.  For a segment the barycentric
// coordinates are computed directly from dot products with each end point
// (not as 1 − μ, which loses the small coordinate).  For a triangle the
// origin is projected onto its plane and the signed areas of the three
// sub-triangles are taken in the coordinate plane where the triangle's
// projection is largest; for a tetrahedron the signed volumes with one
// vertex replaced by the origin.  When every sign agrees with the whole the
// origin's projection is inside and the ratios are the barycentric
// coordinates; otherwise only faces opposite a disagreeing vertex can hold
// the closest point, and the best of those is taken recursively.  Degenerate
// (zero area / zero volume) simplices fall through to all their faces, so
// coincident points, parallel edges and face–face contact give finite
// answers.
//
// Warm start: the cache keeps the support index pairs of the final simplex.
// The next query rebuilds that simplex at the new poses (no search), solves
// it, and usually needs a single support query to certify the result, which
// is the point of seed 5.3.1's "aggressive use of prior results".
//
// Overlap: when |v| reaches zero (or the simplex is a tetrahedron holding the
// origin) the pieces touch or intersect and the distance is 0.  The normal is
// then the direction of least penetration among the face normals of both
// pieces, the direction of the last non-zero v and the line of centres — a
// cheap estimate (no EPA), which is what a contact that the time-of-impact
// search lands just before (distance > 0) never needs.
//
// Rejected alternatives:
//   * Lin–Canny closest features (the seed's method): needs a separate
//     Voronoi-region walk per feature type and a special path for
//     intersection; GJK with a cached simplex gives the same coherence.
//   * Johnson's original recursive determinants: numerically fragile for
//     nearly degenerate simplices (van den Bergen's backup procedure exists
//     because of it).  Signed volumes need no backup procedure.
//   * EPA for penetration depth: not needed by the solver, which stops
//     before contact.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/collide/collide.h"

namespace asgard::collide {
namespace {

constexpr int kMaxIterations = 64;
constexpr double kGapTolerance = 1e-12;   // relative to the configuration size
constexpr double kZeroTolerance = 1e-12;  // |v| below this × scale is contact

struct SupportVertex {
  Eigen::Vector3d w;  // a − b
  Eigen::Vector3d a;  // core point of a, world
  Eigen::Vector3d b;  // core point of b, world
  int ia = 0;
  int ib = 0;
};

// A sub-simplex: indices into the parent simplex and barycentric weights.
struct Sub {
  int n = 0;
  std::array<int, 4> index{};
  std::array<double, 4> lambda{};
};

using Points = std::array<Eigen::Vector3d, 4>;

Eigen::Vector3d Combine(const Sub& sub, const Points& w) {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (int k = 0; k < sub.n; ++k)
    v += sub.lambda[static_cast<size_t>(k)] *
         w[static_cast<size_t>(sub.index[static_cast<size_t>(k)])];
  return v;
}

bool SameSign(double x, double y) { return (x > 0.0 && y > 0.0) || (x < 0.0 && y < 0.0); }

Sub Single(int i) {
  Sub s;
  s.n = 1;
  s.index[0] = i;
  s.lambda[0] = 1.0;
  return s;
}

// Keeps the candidate with the smallest |v|; the first wins ties.
struct Best {
  Sub sub;
  double norm2 = std::numeric_limits<double>::infinity();
  void Consider(const Sub& candidate, const Points& w) {
    const double n2 = Combine(candidate, w).squaredNorm();
    if (n2 < norm2) {
      norm2 = n2;
      sub = candidate;
    }
  }
};

Sub SolveSegment(const Points& w, int i, int j) {
  const Eigen::Vector3d& p = w[static_cast<size_t>(i)];
  const Eigen::Vector3d& q = w[static_cast<size_t>(j)];
  const Eigen::Vector3d t = q - p;
  const double tt = t.squaredNorm();
  if (!(tt > 0.0)) return Single(i);
  const double li = q.dot(t);   // λ_i · |t|²
  const double lj = -p.dot(t);  // λ_j · |t|²
  if (lj <= 0.0) return Single(i);
  if (li <= 0.0) return Single(j);
  Sub s;
  s.n = 2;
  s.index = {i, j, 0, 0};
  s.lambda = {li / tt, lj / tt, 0.0, 0.0};
  return s;
}

Sub SolveTriangle(const Points& w, int i, int j, int k) {
  const Eigen::Vector3d& p0 = w[static_cast<size_t>(i)];
  const Eigen::Vector3d& p1 = w[static_cast<size_t>(j)];
  const Eigen::Vector3d& p2 = w[static_cast<size_t>(k)];
  const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0);
  const double nn = n.squaredNorm();
  Best best;
  if (nn > 0.0) {
    const Eigen::Vector3d o = n * (n.dot(p0) / nn);  // origin projected on the plane
    int axis = 0;
    n.cwiseAbs().maxCoeff(&axis);
    const int a = (axis + 1) % 3;
    const int b = (axis + 2) % 3;
    auto area = [a, b](const Eigen::Vector3d& x, const Eigen::Vector3d& y,
                       const Eigen::Vector3d& z) {
      return (y[a] - x[a]) * (z[b] - x[b]) - (y[b] - x[b]) * (z[a] - x[a]);
    };
    const double nu = area(p0, p1, p2);
    const double c0 = area(o, p1, p2);
    const double c1 = area(p0, o, p2);
    const double c2 = area(p0, p1, o);
    if (SameSign(c0, nu) && SameSign(c1, nu) && SameSign(c2, nu)) {
      Sub s;
      s.n = 3;
      s.index = {i, j, k, 0};
      s.lambda = {c0 / nu, c1 / nu, c2 / nu, 0.0};
      return s;
    }
    if (!SameSign(c0, nu)) best.Consider(SolveSegment(w, j, k), w);
    if (!SameSign(c1, nu)) best.Consider(SolveSegment(w, i, k), w);
    if (!SameSign(c2, nu)) best.Consider(SolveSegment(w, i, j), w);
    return best.sub;
  }
  best.Consider(SolveSegment(w, j, k), w);
  best.Consider(SolveSegment(w, i, k), w);
  best.Consider(SolveSegment(w, i, j), w);
  return best.sub;
}

double Volume(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
              const Eigen::Vector3d& d) {
  return (b - a).dot((c - a).cross(d - a));
}

Sub SolveTetrahedron(const Points& w) {
  const Eigen::Vector3d z = Eigen::Vector3d::Zero();
  const double det = Volume(w[0], w[1], w[2], w[3]);
  const std::array<double, 4> c = {Volume(z, w[1], w[2], w[3]), Volume(w[0], z, w[2], w[3]),
                                   Volume(w[0], w[1], z, w[3]), Volume(w[0], w[1], w[2], z)};
  if (SameSign(c[0], det) && SameSign(c[1], det) && SameSign(c[2], det) && SameSign(c[3], det)) {
    Sub s;
    s.n = 4;
    s.index = {0, 1, 2, 3};
    s.lambda = {c[0] / det, c[1] / det, c[2] / det, c[3] / det};
    return s;
  }
  Best best;
  if (!SameSign(c[0], det)) best.Consider(SolveTriangle(w, 1, 2, 3), w);
  if (!SameSign(c[1], det)) best.Consider(SolveTriangle(w, 0, 2, 3), w);
  if (!SameSign(c[2], det)) best.Consider(SolveTriangle(w, 0, 1, 3), w);
  if (!SameSign(c[3], det)) best.Consider(SolveTriangle(w, 0, 1, 2), w);
  return best.sub;
}

struct Simplex {
  std::array<SupportVertex, 4> vertex;
  std::array<double, 4> lambda{};
  int n = 0;

  // The sub-simplex closest to the origin of the simplex with `extra`
  // appended (null: the simplex itself), its points in `w`; not applied.
  Sub Solve(const SupportVertex* extra, Points& w) const {
    for (int k = 0; k < n; ++k) w[static_cast<size_t>(k)] = vertex[static_cast<size_t>(k)].w;
    const int m = extra != nullptr ? n + 1 : n;
    if (extra != nullptr) w[static_cast<size_t>(n)] = extra->w;
    switch (m) {
      case 1:
        return Single(0);
      case 2:
        return SolveSegment(w, 0, 1);
      case 3:
        return SolveTriangle(w, 0, 1, 2);
      default:
        return SolveTetrahedron(w);
    }
  }
  // The closest point of a solved sub-simplex (Closest once it is applied).
  static Eigen::Vector3d ClosestOf(const Sub& sub, const Points& w) {
    return sub.n == 4 ? Eigen::Vector3d::Zero() : Combine(sub, w);
  }
  // Keeps the sub-simplex `sub` of the simplex with `extra` appended.
  void Apply(const Sub& sub, const SupportVertex* extra) {
    std::array<SupportVertex, 4> kept;
    for (int k = 0; k < sub.n; ++k) {
      const int i = sub.index[static_cast<size_t>(k)];
      kept[static_cast<size_t>(k)] = i == n ? *extra : vertex[static_cast<size_t>(i)];
      lambda[static_cast<size_t>(k)] = sub.lambda[static_cast<size_t>(k)];
    }
    vertex = kept;
    n = sub.n;
  }
  // Replaces the simplex by its sub-simplex closest to the origin; returns v.
  Eigen::Vector3d Reduce() {
    Points w;
    Apply(Solve(nullptr, w), nullptr);
    return Closest();
  }
  Eigen::Vector3d Closest() const {
    if (n == 4) return Eigen::Vector3d::Zero();
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k)
      v += lambda[static_cast<size_t>(k)] * vertex[static_cast<size_t>(k)].w;
    return v;
  }
  Eigen::Vector3d PointA() const {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k)
      p += lambda[static_cast<size_t>(k)] * vertex[static_cast<size_t>(k)].a;
    return p;
  }
  Eigen::Vector3d PointB() const {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k)
      p += lambda[static_cast<size_t>(k)] * vertex[static_cast<size_t>(k)].b;
    return p;
  }
  bool Contains(int ia, int ib) const {
    for (int k = 0; k < n; ++k) {
      if (vertex[static_cast<size_t>(k)].ia == ia && vertex[static_cast<size_t>(k)].ib == ib)
        return true;
    }
    return false;
  }
};

bool ValidIndex(const Piece& piece, int index) {
  if (piece.is_sphere) return index == 0;
  return index >= 0 && static_cast<size_t>(index) < piece.vertices.size();
}

// Largest value of dir·x over the piece (radius included), world frame.
double Extent(const Piece& piece, const Pose& pose, const Eigen::Vector3d& dir) {
  const Eigen::Vector3d body = pose.R.transpose() * dir;
  const Eigen::Vector3d& core = piece.CorePoint(piece.SupportIndex(body, 0));
  return dir.dot(pose.p + pose.R * core) + piece.CoreRadius() * dir.norm();
}

class Gjk {
 public:
  Gjk(const Piece& a, const Pose& pa, const Piece& b, const Pose& pb)
      : a_(a), pa_(pa), b_(b), pb_(pb), rat_(pa.R.transpose()), rbt_(pb.R.transpose()) {}

  SupportVertex Vertex(int ia, int ib) const {
    SupportVertex s;
    s.ia = ia;
    s.ib = ib;
    s.a = pa_.p + pa_.R * a_.CorePoint(ia);
    s.b = pb_.p + pb_.R * b_.CorePoint(ib);
    s.w = s.a - s.b;
    return s;
  }

  // Support of A − B in direction d.
  SupportVertex Support(const Eigen::Vector3d& d) {
    hint_a_ = a_.SupportIndex(rat_ * d, hint_a_);
    hint_b_ = b_.SupportIndex(-(rbt_ * d), hint_b_);
    return Vertex(hint_a_, hint_b_);
  }

  void SetHints(int ia, int ib) {
    hint_a_ = ia;
    hint_b_ = ib;
  }

 private:
  const Piece& a_;
  const Pose& pa_;
  const Piece& b_;
  const Pose& pb_;
  Eigen::Matrix3d rat_, rbt_;
  int hint_a_ = 0;
  int hint_b_ = 0;
};

// Direction (from a to b) of least penetration among a few candidates.
Eigen::Vector3d OverlapNormal(const Piece& a, const Pose& pa, const Piece& b, const Pose& pb,
                              const Eigen::Vector3d& hint) {
  Eigen::Vector3d best_dir = Eigen::Vector3d::UnitX();
  double best_depth = std::numeric_limits<double>::infinity();
  auto consider = [&](const Eigen::Vector3d& dir) {
    const double length = dir.norm();
    if (!(length > 0.0) || !std::isfinite(length)) return;
    const Eigen::Vector3d n = dir / length;
    const double depth = Extent(a, pa, n) + Extent(b, pb, -n);
    if (depth < best_depth) {
      best_depth = depth;
      best_dir = n;
    }
  };
  consider(hint);
  for (const Eigen::Vector3d& n : a.normals) consider(pa.R * n);
  for (const Eigen::Vector3d& n : b.normals) consider(-(pb.R * n));
  consider((pb.p + pb.R * b.CorePoint(0)) - (pa.p + pa.R * a.CorePoint(0)));
  return best_dir;
}

DistanceResult SphereSphere(const Piece& a, const Pose& pa, const Piece& b, const Pose& pb,
                            DistanceCache* cache) {
  DistanceResult r;
  r.iterations = 1;
  const Eigen::Vector3d ca = pa.p + pa.R * a.center;
  const Eigen::Vector3d cb = pb.p + pb.R * b.center;
  const Eigen::Vector3d delta = cb - ca;
  const double d = delta.norm();
  r.normal = d > 0.0 ? Eigen::Vector3d(delta / d) : Eigen::Vector3d::UnitX();
  const double gap = d - a.radius - b.radius;
  const double scale = d + a.radius + b.radius;
  r.point_a = ca + a.radius * r.normal;
  r.point_b = cb - b.radius * r.normal;
  if (gap > kZeroTolerance * scale) {
    r.distance = gap;
  } else {
    r.distance = 0.0;
    r.overlapping = true;
  }
  if (cache != nullptr) {
    cache->count = 1;
    cache->simplex[0] = {0, 0};
    if (d > 0.0) cache->last_direction = -delta;
    cache->valid = true;
  }
  return r;
}

}  // namespace

DistanceResult Distance(const Piece& a, const Pose& pa, const Piece& b, const Pose& pb,
                        DistanceCache* cache) {
  if (a.is_sphere && b.is_sphere) return SphereSphere(a, pa, b, pb, cache);
  Gjk gjk(a, pa, b, pb);
  Simplex s;
  int iterations = 0;
  bool warm = false;
  if (cache != nullptr && cache->valid && cache->count >= 1 && cache->count <= 4) {
    warm = true;
    for (int k = 0; k < cache->count; ++k) {
      const auto& [ia, ib] = cache->simplex[static_cast<size_t>(k)];
      if (!ValidIndex(a, ia) || !ValidIndex(b, ib) || s.Contains(ia, ib)) {
        warm = false;
        break;
      }
      s.vertex[static_cast<size_t>(s.n++)] = gjk.Vertex(ia, ib);
    }
    if (warm) gjk.SetHints(cache->simplex[0].first, cache->simplex[0].second);
  }
  if (!warm) {
    s.n = 0;
    Eigen::Vector3d d = (pb.p + pb.R * b.CorePoint(0)) - (pa.p + pa.R * a.CorePoint(0));
    if (!(d.squaredNorm() > 0.0)) d = Eigen::Vector3d::UnitX();
    s.vertex[0] = gjk.Support(d);
    s.n = 1;
    ++iterations;
  }
  double scale = 0.0;
  for (int k = 0; k < s.n; ++k) scale = std::max(scale, s.vertex[static_cast<size_t>(k)].w.norm());
  Eigen::Vector3d v = s.Reduce();
  Eigen::Vector3d last_nonzero = v;
  bool contact = false;
  while (true) {
    const double vv = v.squaredNorm();
    if (vv > 0.0) last_nonzero = v;
    const double zero = kZeroTolerance * scale;
    if (s.n == 4 || vv <= zero * zero) {
      contact = true;
      break;
    }
    if (iterations >= kMaxIterations) break;
    const SupportVertex w = gjk.Support(-v);
    ++iterations;
    scale = std::max(scale, w.w.norm());
    const double gap = vv - v.dot(w.w);  // |v| × (upper − lower bound)
    if (gap <= kGapTolerance * scale * std::sqrt(vv)) break;
    if (s.Contains(w.ia, w.ib)) break;
    // The simplex with w, solved before it replaces this one (kept where
    // there is no progress).
    Points points;
    const Sub sub = s.Solve(&w, points);
    const Eigen::Vector3d v_next = Simplex::ClosestOf(sub, points);
    if (!(v_next.squaredNorm() < vv)) break;  // no progress left in floating point
    s.Apply(sub, &w);
    v = v_next;
  }

  DistanceResult r;
  r.iterations = iterations;
  const double ra = a.CoreRadius();
  const double rb = b.CoreRadius();
  const Eigen::Vector3d core_a = s.PointA();
  const Eigen::Vector3d core_b = s.PointB();
  const double core_distance = contact ? 0.0 : v.norm();
  if (core_distance > 0.0) {
    r.normal = -v / core_distance;
  } else {
    const Eigen::Vector3d hint = -last_nonzero;
    r.normal = OverlapNormal(a, pa, b, pb, hint);
  }
  r.point_a = core_a + ra * r.normal;
  r.point_b = core_b - rb * r.normal;
  const double gap = core_distance - ra - rb;
  if (core_distance > 0.0 && gap > kZeroTolerance * (scale + ra + rb)) {
    r.distance = gap;
  } else {
    r.distance = 0.0;
    r.overlapping = true;
  }
  if (cache != nullptr) {
    cache->count = s.n;
    for (int k = 0; k < s.n; ++k) {
      cache->simplex[static_cast<size_t>(k)] = {s.vertex[static_cast<size_t>(k)].ia,
                                                s.vertex[static_cast<size_t>(k)].ib};
    }
    if (last_nonzero.squaredNorm() > 0.0) cache->last_direction = last_nonzero;
    cache->valid = true;
  }
  return r;
}

}  // namespace asgard::collide
