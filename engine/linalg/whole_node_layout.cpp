#include "engine/linalg/whole_node_layout.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace loom {
namespace {

// Rows by whole nodes when the structure numbers exactly A's equations, else A's equations as they are.
void number_rows(const SparseMatrix& A, const SolveStructure& s, WholeNodeLayout& l, std::vector<int>& decoupled_rows) {
  const DofMap& dofs = s.dofs;
  const Index n_free = A.rows();
  l.whole_nodes = s.dim > 0 && dofs.per_node > 0 && dofs.n_free == n_free;
  l.row_of_equation.assign(std::size_t(n_free), 0);
  if (!l.whole_nodes) {
    std::iota(l.row_of_equation.begin(), l.row_of_equation.end(), 0);
    l.block_size = 1;
    l.rows = int(n_free);
    return;
  }
  l.block_size = dofs.per_node;
  int row = 0;
  for (Index node = 0; node < dofs.n_nodes(); ++node) {
    bool has_free = false;
    for (int c = 0; c < dofs.per_node; ++c) has_free |= dofs.kind[std::size_t(dofs.dof(node, c))] == DofKind::free;
    if (!has_free) continue;
    l.node_of_row_block.push_back(node);
    for (int c = 0; c < dofs.per_node; ++c, ++row) {
      const Index dof = dofs.dof(node, c);
      if (dofs.kind[std::size_t(dof)] == DofKind::free) l.row_of_equation[std::size_t(dofs.equation[std::size_t(dof)])] = row;
      else decoupled_rows.push_back(row);
    }
  }
  l.rows = row;
}

}  // namespace

WholeNodeLayout whole_node_layout(const SparseMatrix& A, const SolveStructure& structure) {
  WholeNodeLayout l;
  std::vector<int> decoupled_rows;
  number_rows(A, structure, l, decoupled_rows);
  // Entries counted per row, placed by a prefix sum, then each row sorted by column (source -1: a decoupled diagonal).
  struct Entry {
    int column;
    Index source;
  };
  l.offsets.assign(std::size_t(l.rows) + 1, 0);
  const int* inner = A.innerIndexPtr();
  const int* outer = A.outerIndexPtr();
  for (Index k = 0; k < A.nonZeros(); ++k) ++l.offsets[std::size_t(l.row_of_equation[std::size_t(inner[k])]) + 1];
  for (int r : decoupled_rows) ++l.offsets[std::size_t(r) + 1];
  std::partial_sum(l.offsets.begin(), l.offsets.end(), l.offsets.begin());
  std::vector<Entry> entries(std::size_t(l.offsets.back()));
  std::vector<int> next(l.offsets.begin(), l.offsets.end() - 1);
  for (Index j = 0; j < A.outerSize(); ++j)
    for (Index k = outer[j]; k < outer[j + 1]; ++k)
      entries[std::size_t(next[std::size_t(l.row_of_equation[std::size_t(inner[k])])]++)] = {l.row_of_equation[std::size_t(j)], k};
  for (int r : decoupled_rows) entries[std::size_t(next[std::size_t(r)]++)] = {r, -1};
  l.columns.resize(entries.size());
  l.slot_of_value.assign(std::size_t(A.nonZeros()), 0);
  for (int r = 0; r < l.rows; ++r) {
    const auto first = entries.begin() + l.offsets[std::size_t(r)], last = entries.begin() + l.offsets[std::size_t(r) + 1];
    std::sort(first, last, [](const Entry& a, const Entry& b) { return a.column < b.column; });
    for (auto e = first; e != last; ++e) {
      const int slot = int(e - entries.begin());
      l.columns[std::size_t(slot)] = e->column;
      if (e->source < 0) l.decoupled_slots.push_back(slot);
      else l.slot_of_value[std::size_t(e->source)] = slot;
    }
  }
  // The transpose of each value, found in its column's row (the pattern of a loom tangent is symmetric).
  l.transpose.assign(l.slot_of_value.size(), -1);
  for (int r = 0; r < l.rows; ++r)
    for (int s = l.offsets[std::size_t(r)]; s < l.offsets[std::size_t(r) + 1]; ++s) {
      const Index k = entries[std::size_t(s)].source;
      if (k < 0) continue;
      const int c = l.columns[std::size_t(s)];
      const auto first = l.columns.begin() + l.offsets[std::size_t(c)], last = l.columns.begin() + l.offsets[std::size_t(c) + 1];
      const auto it = std::lower_bound(first, last, r);
      if (it != last && *it == r) l.transpose[std::size_t(k)] = entries[std::size_t(it - l.columns.begin())].source;
    }
  return l;
}

std::vector<int> rows_of_ranks(const WholeNodeLayout& layout, int ranks) {
  const int bs = std::max(layout.block_size, 1), blocks = layout.rows / bs;
  const double entries = double(layout.offsets.empty() ? 0 : layout.offsets.back());
  std::vector<int> first_row(std::size_t(ranks) + 1, layout.rows);
  first_row[0] = 0;
  // Rank r starts at the first block boundary whose entries before it reach r / ranks of all of them.
  int r = 1;
  for (int b = 0; b < blocks && r < ranks; ++b)
    while (r < ranks && double(layout.offsets[std::size_t(b * bs)]) >= entries * double(r) / double(ranks)) first_row[std::size_t(r++)] = b * bs;
  return first_row;
}

bool is_symmetric(const SparseMatrix& A, const std::vector<Index>& transpose, double tolerance) {
  const double* v = A.valuePtr();
  double largest = 0.0, asymmetry = 0.0;
  for (std::size_t k = 0; k < transpose.size(); ++k) {
    largest = std::max(largest, std::abs(v[k]));
    asymmetry = std::max(asymmetry, transpose[k] < 0 ? std::abs(v[k]) : std::abs(v[k] - v[transpose[k]]));
  }
  return asymmetry <= tolerance * largest;
}

void copy_values(const SparseMatrix& A, const WholeNodeLayout& layout, double decoupled, double* values) {
  const double* v = A.valuePtr();
  for (std::size_t k = 0; k < layout.slot_of_value.size(); ++k) values[layout.slot_of_value[k]] = v[k];
  for (int s : layout.decoupled_slots) values[s] = decoupled;
}

}  // namespace loom
