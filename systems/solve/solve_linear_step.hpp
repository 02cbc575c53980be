// Solves the Newton correction K du = -r with the run's linear solver and builds the full-dof increment
// (prescribed dofs: the gap to their target).
#pragma once

#include "engine/linalg/linear_solver.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/nodes.hpp"
#include "engine/timing/timers.hpp"

namespace loom {

enum class LinearSolveStatus { ok, singular };

// Factorizes the assembled tangent and solves K du = -r for the free dofs into system.increment (timed as
// newton/solve/factorize and newton/solve/back_substitute); shared by the fem/pfem and mpm steps.
// refactorize = false reuses the factorisation of the last call (a tangent frozen for the step).
LinearSolveStatus solve_free_dofs(LinearSolve& solver, LinearSystem& system, Timers& timers, bool refactorize = true);

// Gives the solver the structure of the equations (SolveStructure: dofs and node coordinates, X + u if `current`)
// when its back-end wants it and the pattern is new.
template <int D>
void give_structure(const Nodes<D>& nodes, bool current, LinearSolve& solver, const LinearSystem& system);

template <int D>
LinearSolveStatus solve_linear_step(const Nodes<D>& nodes, const BoundaryConditions<D>& bc, LinearSolve& solver,
                                    LinearSystem& system, Timers& timers, bool refactorize = true);

}  // namespace loom
