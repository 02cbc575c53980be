// Where the points of a Points store sit in the MPM background grid at the start of the step: the
// per-step quadrature data of material points (DESIGN §2 QuadPoints, with a variable number of points per
// cell). Rebuilt by the locate system every (sub)step; the shape gradients are the cell's (tri3) or follow
// from N (quad4): engine/mesh/grid_shape.hpp.
#pragma once

#include <string>
#include <vector>

#include "engine/core/types.hpp"
#include "engine/store/column.hpp"

namespace loom {

struct PointLocations {
  std::string entity = "particle";  // what the points are, in messages

  Column<Index> cell;  // grid cell holding the point at its position x_n = X + u_n
  Column<Vec4> N;      // shape functions of the cell's corners at x_n (tri3: barycentric, fourth entry 0)
  Column<Vec2> xi;     // quad9 grids: the point's coordinates in the reference square [-1, 1]^2 of its cell
  Column<Mat3> F;      // material points: deformation gradient at the current Newton iterate
  Column<Mat3> be;     // materials with history: b^e after the return map at the iterate (committed at convergence)
  // Particle Newmark with receding contact (seed 004 §5): the side (0-3) of the host cell on a wall that
  // the particle moves away from this step, or kNoIndex.
  Column<Index> receding;

  // Points grouped by cell (a counting sort, ascending point index within a cell): the points of cell c
  // are by_cell[cell_offsets[c] .. cell_offsets[c + 1]). Scatters to the grid visit cells colour by colour
  // and the points of a cell in this order, so that sums do not depend on the thread count.
  std::vector<Index> by_cell;
  std::vector<Index> cell_offsets;

  PointLocations() {
    cell.use();
    N.use();
  }

  Index size() const { return cell.size(); }
  Index count_in(Index c) const { return cell_offsets[std::size_t(c) + 1] - cell_offsets[std::size_t(c)]; }
  const Index* points_in(Index c) const { return by_cell.data() + cell_offsets[std::size_t(c)]; }
  // Prefetches the rows of cell c's points in the given columns (or per-point vectors): loops over cells call it
  // for the next cell (engine/core/prefetch.hpp).
  template <class... PointColumns>
  void prefetch_points_in(Index c, const PointColumns&... columns) const {
    const Index* pts = points_in(c);
    for (Index k = 0; k < count_in(c); ++k) (prefetch_row(columns, pts[k]), ...);
  }

  void resize(Index n) {
    cell.resize(n, kNoIndex);
    N.resize(n, Vec4::Zero());
    xi.resize(n, Vec2::Zero());
    F.resize(n, Mat3::Identity());
    be.resize(n, Mat3::Identity());
    receding.resize(n, kNoIndex);
  }

  template <class Visit>
  void for_each_column(Visit&& f) {
    f("cell", cell), f("N", N), f("xi", xi), f("F", F), f("be", be), f("receding", receding);
  }
  template <class Visit>
  void for_each_column(Visit&& f) const {
    const_cast<PointLocations*>(this)->for_each_column([&](const char* name, const auto& c) { f(name, c); });
  }
};

}  // namespace loom
