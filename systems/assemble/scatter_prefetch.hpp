// Look-ahead of the assembly loops (engine/core/prefetch.hpp): a cell's scatter row (its slots), called for the
// next cell; then, with the row in cache, the matrix entries its slots name, called before the cell is integrated
// so that the lines arrive by the time the scatter adds to them. Consecutive cells of a colour share no node, so
// each cell's slots and entries would otherwise miss the cache (perf/compare/README.md, "Cache misses").
#pragma once

#include <cstddef>

#include "engine/core/prefetch.hpp"
#include "engine/linalg/linear_system.hpp"

namespace loom {

inline void prefetch_scatter_row(Index entry, const CellScatter& sc) {
  const std::size_t n = std::size_t(sc.dofs_per_cell) * std::size_t(sc.dofs_per_cell);
  const char* row = reinterpret_cast<const char*>(sc.slot.data() + std::size_t(entry) * n);
  for (std::size_t offset = 0; offset < n * sizeof(Index); offset += 64) prefetch_line(row + offset);
}
inline void prefetch_scatter_entries(Index entry, const CellScatter& sc, const LinearSystem& system) {
  const double* values = system.pattern.matrix.valuePtr();
  for (int b = 0; b < sc.dofs_per_cell; ++b)
    for (int a = 0; a < sc.dofs_per_cell; a += 2) {  // a node's two rows share a line but at its end
      const Index s = sc.matrix_slot(entry, a, b);
      if (s != kNoIndex) prefetch_line(reinterpret_cast<const char*>(values + s));
    }
}

}  // namespace loom
