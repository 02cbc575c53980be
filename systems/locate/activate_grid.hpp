// Activates the background-grid cells that hold material points and their nodes (seed 003 §3.1; seed 004
// eq 27), and numbers the Newton system on them: dofs of inactive nodes are absent (masked, nothing is
// resized), prescribed dofs of active nodes are eliminated, the rest are free. The dof numbering, the
// sparsity pattern (over the active cells) and the cell scatter are rebuilt only when the active set
// changes; the new pattern version makes the linear solver redo its symbolic analysis.
#pragma once

#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_activity.hpp"
#include "engine/store/point_locations.hpp"

namespace loom {

void activate_grid(const StepContext& ctx, const Cells& grid, const PointLocations& particle_loc,
                   const BoundaryConditions<2>& bc, GridActivity& activity, LinearSystem& system);

}  // namespace loom
