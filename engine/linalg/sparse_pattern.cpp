#include "engine/linalg/sparse_pattern.hpp"

#include <algorithm>
#include <atomic>

#include "engine/core/errors.hpp"
#include "engine/core/parallel.hpp"

namespace loom {

void build_pattern(const std::vector<const Cells*>& blocks, const DofMap& dofs, SparsePattern& pattern,
                   const std::vector<const std::vector<Index>*>& subsets) {
  const Index n_nodes = dofs.n_nodes();
  const int pn = dofs.per_node;
  // Node -> listed cells incidence in flat arrays (an MPM grid rebuilds its pattern whenever its active set
  // changes: no per-node allocation over the whole grid).
  auto for_listed_cells = [&](auto&& visit) {
    for (std::size_t k = 0; k < blocks.size(); ++k) {
      const std::vector<Index>* subset = k < subsets.size() ? subsets[k] : nullptr;
      const Index n_cells = subset ? Index(subset->size()) : blocks[k]->size();
      for (Index s = 0; s < n_cells; ++s) visit(*blocks[k], subset ? (*subset)[std::size_t(s)] : s);
    }
  };
  std::vector<Index> first(std::size_t(n_nodes) + 1, 0);
  for_listed_cells([&](const Cells& cells, Index c) {
    for (int a = 0; a < cells.stride; ++a) ++first[std::size_t(cells.node(c, a)) + 1];
  });
  for (Index i = 0; i < n_nodes; ++i) first[std::size_t(i) + 1] += first[std::size_t(i)];
  std::vector<const Index*> incident(std::size_t(first.back()));  // each: the listed cell's node list
  std::vector<int> incident_stride(std::size_t(first.back()));
  {
    std::vector<Index> cursor(first.begin(), first.end() - 1);
    for_listed_cells([&](const Cells& cells, Index c) {
      for (int a = 0; a < cells.stride; ++a) {
        const Index at = cursor[std::size_t(cells.node(c, a))]++;
        incident[std::size_t(at)] = cells.cell_nodes(c);
        incident_stride[std::size_t(at)] = cells.stride;
      }
    });
  }
  // Column j = equation of dof (node, comp): rows are the free dofs of the nodes sharing a listed cell with
  // it (itself included), ascending because free dofs are numbered node by node.
  const Index n = dofs.n_free;
  std::vector<int> outer(std::size_t(n) + 1, 0);
  std::vector<int> inner;
  std::vector<Index> seen(std::size_t(n_nodes), kNoIndex), adjacent;
  for (Index node = 0; node < n_nodes; ++node) {
    adjacent.clear();
    for (Index k = first[std::size_t(node)]; k < first[std::size_t(node) + 1]; ++k)
      for (int b = 0; b < incident_stride[std::size_t(k)]; ++b) {
        const Index m = incident[std::size_t(k)][b];
        if (seen[std::size_t(m)] != node) seen[std::size_t(m)] = node, adjacent.push_back(m);
      }
    std::sort(adjacent.begin(), adjacent.end());
    for (int cj = 0; cj < pn; ++cj) {
      const Index col = dofs.equation[std::size_t(dofs.dof(node, cj))];
      if (col == kNoIndex) continue;
      for (Index m : adjacent)
        for (int ci = 0; ci < pn; ++ci) {
          const Index row = dofs.equation[std::size_t(dofs.dof(m, ci))];
          if (row != kNoIndex) inner.push_back(row);
        }
      outer[std::size_t(col) + 1] = int(inner.size());
    }
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
                   const std::vector<Index>* subset, bool* complete) {
  std::atomic<bool> all_found{true};
  const int pn = dofs.per_node;
  const int nd = cells.stride * pn;
  const SparseMatrix& A = pattern.matrix;
  const Index n_cells = subset ? Index(subset->size()) : cells.size();
  scatter.dofs_per_cell = nd;
  scatter.slot.assign(std::size_t(n_cells) * std::size_t(nd) * std::size_t(nd), kNoIndex);
  scatter.dof.assign(std::size_t(n_cells) * std::size_t(nd), kNoIndex);
  scatter.tie_offset.assign(std::size_t(n_cells) + 1, 0);
  scatter.local_ties.clear();
  auto cell_dofs = [&](Index c) {
    const Index* nodes = cells.cell_nodes(subset ? (*subset)[std::size_t(c)] : c);
    for (int a = 0; a < nd; ++a) scatter.dof[std::size_t(c) * nd + a] = dofs.dof(nodes[a / pn], a % pn);
  };
  // Each cell writes only its own entries: the slots in parallel (an MPM grid rebuilds them whenever its
  // active set changes); the ties, appended in cell order, serially.
  // A node's free dofs are consecutive equations, and the columns of one node hold the same rows: one
  // search per pair of nodes (not per pair of dofs) finds all their slots.
  const int nc = cells.stride;
  auto cell_slots = [&](Index c) {
    if (dofs.ties.empty()) cell_dofs(c);
    auto slot = [&](int a, int b) -> Index& { return scatter.slot[(std::size_t(c) * nd + std::size_t(a)) * nd + std::size_t(b)]; };
    auto equation = [&](int a) { return dofs.equation[std::size_t(scatter.cell_dof(c, a))]; };
    for (int bn = 0; bn < nc; ++bn) {
      int b0 = -1;  // the node's first free dof (local index)
      for (int k = 0; k < pn && b0 < 0; ++k)
        if (equation(bn * pn + k) != kNoIndex) b0 = bn * pn + k;
      if (b0 < 0) continue;
      const Index col0 = equation(b0);
      const int* begin = A.innerIndexPtr() + A.outerIndexPtr()[col0];
      const int* end = A.innerIndexPtr() + A.outerIndexPtr()[col0 + 1];
      for (int an = 0; an < nc; ++an) {
        Index pos = kNoIndex;
        for (int k = 0; k < pn; ++k) {
          const Index row = equation(an * pn + k);
          if (row == kNoIndex) continue;
          if (pos == kNoIndex) pos = Index(std::lower_bound(begin, end, row) - A.innerIndexPtr());
          else ++pos;
          if (complete && !(pos < A.outerIndexPtr()[col0 + 1] && A.innerIndexPtr()[pos] == row)) {
            all_found.store(false, std::memory_order_relaxed);
            return;
          }
          LOOM_ASSERT(pos < A.outerIndexPtr()[col0 + 1] && A.innerIndexPtr()[pos] == row, "pattern misses a coupling of cell " << c);
          slot(an * pn + k, b0) = pos;
        }
      }
      for (int k = b0 - bn * pn + 1, shift_col = 1; k < pn; ++k) {
        if (equation(bn * pn + k) == kNoIndex) continue;
        const Index shift = A.outerIndexPtr()[col0 + shift_col] - A.outerIndexPtr()[col0];
        LOOM_ASSERT(equation(bn * pn + k) == col0 + shift_col, "a node's free dofs must be consecutive equations");
        for (int a = 0; a < nd; ++a)
          if (slot(a, b0) != kNoIndex) slot(a, bn * pn + k) = slot(a, b0) + shift;
        ++shift_col;
      }
    }
  };
  if (dofs.ties.empty()) {
    for_each_index(n_cells, cell_slots);
    if (complete) *complete = all_found.load();
    return;
  }
  for (Index c = 0; c < n_cells; ++c) {
    cell_dofs(c);
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
    cell_slots(c);
  }
  if (complete) *complete = all_found.load();
}

}  // namespace loom
