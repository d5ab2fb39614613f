// Geometry: convex hulls (qhull), mass properties, rotation vectors.
//
// Design
// ------
// ComputeHull runs in four stages:
//   1. Validation, before qhull sees anything: every coordinate must be finite,
//      at least 4 distinct points are needed (exact duplicates are dropped),
//      and the point set must have volume.  Flatness is measured with the
//      principal axes of the points: the largest distance from the best-fit
//      plane (line) is compared with the extent (bounding-box diagonal); below
//      kFlatTolerance × extent the set is reported as coplanar (collinear).
//   2. qhull (reentrant, "qhull Qt") on the distinct points.  qhull reports
//      failures by longjmp-ing back into qh_new_qhull, which then returns a
//      nonzero code; its messages go to an in-memory stream (open_memstream)
//      and are quoted in the GeometryError.
//   3. Faces.  qhull's (triangulated) facets are grouped into planes by a
//      union-find over facet adjacency, joining neighbours whose unit normals
//      agree within kCoplanarNormalTolerance.  qhull's vertex order
//      (toporient) is ignored: each plane's vertices are projected into a
//      2-d frame (u, v) with u × v = n, where n is the plane normal oriented
//      away from the interior (checked against the vertex centroid), and
//      their 2-d convex hull (monotone chain, collinear points dropped) gives
//      the polygon, counter-clockwise seen from outside.  The final normal is
//      Newell's normal of that polygon and the offset the mean of n·x.
//   4. Triangles are fans of the face polygons, so every triangle is
//      counter-clockwise from outside and none is degenerate.  Only vertices
//      used by some face survive; they are renumbered in input order.
//
// Mass properties decompose the hull into tetrahedra (reference point = vertex
// centroid, one tetrahedron per triangle).  For a tetrahedron with the
// reference point at the origin and edge vectors A = [a b c], the second
// moment ∫ x xᵀ dV equals det(A) · A · C₀ · Aᵀ, with C₀ the canonical
// tetrahedron's covariance (1/120)·[[2,1,1],[1,2,1],[1,1,2]].  Summing,
// shifting to the centroid (C − V·x̄x̄ᵀ) and forming I = ρ(tr(C)·𝟙 − C) gives
// the inertia tensor about the centroid.  Combination uses the parallel-axis
// theorem I = Σ Iᵢ + mᵢ(|dᵢ|²𝟙 − dᵢdᵢᵀ).
//
// Rotation vectors use series expansions of sin(θ/2)/θ and atan(s/w)/s when
// the angle is small, so tiny rotations round-trip to full relative precision;
// the returned angle lies in [0, π] (the quaternion is flipped to w ≥ 0).
#include "core/geometry/geometry.h"

#include <libqhull_r/libqhull_r.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <numeric>
#include <sstream>
#include <unordered_map>

namespace asgard::geometry {
namespace {

// A point set is flat when all points lie within this fraction of its extent
// from one plane.
constexpr double kFlatTolerance = 1e-9;
// Adjacent facets whose unit normals differ by less than this are one face.
constexpr double kCoplanarNormalTolerance = 1e-9;
// Polygon vertices within this fraction of the coordinate scale of the line
// through their neighbours are dropped (they lie on an edge).
constexpr double kCollinearTolerance = 1e-10;

std::string FormatPoint(const Eigen::Vector3d& p) {
  std::ostringstream out;
  out.precision(17);
  out << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return out.str();
}

// Captures everything qhull writes to its error stream.
class MemoryStream {
 public:
  MemoryStream() { file_ = open_memstream(&buffer_, &size_); }
  ~MemoryStream() {
    if (file_ != nullptr) std::fclose(file_);
    std::free(buffer_);
  }
  MemoryStream(const MemoryStream&) = delete;
  MemoryStream& operator=(const MemoryStream&) = delete;

