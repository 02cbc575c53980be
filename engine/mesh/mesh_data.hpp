// A mesh as a builder produces it, before it is loaded into stores: coordinates and tri3 connectivity.
#pragma once

#include <vector>

#include "engine/core/types.hpp"

namespace loom {

struct MeshData {
  std::vector<Vec2> X;         // node coordinates
  std::vector<Index> triangles;  // 3 node indices per triangle, counter-clockwise
  Index n_triangles() const { return Index(triangles.size() / 3); }
};

}  // namespace loom
