// locate (DESIGN §3, seed 003 Algorithm 1 phase 1): finds the background-grid cell holding each point at
// its current position x = X + u, the linear shape functions of the cell's corners there (barycentric
// coordinates), and groups the points by cell. Structured grids are searched by arithmetic; other grids
// by walking from the point's previous cell through the neighbours (bucket index when there is none or
// the walk leaves the grid). A point outside the grid is an anomaly: RunError naming the point.
#pragma once

#include "engine/graph/step_context.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_layout.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/point_locations.hpp"
#include "engine/store/points.hpp"

namespace loom {

void locate_points(const StepContext& ctx, const GridLayout& layout, const Cells& grid, const Nodes<2>& grid_nodes,
                   const Points<2>& points, PointLocations& loc);

// The cell holding x (kNoIndex if none) and the barycentric coordinates there; `hint` is a cell to start
// a walk from (kNoIndex: none). Exposed for tests and benchmarks.
Index find_cell(const GridLayout& layout, const Cells& grid, const Nodes<2>& grid_nodes, const Vec2& x, Index hint, Vec3& N);

}  // namespace loom