  FILE* file() const { return file_; }
  std::string Contents() {
    if (file_ == nullptr) return {};
    std::fflush(file_);
    return buffer_ == nullptr ? std::string() : std::string(buffer_, size_);
  }

 private:
  char* buffer_ = nullptr;
  size_t size_ = 0;
  FILE* file_ = nullptr;
};

// Owns a qhull instance and releases all its memory on scope exit.
class Qhull {
 public:
  explicit Qhull(FILE* errfile) : qh_(std::make_unique<qhT>()) { qh_zero(qh_.get(), errfile); }
  ~Qhull() {
    qh_freeqhull(qh_.get(), !qh_ALL);
    int curlong = 0;
    int totlong = 0;
    qh_memfreeshort(qh_.get(), &curlong, &totlong);
  }
  Qhull(const Qhull&) = delete;
  Qhull& operator=(const Qhull&) = delete;
  qhT* get() { return qh_.get(); }

 private:
  std::unique_ptr<qhT> qh_;
};

// First few lines of qhull's message, for the exception text.
std::string SummarizeQhullMessage(const std::string& message) {
  std::istringstream in(message);
  std::string line;
  std::string summary;
  int lines = 0;
  while (lines < 4 && std::getline(in, line)) {
    if (line.empty()) continue;
    if (!summary.empty()) summary += " ";
    summary += line;
    ++lines;
  }
  return summary.empty() ? std::string("no message") : summary;
}

struct DisjointSets {
  explicit DisjointSets(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int Find(int i) {
    while (parent[i] != i) {
      parent[i] = parent[parent[i]];
      i = parent[i];
    }
    return i;
  }
  void Join(int a, int b) { parent[Find(a)] = Find(b); }
  std::vector<int> parent;
};

// Removes exact duplicates, keeping the first occurrence (input order).
std::vector<Eigen::Vector3d> DistinctPoints(std::span<const Eigen::Vector3d> points) {
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  auto less = [&](int a, int b) {
    const auto& p = points[a];
    const auto& q = points[b];
    if (p.x() != q.x()) return p.x() < q.x();
    if (p.y() != q.y()) return p.y() < q.y();
    if (p.z() != q.z()) return p.z() < q.z();
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<bool> keep(points.size(), false);
  for (size_t k = 0; k < order.size(); ++k) {
    keep[order[k]] = k == 0 || points[order[k]] != points[order[k - 1]];
  }
  std::vector<Eigen::Vector3d> distinct;
  for (size_t i = 0; i < points.size(); ++i) {
    if (keep[i]) distinct.push_back(points[i]);
  }
  return distinct;
}

// Throws unless the (distinct, finite) points span a volume.
void CheckHasVolume(const std::vector<Eigen::Vector3d>& points, double extent) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& p : points) covariance += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  // Eigenvalues ascending: column 0 is the plane normal, column 2 the line.
  const Eigen::Vector3d normal = solver.eigenvectors().col(0);
  const Eigen::Vector3d direction = solver.eigenvectors().col(2);
  double thickness = 0.0;
  double line_distance = 0.0;
  for (const auto& p : points) {
    const Eigen::Vector3d d = p - mean;
    thickness = std::max(thickness, std::abs(normal.dot(d)));
    line_distance = std::max(line_distance, (d - direction.dot(d) * direction).norm());
  }
  const double tolerance = kFlatTolerance * extent;
  if (line_distance <= tolerance) {
    throw GeometryError("points are collinear: a convex piece needs volume (" +
                        std::to_string(points.size()) +
                        " distinct points lie on one line through " + FormatPoint(mean) + ")");
  }
  if (thickness <= tolerance) {
    throw GeometryError("points are coplanar: a convex piece needs volume (" +
                        std::to_string(points.size()) +
                        " distinct points lie in one plane through " + FormatPoint(mean) +
                        " with normal " + FormatPoint(normal) + ")");
  }
}

struct Facet {
  std::array<int, 3> vertices{};
  Eigen::Vector3d normal;
  std::vector<int> neighbors;  // indices into the facet list
};

struct QhullResult {
  std::vector<Facet> facets;
  std::vector<int> vertices;  // indices of hull vertices into the input
};

QhullResult RunQhull(const std::vector<Eigen::Vector3d>& points) {
  std::vector<coordT> coordinates;
  coordinates.reserve(points.size() * 3);
  for (const auto& p : points) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});

