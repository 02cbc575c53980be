// Boundary edges of a triangle or quadrilateral mesh: edges used by exactly one cell, oriented as in that cell
// (counter-clockwise cells give a counter-clockwise outline, outward normal on the right).
#pragma once

#include <vector>

#include "engine/core/types.hpp"

namespace loom {

struct BoundaryEdge {
  Index a, b;   // corner nodes, in the cell's orientation
  Index cell;   // the cell the edge belongs to
  int side;     // local side: corners (side, side + 1 mod corners); its mid-node, if any, is node corners + side
};

// `connectivity` holds `stride` nodes per cell, the corners first (three for stride 3 and 6, four for 4 and 9).
std::vector<BoundaryEdge> boundary_edges(const std::vector<Index>& connectivity, int stride);

}  // namespace loom
