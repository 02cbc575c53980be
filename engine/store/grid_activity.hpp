// The active part of an MPM background grid (seed 003 §3.1, seed 004 eq 27): the cells holding material
// points and their corner nodes. Inactive nodes are absent from the Newton system (DofKind::absent); the
// node and cell stores keep their size. `version` changes only when the active set changes, and with it
// the dof numbering and the sparsity pattern (SparsePattern::version then redoes the symbolic analysis).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/core/types.hpp"
#include "engine/store/cells.hpp"

namespace loom {

struct GridActivity {
  std::vector<char> cell_active;  // per grid cell
  std::vector<char> node_active;  // per grid node
  std::vector<Index> active_cells;  // ascending
  std::vector<Index> active_index;  // per grid cell: its position in active_cells, or kNoIndex
  std::vector<Index> active_by_colour;  // active cells grouped by the grid's colours
  std::vector<Index> colour_offsets;    // n_colours + 1 into active_by_colour
  // Method mpm_fem: cells from this index on are FEM cells (seed 004 §4), active whether or not they hold
  // particles; kNoIndex: none.
  Index always_active_from = kNoIndex;
  std::uint64_t version = 0;  // incremented whenever the active set changes

  // The Newton system (systems/locate/grid_system.hpp) spans more than the active cells, so that its dof
  // numbering, pattern and symbolic factorisation outlive most changes of the active set: it is built around
  // `system_base` (the active set of its last rebuild) with one layer of neighbouring cells and, where a
  // boundary may move, the couplings of ghost faces. Nodes of system cells that no active cell holds are
  // dormant: their free dofs get an identity row (zero increment), as if absent.
  std::vector<Index> system_base;    // ascending; checkpointed, so that a restart builds the same system
  std::vector<Index> system_cells;   // ascending: the cells of the pattern and of scatter[0]
  std::vector<Index> scatter_entry;  // per grid cell: its entry in scatter[0] (position in system_cells), or kNoIndex
  std::vector<Index> dormant_dofs;   // free dofs of dormant nodes, ascending
  int rebuilds = 0;                  // times the dof numbering and pattern were rebuilt

  // Faces with a ghost penalty (grid.ghost_penalty > 0; systems/assemble/elements/ghost_face.hpp): sides
  // shared by two active cells of which at least one is cut by the body's boundary (has a corner that an
  // inactive cell shares). ghost_faces lists each face's nodes in the kernel's local order (stride
  // 2 NC - 2) with colours, for the pattern, the scatter and a race-free assembly.
  Cells ghost_faces;
  std::vector<Index> ghost_cells;  // 2 per face: the left and right cell
  std::vector<Index> ghost_ends;   // 2 per face: the corners of the shared side

  // Particle Newmark with soft stiffness (seed 004 §3.4): per active cell (in active_cells order) its flag
  // M_E, the nodes it shares neither with an inactive cell nor with a boundary marked outside; valid for
  // the active set of `flags_version`.
  std::vector<int> inside_nodes;
  std::uint64_t flags_version = 0;

  Index n_active_cells() const { return Index(active_cells.size()); }
};

}  // namespace loom