  MemoryStream errors;
  FILE* errfile = errors.file();
  if (errfile == nullptr) throw GeometryError("convex hull: cannot open an error stream");
  Qhull qhull(errfile);
  qhT* qh = qhull.get();
  char options[] = "qhull Qt";
  const int code = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(), False,
                                options, nullptr, errfile);
  if (code != 0) {
    throw GeometryError("convex hull failed (qhull error " + std::to_string(code) +
                        "): " + SummarizeQhullMessage(errors.Contents()));
  }

  QhullResult result;
  std::unordered_map<unsigned, int> facet_index;
  for (facetT* facet = qh->facet_list; facet != nullptr && facet->next != nullptr;
       facet = facet->next) {
    if (facet->upperdelaunay || qh_setsize(qh, facet->vertices) != 3) {
      throw GeometryError("convex hull failed: qhull returned a non-triangular facet");
    }
    Facet f;
    for (int k = 0; k < 3; ++k) {
      f.vertices[k] = qh_pointid(qh, SETelemt_(facet->vertices, k, vertexT)->point);
    }
    f.normal = Eigen::Vector3d(facet->normal[0], facet->normal[1], facet->normal[2]);
    facet_index.emplace(facet->id, static_cast<int>(result.facets.size()));
    result.facets.push_back(std::move(f));
  }
  int i = 0;
  for (facetT* facet = qh->facet_list; facet != nullptr && facet->next != nullptr;
       facet = facet->next, ++i) {
    const int count = qh_setsize(qh, facet->neighbors);
    for (int k = 0; k < count; ++k) {
      auto it = facet_index.find(SETelemt_(facet->neighbors, k, facetT)->id);
      if (it != facet_index.end()) result.facets[i].neighbors.push_back(it->second);
    }
  }
  for (vertexT* vertex = qh->vertex_list; vertex != nullptr && vertex->next != nullptr;
       vertex = vertex->next) {
    result.vertices.push_back(qh_pointid(qh, vertex->point));
  }
  if (result.facets.size() < 4) {
    throw GeometryError("convex hull failed: qhull returned fewer than 4 facets");
  }
  return result;
}

// Counter-clockwise convex polygon (indices into `points`) of the coplanar
// points `ids`, seen from the side `normal` points to.  Collinear points on
// edges are dropped.
std::vector<int> PlanarPolygon(const std::vector<Eigen::Vector3d>& points,
                               const std::vector<int>& ids, const Eigen::Vector3d& normal,
                               double length_tolerance) {
  const Eigen::Vector3d u = normal.unitOrthogonal();
  const Eigen::Vector3d v = normal.cross(u);
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  for (int id : ids) origin += points[id];
  origin /= static_cast<double>(ids.size());
  struct Projected {
    double x, y;
    int id;
  };
  std::vector<Projected> projected;
  for (int id : ids) {
    const Eigen::Vector3d d = points[id] - origin;
    projected.push_back({d.dot(u), d.dot(v), id});
  }
  std::sort(projected.begin(), projected.end(), [](const Projected& a, const Projected& b) {
    return a.x != b.x ? a.x < b.x : a.y < b.y;
  });
  // The middle point a is kept only when o → a → b turns counter-clockwise and
  // a lies farther than the tolerance from the line o → b.
  auto turns_left = [&](const Projected& o, const Projected& a, const Projected& b) {
    const double ax = a.x - o.x, ay = a.y - o.y;
    const double bx = b.x - o.x, by = b.y - o.y;
    const double base = std::hypot(bx, by);
    return ax * by - ay * bx > length_tolerance * base;
  };
  std::vector<Projected> hull;
  const size_t n = projected.size();
  hull.reserve(2 * n);
  for (size_t k = 0; k < n; ++k) {  // lower chain
    while (hull.size() >= 2 && !turns_left(hull[hull.size() - 2], hull.back(), projected[k])) {
      hull.pop_back();
    }
    hull.push_back(projected[k]);
  }
  const size_t lower = hull.size() + 1;
  for (size_t k = n - 1; k-- > 0;) {  // upper chain
    while (hull.size() >= lower && !turns_left(hull[hull.size() - 2], hull.back(), projected[k])) {
      hull.pop_back();
    }
    hull.push_back(projected[k]);
  }
  hull.pop_back();  // the first point closes the loop
  std::vector<int> polygon;
  for (const auto& p : hull) polygon.push_back(p.id);
  return polygon;
}

}  // namespace

