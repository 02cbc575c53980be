// Numbering of the unknowns: each node carries `per_node` dofs (D displacement components, later a
// pressure or dilatation); a dof is free (an equation of the linear system), prescribed (Dirichlet,
// eliminated), tied (a linear constraint: the mean of two master dofs, seed 000 eq 24 for PFEM TRI6
// mid-nodes on boundary edges; eliminated) or absent (e.g. no dilatation on a TRI6 mid-node). Free dofs
// are numbered node by node, so the rows of one node are consecutive.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/core/types.hpp"

namespace loom {

enum class DofKind : std::int8_t { free, prescribed, tied, absent };

// A tied dof equals the mean of its two masters (free or prescribed dofs).
struct Tie {
  Index dof;
  Index master[2];
};

struct DofMap {
  int per_node = 0;
  std::vector<DofKind> kind;    // n_nodes * per_node
  std::vector<Index> equation;  // free: equation number; otherwise kNoIndex
  Index n_free = 0;
  std::vector<Tie> ties;        // sorted by dof

  const Tie* tie_of(Index dof) const;

  Index n_nodes() const { return per_node == 0 ? 0 : Index(kind.size()) / per_node; }
  Index n_dofs() const { return Index(kind.size()); }
  Index dof(Index node, int component) const { return node * per_node + component; }

  // Numbers the free dofs of `kind` (which must have n_nodes * per_node entries); every dof of kind tied
  // must have its entry in `tie_list`.
  void build(int dofs_per_node, std::vector<DofKind> kinds, std::vector<Tie> tie_list = {});
};

}  // namespace loom
