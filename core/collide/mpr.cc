// Overlap test and penetration with libccd's Minkowski Portal Refinement
// (test oracle; depth and direction for pushing overlapping bodies apart).
//
// Design
// ------
// libccd calls back with an opaque object pointer and a direction; the object
// here is a piece, its pose and a call counter.  Supports are of the true
// shapes (a sphere includes its radius), centres are the pose of the core's
// mean point.  libccd is built for double precision on Debian (CCD_DOUBLE in
// ccd/config.h); a static_assert checks that ccd_real_t is double so a single
// precision build fails to compile instead of silently losing accuracy.
//
// libccd 2.1's MPR loops (portal discovery and refinement) have no iteration
// limit of their own — ccd_t::max_iterations is only read by GJK/EPA.  The cap
// is enforced in the support callback: once the budget is spent it returns a
// point far behind the search direction, which makes every MPR loop stop at
// its next "origin outside" test, and the answer is reported as untrusted
// (nullopt).  Non-finite poses or shapes are also nullopt.
//
// Rejected alternatives:
//   * ccdGJKIntersect: needs its own tolerance tuning and is a second GJK;
//     the point of this function is an independent check of ours.
//   * longjmp out of the callback: skips libccd's frames safely only by
//     accident of its implementation; the far-point trick uses its public
//     contract.
#include <ccd/ccd.h>

#include <cmath>
#include <type_traits>

#include "core/collide/collide.h"

namespace asgard::collide {
namespace {

static_assert(std::is_same_v<ccd_real_t, double>, "libccd must be built with CCD_DOUBLE");

constexpr unsigned long kMaxIterations = 500;
constexpr double kTolerance = 1e-12;
constexpr double kFar = 1e100;

struct Shape {
  const Piece* piece;
  const Pose* pose;
  Eigen::Vector3d centre;
  mutable unsigned long calls = 0;
  mutable bool exhausted = false;
};

Eigen::Vector3d ToEigen(const ccd_vec3_t* v) { return {ccdVec3X(v), ccdVec3Y(v), ccdVec3Z(v)}; }

void FromEigen(const Eigen::Vector3d& e, ccd_vec3_t* v) { ccdVec3Set(v, e.x(), e.y(), e.z()); }

void SupportFn(const void* object, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const Shape& shape = *static_cast<const Shape*>(object);
  const Eigen::Vector3d d = ToEigen(dir);
  if (++shape.calls > kMaxIterations) {
    shape.exhausted = true;
    // Far behind the direction: libccd then sees the origin outside and stops.
    FromEigen(-kFar * d, out);
    return;
  }
  const Eigen::Vector3d body = shape.pose->R.transpose() * d;
  FromEigen(shape.pose->p + shape.pose->R * shape.piece->Support(body), out);
}

void CentreFn(const void* object, ccd_vec3_t* out) {
  FromEigen(static_cast<const Shape*>(object)->centre, out);
}

Eigen::Vector3d CoreCentre(const Piece& piece, const Pose& pose) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  if (piece.is_sphere) {
    mean = piece.center;
  } else {
    for (const Eigen::Vector3d& v : piece.vertices) mean += v;
    mean /= static_cast<double>(piece.vertices.size());
  }
  return pose.p + pose.R * mean;
}

bool Finite(const Piece& piece, const Pose& pose) {
  if (!pose.p.allFinite() || !pose.R.allFinite()) return false;
  if (piece.is_sphere) return piece.center.allFinite() && std::isfinite(piece.radius);
  if (piece.vertices.empty()) return false;
  for (const Eigen::Vector3d& v : piece.vertices) {
    if (!v.allFinite()) return false;
  }
  return true;
}

ccd_t Config() {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = SupportFn;
  ccd.support2 = SupportFn;
  ccd.center1 = CentreFn;
  ccd.center2 = CentreFn;
  ccd.max_iterations = kMaxIterations;
  ccd.mpr_tolerance = kTolerance;
  return ccd;
}

}  // namespace

std::optional<Penetration> PenetrationMpr(const Piece& a, const Pose& pa, const Piece& b,
                                          const Pose& pb) {
  if (!Finite(a, pa) || !Finite(b, pb)) return std::nullopt;
  Shape sa{&a, &pa, CoreCentre(a, pa)};
  Shape sb{&b, &pb, CoreCentre(b, pb)};
  const ccd_t ccd = Config();
  ccd_real_t depth = 0;
  ccd_vec3_t dir, pos;
  const int result = ccdMPRPenetration(&sa, &sb, &ccd, &depth, &dir, &pos);
  if (sa.exhausted || sb.exhausted || result != 0) return std::nullopt;
  Penetration out;
  out.depth = depth;
  out.normal = ToEigen(&dir);
  out.point = ToEigen(&pos);
  const double length = out.normal.norm();
  if (!std::isfinite(depth) || !(length > 0.0) || !out.point.allFinite()) return std::nullopt;
  out.normal /= length;
  return out;
}

std::optional<bool> OverlapMpr(const Piece& a, const Pose& pa, const Piece& b, const Pose& pb) {
  if (!Finite(a, pa) || !Finite(b, pb)) return std::nullopt;
  Shape sa{&a, &pa, CoreCentre(a, pa)};
  Shape sb{&b, &pb, CoreCentre(b, pb)};
  const ccd_t ccd = Config();
  const int result = ccdMPRIntersect(&sa, &sb, &ccd);
  if (sa.exhausted || sb.exhausted) return std::nullopt;
  return result != 0;
}

}  // namespace asgard::collide