ConvexHull ComputeHull(std::span<const Eigen::Vector3d> points) {
  for (size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw GeometryError("point " + std::to_string(i) + " has a non-finite coordinate " +
                          FormatPoint(points[i]));
    }
  }
  const std::vector<Eigen::Vector3d> distinct = DistinctPoints(points);
  if (distinct.size() < 4) {
    throw GeometryError("a convex hull needs at least 4 distinct points, got " +
                        std::to_string(distinct.size()) + " (of " + std::to_string(points.size()) +
                        " given)");
  }
  Eigen::Vector3d lo = distinct.front();
  Eigen::Vector3d hi = distinct.front();
  double magnitude = 0.0;
  for (const auto& p : distinct) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    magnitude = std::max(magnitude, p.cwiseAbs().maxCoeff());
  }
  const double extent = (hi - lo).norm();
  CheckHasVolume(distinct, extent);

  const QhullResult qhull = RunQhull(distinct);

  // An interior point: the centroid of qhull's hull vertices.
  Eigen::Vector3d interior = Eigen::Vector3d::Zero();
  for (int id : qhull.vertices) interior += distinct[id];
  interior /= static_cast<double>(qhull.vertices.size());

  // Group adjacent facets with equal normals into planes.
  const int facet_count = static_cast<int>(qhull.facets.size());
  DisjointSets planes(facet_count);
  for (int i = 0; i < facet_count; ++i) {
    for (int j : qhull.facets[i].neighbors) {
      if ((qhull.facets[i].normal - qhull.facets[j].normal).norm() < kCoplanarNormalTolerance) {
        planes.Join(i, j);
      }
    }
  }
  std::unordered_map<int, std::vector<int>> plane_facets;
  std::vector<int> plane_order;  // deterministic: order of first facet
  for (int i = 0; i < facet_count; ++i) {
    auto [it, inserted] = plane_facets.try_emplace(planes.Find(i));
    if (inserted) plane_order.push_back(planes.Find(i));
    it->second.push_back(i);
  }

  const double length_tolerance = kCollinearTolerance * std::max(extent, magnitude);
  std::vector<std::vector<int>> polygons;  // indices into `distinct`
  std::vector<Eigen::Vector3d> normals;
  for (int root : plane_order) {
    const std::vector<int>& members = plane_facets[root];
    std::vector<int> ids;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (int f : members) {
      normal += qhull.facets[f].normal;
      ids.insert(ids.end(), qhull.facets[f].vertices.begin(), qhull.facets[f].vertices.end());
    }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    normal.normalize();
    // Orient away from the interior, whatever qhull's convention.
    Eigen::Vector3d face_center = Eigen::Vector3d::Zero();
    for (int id : ids) face_center += distinct[id];
    face_center /= static_cast<double>(ids.size());
    if (normal.dot(face_center - interior) < 0.0) normal = -normal;
    std::vector<int> polygon = PlanarPolygon(distinct, ids, normal, length_tolerance);
    if (polygon.size() < 3) continue;  // a sliver with no area
    polygons.push_back(std::move(polygon));
    normals.push_back(normal);
  }

  // Keep only vertices used by a face, renumbered in input order.
  std::vector<int> new_index(distinct.size(), -1);
  for (const auto& polygon : polygons) {
    for (int id : polygon) new_index[id] = 0;
  }
  ConvexHull hull;
  for (size_t id = 0; id < distinct.size(); ++id) {
    if (new_index[id] < 0) continue;
    new_index[id] = static_cast<int>(hull.vertices.size());
    hull.vertices.push_back(distinct[id]);
  }

  for (size_t f = 0; f < polygons.size(); ++f) {
    HullFace face;
    for (int id : polygons[f]) face.vertices.push_back(new_index[id]);
    // Newell's normal: exact for planar polygons, independent of qhull's.
    Eigen::Vector3d newell = Eigen::Vector3d::Zero();
    Eigen::Vector3d center = Eigen::Vector3d::Zero();
    const size_t n = face.vertices.size();
    for (size_t k = 0; k < n; ++k) center += hull.vertices[face.vertices[k]];
    center /= static_cast<double>(n);
    for (size_t k = 0; k < n; ++k) {
      const Eigen::Vector3d a = hull.vertices[face.vertices[k]] - center;
      const Eigen::Vector3d b = hull.vertices[face.vertices[(k + 1) % n]] - center;
      newell += a.cross(b);
    }
    face.normal = newell.norm() > 0.0 ? newell.normalized() : normals[f];
    if (face.normal.dot(normals[f]) < 0.0) face.normal = normals[f];  // numerically degenerate
    face.offset = face.normal.dot(center);
    for (size_t k = 1; k + 1 < n; ++k) {
      hull.triangles.push_back({face.vertices[0], face.vertices[k], face.vertices[k + 1]});
    }
    hull.faces.push_back(std::move(face));
  }
  if (hull.faces.size() < 4) {
    throw GeometryError("convex hull failed: the points are too flat to bound a volume");
  }
  return hull;
}

