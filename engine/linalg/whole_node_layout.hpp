// The tangent laid out by whole nodes, for a back-end whose preconditioner wants every node's dofs together (PETSc's
// smoothed-aggregation multigrid: block size = dofs per node, rigid-body modes per node; a fieldsplit by stride).
// loom's matrix holds only the free equations; here every node with a free dof brings all its dofs, the eliminated
// ones (prescribed, tied, absent) as decoupled rows whose only entry is the diagonal. The layout is a row-major
// pattern (CSR, columns sorted in each row) with the position of each of loom's values in it, so that new values are
// copied in O(nnz) whatever the symmetry of the tangent. Without a structure that fits the matrix, the rows are loom's
// equations as they are (block size 1). Compiled into the PETSc plugin; no PETSc here, so it is tested on its own.
#pragma once

#include <vector>

#include "engine/linalg/linear_solver.hpp"

namespace loom {

struct WholeNodeLayout {
  bool whole_nodes = false;
  int block_size = 1;
  int rows = 0;
  std::vector<int> row_of_equation;      // loom's free equation -> row
  std::vector<Index> node_of_row_block;  // whole nodes: the node of each block of block_size rows
  std::vector<int> offsets, columns;     // the pattern, CSR (32-bit: PETSc's PetscInt in Debian's build)
  std::vector<int> slot_of_value;        // loom's value index -> position in the CSR values
  std::vector<int> decoupled_slots;      // positions of the decoupled rows' diagonals
  std::vector<Index> transpose;          // loom's value index -> the value index of its transpose (-1: none)
};

WholeNodeLayout whole_node_layout(const SparseMatrix& A, const SolveStructure& structure);

// Whether A equals its transpose to `tolerance` times its largest entry.
bool is_symmetric(const SparseMatrix& A, const std::vector<Index>& transpose, double tolerance);

// The rows each of `ranks` processes owns in a distributed solve: first_row[r] .. first_row[r + 1], whole row blocks
// (a node's dofs stay on one rank, as the block size and the near-null space need), contiguous, and balanced by
// entries (the work of a matrix-vector product), not by rows. A pure function of the layout: every rank computes it.
std::vector<int> rows_of_ranks(const WholeNodeLayout& layout, int ranks);

// Writes A's values into the CSR value array of the layout, and `decoupled` on the decoupled rows' diagonals.
void copy_values(const SparseMatrix& A, const WholeNodeLayout& layout, double decoupled, double* values);

}  // namespace loom
