// Quadratic cells from linear ones: one mid-node per edge, at the edge's midpoint (seed 000 §4.1:
// mid-nodes are created on straight edges). Connectivity follows VTK's quadratic triangle: corners
// c0 c1 c2, then the mid-nodes of edges (c0,c1), (c1,c2), (c2,c0). Quadrilaterals (quad4 -> quad9,
// VTK_BIQUADRATIC_QUAD and seed 004's order): corners, the mid-nodes of (c0,c1) ... (c3,c0), then the centre at
// the mean of the corners -- the centre of the bilinear map, so the quad9 map of a straight-sided cell is that
// bilinear map and affine fields stay in its span.
#pragma once

#include <vector>

#include "engine/core/types.hpp"

namespace loom {

// Appends the mid-nodes to X (numbered in order of first use, cell by cell) and returns the six-node
// connectivity of every triangle of `tri3` (3 nodes per triangle).
std::vector<Index> add_mid_nodes(std::vector<Vec2>& X, const std::vector<Index>& tri3);

// The same for counter-clockwise quadrilaterals (4 corners each): nine nodes per cell, the mid-nodes shared
// between neighbours, then one centre node per cell.
std::vector<Index> add_quad9_nodes(std::vector<Vec2>& X, const std::vector<Index>& quad4);

}  // namespace loom
