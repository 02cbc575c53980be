// The sparsity pattern of the assembled tangent and the scatter map of each cell into it (STYLE §4):
// precomputed once per connectivity, so that assembly writes local matrices straight into the value
// array, with no search and no allocation. The matrix is Eigen's compressed column storage (what
// CHOLMOD and UMFPACK take); for the symmetric patterns of element couplings it is the CSR layout of
// the transpose, so "row" and "column" can be read either way.
#pragma once

#include <Eigen/SparseCore>
#include <array>
#include <cstdint>
#include <vector>

#include "engine/linalg/dof_map.hpp"
#include "engine/store/cells.hpp"

namespace loom {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// Scatter of one Cells store: local dof k of a cell is component k % per_node of its node k / per_node.
struct CellScatter {
  int dofs_per_cell = 0;
  std::vector<Index> slot;      // n_cells * dofs_per_cell^2, row-major (a, b): value index or kNoIndex
  std::vector<Index> dof;       // n_cells * dofs_per_cell: global dof (free or not)
  // Tied dofs of each cell with their masters, as local indices (tied, master, master): the ties of cell c
  // are local_ties[tie_offset[c] .. tie_offset[c + 1]). Masters of a tie lie in the same cell.
  std::vector<Index> tie_offset;
  std::vector<std::array<int, 3>> local_ties;

  Index matrix_slot(Index cell, int a, int b) const {
    return slot[(std::size_t(cell) * dofs_per_cell + std::size_t(a)) * dofs_per_cell + std::size_t(b)];
  }
  Index cell_dof(Index cell, int a) const { return dof[std::size_t(cell) * dofs_per_cell + std::size_t(a)]; }
};

struct SparsePattern {
  SparseMatrix matrix;              // pattern with values (overwritten by every assembly)
  std::vector<Index> diagonal_slot;  // value index of (i, i) for each equation
  std::uint64_t version = 0;         // changes whenever the pattern changes (symbolic analysis is redone)
};

// Builds the pattern coupling every pair of dofs of every cell in `blocks`, numbered by `dofs`. With
// `subsets`, block b contributes only the cells listed in subsets[b] (nullptr: all; MPM: the active cells).
void build_pattern(const std::vector<const Cells*>& blocks, const DofMap& dofs, SparsePattern& pattern,
                   const std::vector<const std::vector<Index>*>& subsets = {});
// Value index of entry (row, col) of the pattern, or kNoIndex.
Index find_slot(const SparsePattern& pattern, Index row, Index col);
// Builds the scatter of one block into an already built pattern; with `subset`, entry k of the scatter is
// cell (*subset)[k]. Every coupling of the cells must be in the pattern; with `complete`, a missing one
// sets *complete = false instead (and the scatter is not usable).
void build_scatter(const Cells& cells, const DofMap& dofs, const SparsePattern& pattern, CellScatter& scatter,
                   const std::vector<Index>* subset = nullptr, bool* complete = nullptr);

}  // namespace loom
