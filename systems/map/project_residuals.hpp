// OSGS residual projections (seed 003 §4-5, Algorithm 1 lines 33-35): the L2 projections onto the grid's
// linear space, with the material points as quadrature and the lumped projection matrix,
//   P_u,I = sum_p V_n N_I R_u(x_p) / sum_p V_n N_I,   R_u = rho (b - a_h) + grad p_h,
//   P_p,I = sum_p V_n N_I R_p(x_p) / sum_p V_n N_I,   R_p = (J - 1) - p_h / kappa,
// of the current Newton iterate (the lumped matrix sum_p V_n N_I is project_to_grid's lumped_volume). The assembly uses them as data (P_h^perp[f^k] ~ f^k - P_h[f^(k-1)]):
// Newton then converges linearly near the solution, as the seed reports (8 iterations against ASGS's 4).
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
void project_residuals(const StepContext& ctx, const std::vector<BodyMaterial>& materials, const Cells& grid,
                       const GridActivity& activity, const Points<D>& particles, const PointLocations& loc,
                       const BoundaryConditions<D>& bc, Nodes<D>& grid_nodes);

}  // namespace loom
