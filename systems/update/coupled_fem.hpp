// The two node updates of method mpm_fem (Aulisa & Capodaglio §2, §4; spec seed004 §1.1, §1.9, §1.11) on the
// one node store of grid and FEM bodies. Each node carries its reference position X = X^ + u_n for the step
// (X^ the undeformed position) and the step's displacement u; u_n is the FEM node's displacement u^n, and the
// reset displacement on the other grid nodes.
//  - commit_fem_nodes, after a converged step: the FEM nodes' Newmark update (eq 46),
//      a = u / (beta dt^2) - v / (beta dt) - (1 - 2 beta) / (2 beta) a^n,  v += dt ((1 - gamma) a^n + gamma a),
//    and u_n += u, X += u, u = 0 (the FEM nodes cannot be reset: they are the body). Run after the particles'
//    update, which reads the step's u and the grid it started from.
//  - reset_grid, at the start of a step: the grid's other nodes take the reset field of eq 8, the solution of
//    div(grad u + grad u^T) = 0 on the undeformed grid with u = u_n on the FEM nodes and u = 0 where [[boundary]]
//    holds a component: X = X^ + u_reset, u_n = u_reset. The operator never changes: ResetField factorises it
//    once (build_reset_field) and each step back-substitutes. u = 0 everywhere afterwards: the step starts from
//    the reference grid, as the plain MPM grid starts undeformed (eqs 9-10).
#pragma once

#include <Eigen/SparseCholesky>
#include <memory>
#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_activity.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

struct ResetField {
  std::vector<Index> free_index;  // per dof (2 per node): its row among the free dofs, or kNoIndex (prescribed)
  std::vector<Index> held_index;  // per dof: its column among the prescribed dofs, or kNoIndex
  std::vector<Index> held_dof;    // the prescribed dofs in column order
  Eigen::SparseMatrix<double> K_fp;  // free rows, prescribed columns
  std::shared_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> K_ff;  // factorised
  bool any_free() const { return K_ff != nullptr; }
};

// From the undeformed grid (nodes.X with u_n = 0): cells [0, grid_cells) of `grid` are the background grid.
// Throws RunError if the operator is singular (a grid region held by neither an FEM node nor a boundary).
void build_reset_field(const Cells& grid, Index grid_cells, const Nodes<2>& nodes, const std::vector<char>& fem_node,
                       const BoundaryConditions<2>& bc, ResetField& out);

void reset_grid(const StepContext& ctx, const ResetField& reset, const std::vector<char>& fem_node, Nodes<2>& nodes);

void commit_fem_nodes(const StepContext& ctx, const std::vector<char>& fem_node, Nodes<2>& nodes);

}  // namespace loom
