// Activates the background-grid cells that hold material points and their nodes (seed 003 §3.1; seed 004
// eq 27), and keeps the Newton system on them (systems/locate/grid_system.hpp): when the active set changes,
// it is fitted into the system built before, whose dof numbering, pattern and symbolic factorisation then
// stay; only when it does not fit is the system rebuilt around it (a new pattern version, a new symbolic
// analysis). Dofs outside the system are absent, prescribed dofs eliminated, the rest free.
#pragma once

#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_activity.hpp"
#include "engine/store/point_locations.hpp"

namespace loom {

template <int D>
void activate_grid(const StepContext& ctx, const Cells& grid, const PointLocations& particle_loc,
                   const BoundaryConditions<D>& bc, GridActivity& activity, LinearSystem& system);

}  // namespace loom
