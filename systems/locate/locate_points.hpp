// locate (DESIGN §3, seed 003 Algorithm 1 phase 1): finds the background-grid cell holding each point at
// its current position x = X + u, the linear shape functions of the cell's corners there (barycentric
// coordinates of triangles and tetrahedra; bilinear on quad4 grids), and groups the points by cell.
// Structured grids (rectangles of squares, boxes of Kuhn cubes) are searched by arithmetic; other grids
// by walking from the point's previous cell through the neighbours (bucket index when there is none or
// the walk leaves the grid). A point outside the grid is an anomaly: RunError naming the point.
// D = 2 (tri3, quad4, quad9 grids) and D = 3 (tet4 grids, engine/mesh/tet_background_grid.hpp).
#pragma once

#include <ostream>
#include <type_traits>

#include "engine/graph/step_context.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_activity.hpp"
#include "engine/store/grid_layout.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/point_locations.hpp"
#include "engine/store/points.hpp"

namespace loom {

// "(x, y[, z])" in messages: os << Coordinates<D>{x}.
template <int D>
struct Coordinates {
  const Vec<D>& v;
};
template <int D>
std::ostream& operator<<(std::ostream& os, const Coordinates<D>& c) {
  os << "(" << c.v[0];
  for (int a = 1; a < D; ++a) os << ", " << c.v[a];
  return os << ")";
}

template <int D>
void locate_points(const StepContext& ctx, const GridLayoutT<D>& layout, const Cells& grid, const Nodes<D>& grid_nodes,
                   const Points<D>& points, PointLocations& loc);

// For a point that follows the body without being a material point (traction and probe points): the active
// cell that carries it, and the linear shape functions of that cell at x. Its own cell when active; else
// the active cell nearest to it (the first ring of side (face) neighbours, up to four rings in 2D and six in
// 3D, that holds one) where x is the least outside, with the shape functions extended (bi)linearly beyond the
// cell (they still sum to one and reproduce linear fields, so a force keeps its resultant and moment).
// kNoIndex if no active cell is near.
template <int D>
Index host_active_cell(const Cells& grid, const Nodes<D>& grid_nodes, const GridActivity& activity, Index cell,
                       const std::type_identity_t<Vec<D>>& x, Vec4& N);

// The cell holding x (kNoIndex if none) and the barycentric coordinates there; `hint` is a cell to start
// a walk from (kNoIndex: none). Exposed for tests and benchmarks.
template <int D>
Index find_cell(const GridLayoutT<D>& layout, const Cells& grid, const Nodes<D>& grid_nodes, const std::type_identity_t<Vec<D>>& x,
                Index hint, Vec4& N);

}  // namespace loom
