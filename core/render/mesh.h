// Triangle meshes of body pieces, for the shaded renderer and the exporters.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <vector>

#include "core/render/sampler.h"

namespace asgard::render {

struct Mesh {
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3f> normals;
  std::vector<uint32_t> indices;  // triangles, counter-clockwise from outside
};

// Hulls are flat shaded (each face gets its own vertices with the face
// normal); spheres are latitude–longitude grids with `slices` segments around
// and slices/2 from pole to pole, smooth normals.
Mesh PieceMesh(const Piece& piece, int slices = 32);

}  // namespace asgard::render
