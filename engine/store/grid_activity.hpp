// The active part of an MPM background grid (seed 003 §3.1, seed 004 eq 27): the cells holding material
// points and their corner nodes. Inactive nodes are absent from the Newton system (DofKind::absent); the
// node and cell stores keep their size. `version` changes only when the active set changes, and with it
// the dof numbering and the sparsity pattern (SparsePattern::version then redoes the symbolic analysis).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/core/types.hpp"

namespace loom {

struct GridActivity {
  std::vector<char> cell_active;  // per grid cell
  std::vector<char> node_active;  // per grid node
  std::vector<Index> active_cells;  // ascending
  std::vector<Index> active_index;  // per grid cell: its position in active_cells (the scatter entry), or kNoIndex
  std::vector<Index> active_by_colour;  // active cells grouped by the grid's colours
  std::vector<Index> colour_offsets;    // n_colours + 1 into active_by_colour
  std::uint64_t version = 0;  // incremented whenever the active set changes
  int rebuilds = 0;           // times the dof numbering and pattern were rebuilt

  Index n_active_cells() const { return Index(active_cells.size()); }
};

}  // namespace loom
