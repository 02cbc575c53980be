// locate (DESIGN §3, seed 003 Algorithm 1 phase 1): finds the background-grid cell holding each point at
// its current position x = X + u, the linear shape functions of the cell's corners there (barycentric
// coordinates; bilinear on quad4 grids), and groups the points by cell. Structured grids are searched by arithmetic; other grids
// by walking from the point's previous cell through the neighbours (bucket index when there is none or
// the walk leaves the grid). A point outside the grid is an anomaly: RunError naming the point.
#pragma once

#include "engine/graph/step_context.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_activity.hpp"
#include "engine/store/grid_layout.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/point_locations.hpp"
#include "engine/store/points.hpp"

namespace loom {

void locate_points(const StepContext& ctx, const GridLayout& layout, const Cells& grid, const Nodes<2>& grid_nodes,
                   const Points<2>& points, PointLocations& loc);

// For a point that follows the body without being a material point (traction and probe points): the active
// cell that carries it, and the linear shape functions of that cell at x. Its own cell when active; else
// the active cell nearest to it (the first ring of side neighbours, up to four, that holds one) where x
// is the least outside, with the shape functions extended (bi)linearly beyond the cell (they still sum to one and reproduce linear
// fields, so a force keeps its resultant and moment). kNoIndex if no active cell is near.
Index host_active_cell(const Cells& grid, const Nodes<2>& grid_nodes, const GridActivity& activity, Index cell, const Vec2& x, Vec4& N);

// The cell holding x (kNoIndex if none) and the barycentric coordinates there; `hint` is a cell to start
// a walk from (kNoIndex: none). Exposed for tests and benchmarks.
Index find_cell(const GridLayout& layout, const Cells& grid, const Nodes<2>& grid_nodes, const Vec2& x, Index hint, Vec4& N);

}  // namespace loom
