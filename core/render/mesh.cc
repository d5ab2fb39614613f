// Tessellation of hull and sphere pieces.
//
// Design: a hull's merged polygon faces are fanned from their first vertex
// (faces are convex), so shading follows the modelled faces rather than
// qhull's internal triangles; spheres use a latitude–longitude grid, which
// gives clean silhouettes at low cost and deterministic vertex order.
#include "core/render/mesh.h"

#include <cmath>

namespace asgard::render {

Mesh PieceMesh(const Piece& piece, int slices) {
  Mesh m;
  if (!piece.is_sphere) {
    for (const auto& hull_face : piece.hull.faces) {
      const auto& face = hull_face.vertices;
      if (face.size() < 3) continue;
      const uint32_t base = static_cast<uint32_t>(m.positions.size());
      for (int v : face) {
        m.positions.push_back(piece.hull.vertices[v].cast<float>());
        m.normals.push_back(hull_face.normal.cast<float>());
      }
      for (uint32_t k = 1; k + 1 < face.size(); ++k) {
        m.indices.push_back(base);
        m.indices.push_back(base + k);
        m.indices.push_back(base + k + 1);
      }
    }
    return m;
  }
  slices = std::max(8, slices);
  const int stacks = slices / 2;
  for (int i = 0; i <= stacks; ++i) {
    const double phi = M_PI * i / stacks;  // from +z (north) to −z
    for (int j = 0; j <= slices; ++j) {
      const double theta = 2 * M_PI * j / slices;
      const Eigen::Vector3d n(std::sin(phi) * std::cos(theta), std::sin(phi) * std::sin(theta),
                              std::cos(phi));
      m.normals.push_back(n.cast<float>());
      m.positions.push_back((piece.center + piece.radius * n).cast<float>());
    }
  }
  const uint32_t row = static_cast<uint32_t>(slices + 1);
  for (int i = 0; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      const uint32_t a = i * row + j, b = a + row, c = b + 1, d = a + 1;
      // Counter-clockwise from outside: a (upper), b (lower), c (lower, next).
      if (i != 0) m.indices.insert(m.indices.end(), {a, b, d});
      if (i != stacks - 1) m.indices.insert(m.indices.end(), {d, b, c});
    }
  }
  return m;
}

}  // namespace asgard::render