MassProperties HullMassProperties(const ConvexHull& hull, double density) {
  if (!std::isfinite(density) || density < 0.0) {
    throw GeometryError("density must be finite and non-negative");
  }
  if (hull.vertices.empty() || hull.triangles.empty()) {
    throw GeometryError("mass properties of an empty hull");
  }
  Eigen::Vector3d reference = Eigen::Vector3d::Zero();
  for (const auto& v : hull.vertices) reference += v;
  reference /= static_cast<double>(hull.vertices.size());

  Eigen::Matrix3d canonical;
  canonical << 2, 1, 1, 1, 2, 1, 1, 1, 2;
  canonical /= 120.0;

  double six_volume = 0.0;                           // Σ det(A)
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  // Σ det(A)·(a+b+c)
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  // Σ det(A)·A·C₀·Aᵀ
  for (const auto& t : hull.triangles) {
    Eigen::Matrix3d a;
    a.col(0) = hull.vertices[t[0]] - reference;
    a.col(1) = hull.vertices[t[1]] - reference;
    a.col(2) = hull.vertices[t[2]] - reference;
    const double det = a.determinant();
    six_volume += det;
    moment += det * (a.col(0) + a.col(1) + a.col(2));
    second += det * a * canonical * a.transpose();
  }
  const double volume = six_volume / 6.0;
  if (!(volume > 0.0)) throw GeometryError("hull has no volume (are the triangles outward?)");
  const Eigen::Vector3d offset = moment / (24.0 * volume);  // centroid - reference
  const Eigen::Matrix3d covariance = second - volume * offset * offset.transpose();

  MassProperties result;
  result.volume = volume;
  result.mass = density * volume;
  result.centroid = reference + offset;
  result.inertia = density * (covariance.trace() * Eigen::Matrix3d::Identity() - covariance);
  result.inertia = 0.5 * (result.inertia + result.inertia.transpose()).eval();
  return result;
}

