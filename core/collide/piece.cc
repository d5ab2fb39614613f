// Convex pieces: construction and support mapping.
//
// Design
// ------
// A piece is either a sphere (centre + radius) or a convex polytope (hull
// vertices + CCW faces).  Distance queries treat a sphere as its centre (the
// "core") and add the radius afterwards, so the support mapping used by GJK
// works on cores: SupportIndex returns a vertex index (0 for a sphere), which
// GJK stores in its cache and re-evaluates at new poses without searching.
//
// Support search:
//   * up to kBruteForceVertices vertices: a linear scan, strict '>' so the
//     lowest index wins ties.  Exact, branch-light, and independent of the
//     starting vertex (so cold and warm queries agree on ties).
//   * larger polytopes: steepest-ascent hill climbing over the vertex
//     adjacency graph (edges of the faces) starting at `hint`.  On a convex
//     polytope a vertex with no better neighbour maximises the linear
//     function, and strict improvement guarantees termination.  Neighbour
//     lists are sorted, so the walk is deterministic.
//
// Rejected alternatives:
//   * Dobkin–Kirkpatrick hierarchies: O(log n) support, but far more code
//     than the few dozen vertices Asgard's shapes have justify.
//   * Keeping qhull's normals: the factory takes only vertices and faces,
//     and Newell's normal of the polygon is exact for planar faces and
//     well-defined for slightly non-planar ones.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/collide/collide.h"

namespace asgard::collide {
namespace {

constexpr size_t kBruteForceVertices = 32;

}  // namespace

Piece Piece::Sphere(const Eigen::Vector3d& center, double radius) {
  Piece piece;
  piece.is_sphere = true;
  piece.center = center;
  piece.radius = radius;
  piece.bound_radius = center.norm() + radius;
  return piece;
}

Piece Piece::Polytope(std::vector<Eigen::Vector3d> vertices, std::vector<std::vector<int>> faces) {
  if (vertices.empty()) throw std::invalid_argument("collide::Piece::Polytope: no vertices");
  const int n = static_cast<int>(vertices.size());
  Piece piece;
  piece.is_sphere = false;
  piece.vertices = std::move(vertices);
  piece.faces = std::move(faces);
  piece.neighbors.assign(static_cast<size_t>(n), {});
  piece.normals.reserve(piece.faces.size());
  for (const std::vector<int>& face : piece.faces) {
    for (int index : face) {
      if (index < 0 || index >= n) {
        throw std::invalid_argument("collide::Piece::Polytope: face index " +
                                    std::to_string(index) + " out of range");
      }
    }
    // Newell's normal: exact for planar polygons, averaged otherwise.
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    const size_t m = face.size();
    for (size_t i = 0; i < m; ++i) {
      const Eigen::Vector3d& p = piece.vertices[static_cast<size_t>(face[i])];
      const Eigen::Vector3d& q = piece.vertices[static_cast<size_t>(face[(i + 1) % m])];
      normal += p.cross(q);
    }
    const double length = normal.norm();
    piece.normals.push_back(length > 0.0 ? Eigen::Vector3d(normal / length)
                                         : Eigen::Vector3d::Zero());
    for (size_t i = 0; i < m; ++i) {
      const int p = face[i];
      const int q = face[(i + 1) % m];
      if (p == q) continue;
      piece.neighbors[static_cast<size_t>(p)].push_back(q);
      piece.neighbors[static_cast<size_t>(q)].push_back(p);
    }
  }
  for (std::vector<int>& list : piece.neighbors) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  double bound = 0.0;
  for (const Eigen::Vector3d& v : piece.vertices) bound = std::max(bound, v.norm());
  piece.bound_radius = bound;
  return piece;
}

int Piece::SupportIndex(const Eigen::Vector3d& d, int hint) const {
  if (is_sphere) return 0;
  const size_t n = vertices.size();
  if (n <= kBruteForceVertices || faces.empty()) {
    int best = 0;
    double best_dot = vertices[0].dot(d);
    for (size_t i = 1; i < n; ++i) {
      const double dot = vertices[i].dot(d);
      if (dot > best_dot) {
        best_dot = dot;
        best = static_cast<int>(i);
      }
    }
    return best;
  }
  int current = (hint >= 0 && static_cast<size_t>(hint) < n) ? hint : 0;
  double current_dot = vertices[static_cast<size_t>(current)].dot(d);
  // Each move strictly increases the dot product, so no vertex repeats and
  // the walk ends after at most n moves.
  for (size_t step = 0; step < n; ++step) {
    int next = current;
    double next_dot = current_dot;
    for (int neighbor : neighbors[static_cast<size_t>(current)]) {
      const double dot = vertices[static_cast<size_t>(neighbor)].dot(d);
      if (dot > next_dot) {
        next_dot = dot;
        next = neighbor;
      }
    }
    if (next == current) break;
    current = next;
    current_dot = next_dot;
  }
  return current;
}

Eigen::Vector3d Piece::Support(const Eigen::Vector3d& d) const {
  if (is_sphere) {
    const double length = d.norm();
    if (!(length > 0.0)) return center;
    return center + (radius / length) * d;
  }
  return vertices[static_cast<size_t>(SupportIndex(d, 0))];
}

}  // namespace asgard::collide
