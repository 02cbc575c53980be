// A sparse Cholesky back-end for two cores: CHOLMOD on the two halves of a METIS bisection, factorised and
// solved concurrently, joined by the dense Schur complement of the separator (bisected_cholesky.cpp derives it).
// SPD only; results differ from the unsplit CHOLMOD in round-off and do not depend on the thread count (bit for bit).
#pragma once

#include <array>
#include <memory>

#include "engine/linalg/linear_solver.hpp"

namespace loom {

std::unique_ptr<LinearSolver> make_bisected_cholmod_solver();
// For tests: {dofs of half 0, dofs of half 1, separator dofs} of a bisected solver after analyze.
std::array<int, 3> bisected_cholmod_split(LinearSolver& solver);

}  // namespace loom
