// The Newton correction on an MPM grid: K du = -r with the run's linear solver, and the full-dof
// increment (prescribed dofs: the gap to their target, displacement or pressure; absent dofs: zero).
#pragma once

#include "engine/linalg/linear_solver.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/nodes.hpp"
#include "engine/timing/timers.hpp"
#include "systems/solve/solve_linear_step.hpp"

namespace loom {

template <int D>
LinearSolveStatus solve_grid_step(const Nodes<D>& grid_nodes, const BoundaryConditions<D>& bc, LinearSolve& solver,
                                  LinearSystem& system, Timers& timers);

}  // namespace loom
