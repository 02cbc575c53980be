// The assembled Newton system of a mesh-based run: dof numbering, tangent pattern and values, cell
// scatters, residuals and increments. One store; the solver back-end (factorization) lives apart in
// LinearSolve because it is not data the systems exchange.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "engine/linalg/dof_map.hpp"
#include "engine/linalg/sparse_pattern.hpp"

namespace loom {

struct LinearSystem {
  DofMap dofs;
  SparsePattern pattern;              // tangent on the free dofs
  std::vector<CellScatter> scatter;   // one per cell block, parallel to the Cells stores
  std::vector<CellScatter> domain_scatter;  // one per Edges store (integration domains of seed 001)
  Eigen::VectorXd residual_full;      // n_dofs: f_int + M a - f_ext (reactions on prescribed dofs)
  Eigen::VectorXd residual;           // n_free: the Newton residual, with the Dirichlet lift
  Eigen::VectorXd increment;          // n_free: solution of K du = -r
  Eigen::VectorXd increment_full;     // n_dofs: du on free dofs, (target - u) on prescribed dofs

  void resize_vectors() {
    residual_full.setZero(dofs.n_dofs());
    residual.setZero(dofs.n_free);
    increment.setZero(dofs.n_free);
    increment_full.setZero(dofs.n_dofs());
  }
};

}  // namespace loom
