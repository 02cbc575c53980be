// GMRES on a matrix A, preconditioned by the factorisation of another matrix of the same pattern (an earlier
// Newton iterate's tangent): the solve that solver.reuse_factor puts in place of a new factorisation.
#pragma once

#include <Eigen/Core>

#include "engine/linalg/linear_solver.hpp"

namespace loom {

struct GmresOutcome {
  bool converged = false;  // |M^-1 (A x - b)| <= tolerance |M^-1 b|, M the factorised matrix: x's relative error
  int iterations = 0;
};

// x from zero, at most max_iterations (no restart); `factor` holds a factorisation of a matrix near A.
GmresOutcome factor_preconditioned_gmres(const SparseMatrix& A, LinearSolver& factor, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                         double tolerance, int max_iterations);

}  // namespace loom
