// Loads and prescribed values of an MPM step on the background grid, at the time t of the (sub)step:
//  - prescribed displacement dofs get the step's increment g(t) - g(t - dt) at the grid node (the grid starts
//    each step undeformed); prescribed pressure dofs get g(t);
//  - body forces act at the particles: f_I += N_I(x_p) m_p b(t, X_p) (X_p the particle's reference position);
//  - dead-load tractions act at the traction points: f_I += N_I(x_q) w_q t(t, X_q), w_q the point's share of
//    its edge's reference length (3D: of its face's reference area) (seed 003 Fig 3b: loads on non-conforming boundaries go to points of the
//    body), through the shape functions of its host active cell (host_active_cell: a traction point in a
//    cell without particles uses the neighbouring active cell's, extended); none nearby is an anomaly
//    (RunError).
// Particle sums run cell by cell colour by colour (deterministic); traction points in index order.
#pragma once

#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_activity.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/point_locations.hpp"
#include "engine/store/points.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {

template <int D>
void apply_grid_loads(const StepContext& ctx, const Cells& grid, const Nodes<D>& grid_nodes, const GridActivity& activity,
                      const Points<D>& particles, const PointLocations& particle_loc, const Points<D>& traction_points,
                      const PointLocations& traction_loc, BoundaryConditions<D>& bc);

}  // namespace loom
