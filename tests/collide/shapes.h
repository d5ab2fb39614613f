// Test helpers: pieces from hulls, random rotations, and brute-force
// reference distances over hull features.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/collide/collide.h"
#include "core/geometry/geometry.h"

namespace asgard::collide::testing {

inline Piece PieceFromHull(const geometry::ConvexHull& hull) {
  std::vector<std::vector<int>> faces;
  for (const geometry::HullFace& f : hull.faces) faces.push_back(f.vertices);
  return Piece::Polytope(hull.vertices, faces);
}

inline Piece Box(const Eigen::Vector3d& half) {
  std::vector<Eigen::Vector3d> corners;
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                         (i & 4) ? half.z() : -half.z());
  }
  return PieceFromHull(geometry::ComputeHull(corners));
}

inline geometry::ConvexHull RandomHull(std::mt19937_64& rng, int points, double size) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.2, 1.0);
  std::vector<Eigen::Vector3d> p;
  const Eigen::Vector3d axes(uniform(rng), uniform(rng), uniform(rng));
  for (int i = 0; i < points; ++i) {
    Eigen::Vector3d x(normal(rng), normal(rng), normal(rng));
    x = x.normalized() * std::cbrt(uniform(rng));
    p.push_back(size * axes.cwiseProduct(x));
  }
  return geometry::ComputeHull(p);
}

inline Eigen::Matrix3d RandomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  return q.normalized().toRotationMatrix();
}

inline Pose MakePose(const Eigen::Vector3d& p, const Eigen::Matrix3d& R) {
  Pose pose;
  pose.p = p;
  pose.R = R;
  return pose;
}

inline double PointSegment(const Eigen::Vector3d& x, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  double t = len2 > 0.0 ? (x - a).dot(ab) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return (a + t * ab - x).norm();
}

// Minimum over the interior stationary point (if inside the triangle) and the
// three edges.
inline double PointTriangle(const Eigen::Vector3d& x, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  double best = std::min({PointSegment(x, a, b), PointSegment(x, b, c), PointSegment(x, c, a)});
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double nn = n.squaredNorm();
  if (nn > 0.0) {
    const Eigen::Vector3d p = x - n * ((x - a).dot(n) / nn);
    const double u = (b - p).cross(c - p).dot(n);
    const double v = (c - p).cross(a - p).dot(n);
    const double w = (a - p).cross(b - p).dot(n);
    if (u >= 0.0 && v >= 0.0 && w >= 0.0) best = std::min(best, (x - p).norm());
  }
  return best;
}

// Minimum over the interior stationary point (if inside the unit square) and
// the four end point–segment distances.
inline double SegmentSegment(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                             const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
  double best = std::min({PointSegment(p0, q0, q1), PointSegment(p1, q0, q1),
                          PointSegment(q0, p0, p1), PointSegment(q1, p0, p1)});
  const Eigen::Vector3d d1 = p1 - p0;
  const Eigen::Vector3d d2 = q1 - q0;
  const Eigen::Vector3d r = p0 - q0;
  const double a = d1.dot(d1), b = d1.dot(d2), c = d2.dot(d2), d = d1.dot(r), e = d2.dot(r);
  const double den = a * c - b * b;
  if (den > 1e-14 * a * c) {
    const double s = (b * e - c * d) / den;
    const double t = (a * e - b * d) / den;
    if (s >= 0.0 && s <= 1.0 && t >= 0.0 && t <= 1.0) {
      best = std::min(best, (p0 + s * d1 - q0 - t * d2).norm());
    }
  }
  return best;
}

inline std::vector<Eigen::Vector3d> WorldVertices(const geometry::ConvexHull& h, const Pose& p) {
  std::vector<Eigen::Vector3d> out;
  for (const Eigen::Vector3d& v : h.vertices) out.push_back(p.p + p.R * v);
  return out;
}

// Distance between disjoint convex polytopes over all feature pairs.
inline double BruteForceDistance(const geometry::ConvexHull& ha, const Pose& pa,
                                 const geometry::ConvexHull& hb, const Pose& pb) {
  const auto va = WorldVertices(ha, pa);
  const auto vb = WorldVertices(hb, pb);
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : hb.triangles) {
    for (const auto& x : va) best = std::min(best, PointTriangle(x, vb[t[0]], vb[t[1]], vb[t[2]]));
  }
  for (const auto& t : ha.triangles) {
    for (const auto& x : vb) best = std::min(best, PointTriangle(x, va[t[0]], va[t[1]], va[t[2]]));
  }
  for (const auto& s : ha.triangles) {
    for (const auto& t : hb.triangles) {
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          best = std::min(
              best, SegmentSegment(va[s[i]], va[s[(i + 1) % 3]], vb[t[j]], vb[t[(j + 1) % 3]]));
        }
      }
    }
  }
  return best;
}

// Separating-axis penetration: the smallest overlap of the projections over
// face normals and edge cross products (negative when separated).  For convex
// polytopes this is the translational penetration depth.
inline double SatPenetration(const geometry::ConvexHull& ha, const Pose& pa,
                             const geometry::ConvexHull& hb, const Pose& pb) {
  const auto va = WorldVertices(ha, pa);
  const auto vb = WorldVertices(hb, pb);
  std::vector<Eigen::Vector3d> axes;
  for (const auto& f : ha.faces) axes.push_back(pa.R * f.normal);
  for (const auto& f : hb.faces) axes.push_back(pb.R * f.normal);
  auto edges = [](const geometry::ConvexHull& h, const std::vector<Eigen::Vector3d>& v) {
    std::vector<Eigen::Vector3d> e;
    for (const auto& f : h.faces) {
      for (size_t i = 0; i < f.vertices.size(); ++i) {
        e.push_back(v[f.vertices[(i + 1) % f.vertices.size()]] - v[f.vertices[i]]);
      }
    }
    return e;
  };
  for (const auto& ea : edges(ha, va)) {
    for (const auto& eb : edges(hb, vb)) {
      const Eigen::Vector3d n = ea.cross(eb);
      if (n.norm() > 1e-9 * ea.norm() * eb.norm()) axes.push_back(n.normalized());
    }
  }
  double depth = std::numeric_limits<double>::infinity();
  for (const auto& n : axes) {
    double amin = 1e300, amax = -1e300, bmin = 1e300, bmax = -1e300;
    for (const auto& x : va) amin = std::min(amin, n.dot(x)), amax = std::max(amax, n.dot(x));
    for (const auto& x : vb) bmin = std::min(bmin, n.dot(x)), bmax = std::max(bmax, n.dot(x));
    depth = std::min(depth, std::min(amax - bmin, bmax - amin));
  }
  return depth;
}

}  // namespace asgard::collide::testing
