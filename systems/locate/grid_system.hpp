// The Newton system of an MPM grid (dof numbering, sparsity pattern, cell and ghost-face scatters), built so
// that it outlives most changes of the active set: a new pattern means a new symbolic factorisation (the
// fill-reducing ordering and the elimination tree), which cost a fifth of a step when it was redone for
// every new active set (perf/compare/README.md).
//
// build_grid_system spans activity.system_base (an active set) and one layer of cells around it (every cell
// sharing a node with it): the body may move up to a cell layer before the system no longer holds its
// cells. With the face ghost penalty, the pattern also couples the two cells across every side where a
// ghost face may appear while the boundary moves by that layer (a side of a cell within one node layer of
// the boundary). fit_grid_system then takes each new active set into the built system: it holds if every
// active cell is a system cell, every ghost face's couplings are in the pattern and the active set has not
// shrunk to less than half the set the system was built around (a body that split or left); the nodes of system cells that no
// active cell holds are dormant, and the assembly gives their free dofs an identity row, which leaves the
// other equations as they were without them. activate_grid rebuilds around the active set when it does not
// fit. The system is a function of system_base and the grid alone, so a restart that restores system_base
// factorises the same matrices as the run it continues.
#pragma once

#include "engine/linalg/linear_system.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_activity.hpp"

namespace loom {

// Builds dofs, pattern and scatter[0] around activity.system_base; `ghost`: the ghost penalty is on.
template <int D>
void build_grid_system(const Cells& grid, const BoundaryConditions<D>& bc, bool ghost, GridActivity& activity, LinearSystem& system);

// Fits the current active set (and its ghost faces) into the built system: false if it does not fit, else
// builds the ghost-face scatter (scatter[1]) and the dormant dofs.
bool fit_grid_system(bool ghost, GridActivity& activity, LinearSystem& system);

}  // namespace loom
