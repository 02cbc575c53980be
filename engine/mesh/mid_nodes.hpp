// Quadratic triangles from linear ones: one mid-node per edge, at the edge's midpoint (seed 000 §4.1:
// mid-nodes are created on straight edges). Connectivity follows VTK's quadratic triangle: corners
// c0 c1 c2, then the mid-nodes of edges (c0,c1), (c1,c2), (c2,c0).
#pragma once

#include <vector>

#include "engine/core/types.hpp"

namespace loom {

// Appends the mid-nodes to X (numbered in order of first use, cell by cell) and returns the six-node
// connectivity of every triangle of `tri3` (3 nodes per triangle).
std::vector<Index> add_mid_nodes(std::vector<Vec2>& X, const std::vector<Index>& tri3);

}  // namespace loom