MassProperties SphereMassProperties(const Eigen::Vector3d& center, double radius, double density) {
  if (!center.allFinite()) throw GeometryError("sphere centre is not finite");
  if (!std::isfinite(radius) || radius <= 0.0) {
    throw GeometryError("sphere radius must be positive and finite, got " + std::to_string(radius));
  }
  if (!std::isfinite(density) || density < 0.0) {
    throw GeometryError("density must be finite and non-negative");
  }
  MassProperties result;
  result.volume = 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  result.mass = density * result.volume;
  result.centroid = center;
  result.inertia = Eigen::Matrix3d::Identity() * (0.4 * result.mass * radius * radius);
  return result;
}

MassProperties CombineMassProperties(std::span<const MassProperties> parts) {
  MassProperties result;
  for (const auto& part : parts) {
    result.mass += part.mass;
    result.volume += part.volume;
  }
  // Weight by mass; fall back to volume when everything is massless.
  const bool by_mass = result.mass > 0.0;
  const double total = by_mass ? result.mass : result.volume;
  if (!(total > 0.0)) return result;
  for (const auto& part : parts) {
    result.centroid += (by_mass ? part.mass : part.volume) / total * part.centroid;
  }
  for (const auto& part : parts) {
    const Eigen::Vector3d d = part.centroid - result.centroid;
    result.inertia += part.inertia + part.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() -
                                                  d * d.transpose());
  }
  return result;
}

Eigen::Quaterniond QuaternionFromRotationVector(const Eigen::Vector3d& r) {
  if (!r.allFinite()) throw GeometryError("rotation vector is not finite");
  const double theta2 = r.squaredNorm();
  const double theta = std::sqrt(theta2);
  double w;
  double s;  // sin(θ/2)/θ
  if (theta < 1e-4) {
    // Series: cos(θ/2) = 1 − θ²/8 + θ⁴/384, sin(θ/2)/θ = 1/2 − θ²/48 + θ⁴/3840.
    w = 1.0 - theta2 / 8.0 + theta2 * theta2 / 384.0;
    s = 0.5 - theta2 / 48.0 + theta2 * theta2 / 3840.0;
  } else {
    w = std::cos(0.5 * theta);
    s = std::sin(0.5 * theta) / theta;
  }
  return Eigen::Quaterniond(w, s * r.x(), s * r.y(), s * r.z());
}

Eigen::Vector3d RotationVectorFromQuaternion(const Eigen::Quaterniond& q_in) {
  Eigen::Vector4d c(q_in.w(), q_in.x(), q_in.y(), q_in.z());
  const double norm = c.norm();
  if (!std::isfinite(norm) || norm == 0.0) {
    throw GeometryError("quaternion must be finite and non-zero");
  }
  c /= norm;
  if (c[0] < 0.0) c = -c;  // same rotation, angle in [0, π]
  const double w = c[0];
  const Eigen::Vector3d v = c.tail<3>();
  const double s = v.norm();  // sin(θ/2)
  double scale;               // θ / sin(θ/2)
  if (s < 1e-4) {
    // θ/s = 2·atan(s/w)/s = (2/w)(1 − t²/3 + t⁴/5), t = s/w, w ≈ 1.
    const double t2 = (s / w) * (s / w);
    scale = 2.0 / w * (1.0 - t2 / 3.0 + t2 * t2 / 5.0);
  } else {
    scale = 2.0 * std::atan2(s, w) / s;
  }
  return scale * v;
}

BoundingSphere BoundHull(const ConvexHull& hull) {
  BoundingSphere bound;
  if (hull.vertices.empty()) return bound;
  for (const auto& v : hull.vertices) bound.center += v;
  bound.center /= static_cast<double>(hull.vertices.size());
  for (const auto& v : hull.vertices) {
    bound.radius = std::max(bound.radius, (v - bound.center).norm());
  }
  return bound;
}

}  // namespace asgard::geometry
