// Boundary edges of a triangle mesh: edges used by exactly one cell, oriented as in that cell
// (counter-clockwise cells give a counter-clockwise outline, outward normal on the right).
#pragma once

#include <vector>

#include "engine/core/types.hpp"

namespace loom {

struct BoundaryEdge {
  Index a, b;   // corner nodes, in the cell's orientation
  Index cell;   // the cell the edge belongs to
  int side;     // local side: corners (side, side+1 mod 3)
};

// `connectivity` holds `stride` nodes per cell, the first three being the corners.
std::vector<BoundaryEdge> boundary_edges(const std::vector<Index>& connectivity, int stride);

}  // namespace loom
