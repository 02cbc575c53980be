// Particle-to-grid projection, seed 003 Algorithm 1 lines 5-10 (initialisation phase): the grid is reset
// to its undeformed state (u = 0: the grid displacement is that of the step) and receives the lumped
// mass and the mass-weighted projections of the particles' velocity, acceleration, pressure and (OSGS)
// residual projections:
//   m_I = sum_p N_I(x_p) m_p,   v_I = sum_p N_I(x_p) m_p v_p / m_I,   likewise a_I, p_I, P_u, P_p.
// With OSGS also the lumped projection matrix sum_p N_I V_p^n (lumped_volume) of project_residuals.
// Mass and momentum are conserved exactly (sum_I N_I = 1). Cells are visited colour by colour and the
// particles of a cell in index order, so the sums do not depend on the thread count. Columns the grid
// does not use (velocities of static runs, pressure of displacement-only runs) are skipped.
#pragma once

#include "engine/graph/step_context.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/point_locations.hpp"
#include "engine/store/points.hpp"

namespace loom {

template <int D>
void project_to_grid(const StepContext& ctx, const Cells& grid, const Points<D>& particles, const PointLocations& loc,
                     Nodes<D>& grid_nodes);

// Runs body(c) for every cell holding points, colour by colour, the cells of a colour in parallel.
template <class Body>
void for_each_occupied_cell_by_colour(const Cells& grid, const PointLocations& loc, Body&& body);
// The same, calling ahead(c') for the next cell of the colour before body(c): ahead prefetches the rows of its
// points that body reads (PointLocations::prefetch_points_in).
template <class Ahead, class Body>
void for_each_occupied_cell_by_colour_looking_ahead(const Cells& grid, const PointLocations& loc, Ahead&& ahead, Body&& body);

}  // namespace loom

#include "engine/core/parallel.hpp"

template <class Body>
void loom::for_each_occupied_cell_by_colour(const Cells& grid, const PointLocations& loc, Body&& body) {
  for (Index k = 0; k < grid.n_colours(); ++k) {
    const Index begin = grid.colour_offsets[std::size_t(k)], end = grid.colour_offsets[std::size_t(k) + 1];
    for_each_in(grid.by_colour.data() + begin, end - begin, [&](Index c) {
      if (loc.count_in(c) > 0) body(c);
    });
  }
}

template <class Ahead, class Body>
void loom::for_each_occupied_cell_by_colour_looking_ahead(const Cells& grid, const PointLocations& loc, Ahead&& ahead, Body&& body) {
  for (Index k = 0; k < grid.n_colours(); ++k) {
    const Index begin = grid.colour_offsets[std::size_t(k)], end = grid.colour_offsets[std::size_t(k) + 1];
    for_each_in_looking_ahead(grid.by_colour.data() + begin, end - begin, ahead, [&](Index c) {
      if (loc.count_in(c) > 0) body(c);
    });
  }
}
