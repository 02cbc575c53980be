// Assembly of the Newton system of an MPM step on the active background grid (seed 003 eqs 16-26): the
// material points are the quadrature points (weights: their volumes), the grid cells the elements.
// Displacement-only grids (element p1) use the updated-Lagrangian displacement kernel at each point; mixed
// grids (p1p1_up) the u-p kernel with the body's stabilisation (none, PPP per cell, ASGS, OSGS). Lumped
// inertia of the grid's Newmark scheme and the external loads are added per node; prescribed dofs enter
// through the Dirichlet lift (as in the fem assembly: while a dof lags its target, the free rows get
// K_fp (g - u_p)). Active cells are visited colour by colour, the points of a cell in index order:
// results do not depend on the thread count. The deformation gradient of each point at the iterate is
// stored in the locations' F column.
#pragma once

#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_activity.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/point_locations.hpp"
#include "engine/store/points.hpp"
#include "systems/assemble/assemble_system.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {

struct GridAssemblyOptions {
  bool tangent = true;
  bool inertia = true;  // false: the static residual f_int - f_ext (initial equilibrium acceleration)
};

// D = 2 (tri3, quad4 grids) or 3 (tet4 grids); instantiated for both.
template <int D>
AssemblyResult assemble_grid_system(const StepContext& ctx, const GridAssemblyOptions& options,
                                    const std::vector<BodyMaterial>& materials, const Cells& grid, const GridActivity& activity,
                                    const Nodes<D>& grid_nodes, const Points<D>& particles, const BoundaryConditions<D>& bc,
                                    PointLocations& loc, LinearSystem& system);

}  // namespace loom
