// The closed loops of a boundary polygon (the edges of a mesh used by one triangle, counter-clockwise around the
// body and clockwise around holes) and how far apart two of its points are along it. The free-surface remesh
// (remesh.hpp, SurfaceMode::constrained) uses it to tell two surfaces that meet (a fold closing, a falling column
// reaching a layer: their points are close to each other but far apart along the boundary, or on different loops)
// from the points of one concave stretch of surface (neighbours along it, or a bend), which must not be joined.
#pragma once

#include <vector>

#include "engine/core/types.hpp"
#include "systems/remesh/remesh_types.hpp"

namespace loom {

struct BoundaryLoops {
  std::vector<Index> loop;      // per point: its loop, kNoIndex for a point on none
  std::vector<Index> position;  // per point: its index along the loop (of its first visit at a pinch point)
  std::vector<double> arc;      // per point: the boundary length from the loop's start to it (with positions)
  std::vector<Index> length;    // per loop: its number of edges
  std::vector<double> perimeter;  // per loop: its length (with positions)
};

// Walks the loops of `boundary` (a pinch point, where two loops touch, joins them into one walk). With `x` (one
// position per point) the lengths along the loops are measured too.
BoundaryLoops boundary_loops(Index n_points, const std::vector<Edge>& boundary, const std::vector<Vec2>* x = nullptr);

// Number of boundary edges between a and b along their loop (the shorter way round); kNoIndex when they are on
// different loops or either is on none.
Index steps_along(const BoundaryLoops& loops, Index a, Index b);

// Length of the boundary between a and b along their loop (the shorter way round); infinity when they are on
// different loops or either is on none. Needs the loops measured with positions.
double length_along(const BoundaryLoops& loops, Index a, Index b);

}  // namespace loom
