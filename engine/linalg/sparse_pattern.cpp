#include "engine/linalg/sparse_pattern.hpp"

#include <algorithm>
#include <atomic>

#include "engine/core/errors.hpp"

namespace loom {

void build_pattern(const std::vector<const Cells*>& blocks, const DofMap& dofs, SparsePattern& pattern,
                   const std::vector<const std::vector<Index>*>& subsets) {
  const Index n_nodes = dofs.n_nodes();
  const int pn = dofs.per_node;
  // Node adjacency (including the node itself), sorted and unique per node.
  std::vector<std::vector<Index>> adjacent(static_cast<std::size_t>(n_nodes));
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    const Cells* cells = blocks[k];
    const std::vector<Index>* subset = k < subsets.size() ? subsets[k] : nullptr;
    const Index n_cells = subset ? Index(subset->size()) : cells->size();
    for (Index s = 0; s < n_cells; ++s) {
      const Index c = subset ? (*subset)[std::size_t(s)] : s;
      const Index* nodes = cells->cell_nodes(c);
      for (int a = 0; a < cells->stride; ++a)
        for (int b = 0; b < cells->stride; ++b) adjacent[std::size_t(nodes[a])].push_back(nodes[b]);
    }
  }
  for (auto& list : adjacent) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  // Column j = equation of dof (node, comp): rows are the free dofs of adjacent nodes, ascending because
  // free dofs are numbered node by node.
  const Index n = dofs.n_free;
  std::vector<int> outer(std::size_t(n) + 1, 0);
  std::vector<int> inner;
  for (Index node = 0; node < n_nodes; ++node)
    for (int cj = 0; cj < pn; ++cj) {
      const Index col = dofs.equation[std::size_t(dofs.dof(node, cj))];
      if (col == kNoIndex) continue;
      for (Index m : adjacent[std::size_t(node)])
        for (int ci = 0; ci < pn; ++ci) {
          const Index row = dofs.equation[std::size_t(dofs.dof(m, ci))];
          if (row != kNoIndex) inner.push_back(row);
        }
      outer[std::size_t(col) + 1] = int(inner.size());
    }
  SparseMatrix& A = pattern.matrix;
  A.resize(n, n);
  A.resizeNonZeros(Eigen::Index(inner.size()));
  std::copy(outer.begin(), outer.end(), A.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), A.innerIndexPtr());
  std::fill(A.valuePtr(), A.valuePtr() + inner.size(), 0.0);
  LOOM_ASSERT(A.isCompressed(), "pattern must be compressed");
  pattern.diagonal_slot.assign(std::size_t(n), kNoIndex);
  for (Index j = 0; j < n; ++j) {
    const int* begin = A.innerIndexPtr() + outer[std::size_t(j)];
    const int* end = A.innerIndexPtr() + outer[std::size_t(j) + 1];
    const int* it = std::lower_bound(begin, end, j);
    LOOM_ASSERT(it != end && *it == j, "missing diagonal entry " << j);
    pattern.diagonal_slot[std::size_t(j)] = Index(it - A.innerIndexPtr());
  }
  static std::atomic<std::uint64_t> next_version{1};  // unique across patterns: a solver never mistakes one for another
  pattern.version = next_version++;
}

Index find_slot(const SparsePattern& pattern, Index row, Index col) {
  const SparseMatrix& A = pattern.matrix;
  const int* begin = A.innerIndexPtr() + A.outerIndexPtr()[col];
  const int* end = A.innerIndexPtr() + A.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  return it != end && *it == row ? Index(it - A.innerIndexPtr()) : kNoIndex;
}

void build_scatter(const Cells& cells, const DofMap& dofs, const SparsePattern& pattern, CellScatter& scatter,
                   const std::vector<Index>* subset) {
  const int pn = dofs.per_node;
  const int nd = cells.stride * pn;
  const SparseMatrix& A = pattern.matrix;
  const Index n_cells = subset ? Index(subset->size()) : cells.size();
  scatter.dofs_per_cell = nd;
  scatter.slot.assign(std::size_t(n_cells) * std::size_t(nd) * std::size_t(nd), kNoIndex);
  scatter.dof.assign(std::size_t(n_cells) * std::size_t(nd), kNoIndex);
  scatter.tie_offset.assign(std::size_t(n_cells) + 1, 0);
  scatter.local_ties.clear();
  for (Index c = 0; c < n_cells; ++c) {
    const Index* nodes = cells.cell_nodes(subset ? (*subset)[std::size_t(c)] : c);
    for (int a = 0; a < nd; ++a) scatter.dof[std::size_t(c) * nd + a] = dofs.dof(nodes[a / pn], a % pn);
    if (!dofs.ties.empty())
      for (int a = 0; a < nd; ++a) {
        const Tie* tie = dofs.tie_of(scatter.cell_dof(c, a));
        if (!tie) continue;
        std::array<int, 3> local{a, -1, -1};
        for (int m = 0; m < 2; ++m)
          for (int b = 0; b < nd; ++b)
            if (scatter.cell_dof(c, b) == tie->master[m]) local[std::size_t(m) + 1] = b;
        LOOM_CHECK(local[1] >= 0 && local[2] >= 0, RunError, "a tied dof's masters are not in its cell " << c);
        scatter.local_ties.push_back(local);
      }
    scatter.tie_offset[std::size_t(c) + 1] = Index(scatter.local_ties.size());
    for (int b = 0; b < nd; ++b) {
      const Index col = dofs.equation[std::size_t(scatter.cell_dof(c, b))];
      if (col == kNoIndex) continue;
      const int* begin = A.innerIndexPtr() + A.outerIndexPtr()[col];
      const int* end = A.innerIndexPtr() + A.outerIndexPtr()[col + 1];
      for (int a = 0; a < nd; ++a) {
        const Index row = dofs.equation[std::size_t(scatter.cell_dof(c, a))];
        if (row == kNoIndex) continue;
        const int* it = std::lower_bound(begin, end, row);
        LOOM_ASSERT(it != end && *it == row, "pattern misses a coupling of cell " << c);
        scatter.slot[(std::size_t(c) * nd + std::size_t(a)) * nd + std::size_t(b)] = Index(it - A.innerIndexPtr());
      }
    }
  }
}

}  // namespace loom
