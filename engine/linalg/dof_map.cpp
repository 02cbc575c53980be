#include "engine/linalg/dof_map.hpp"

#include <algorithm>

#include "engine/core/errors.hpp"

namespace loom {

const Tie* DofMap::tie_of(Index dof) const {
  auto it = std::lower_bound(ties.begin(), ties.end(), dof, [](const Tie& t, Index d) { return t.dof < d; });
  return it != ties.end() && it->dof == dof ? &*it : nullptr;
}

void DofMap::build(int dofs_per_node, std::vector<DofKind> kinds, std::vector<Tie> tie_list) {
  LOOM_ASSERT(dofs_per_node > 0 && kinds.size() % std::size_t(dofs_per_node) == 0, "dof kinds do not match nodes");
  per_node = dofs_per_node;
  kind = std::move(kinds);
  equation.assign(kind.size(), kNoIndex);
  n_free = 0;
  for (std::size_t k = 0; k < kind.size(); ++k)
    if (kind[k] == DofKind::free) equation[k] = n_free++;
  ties = std::move(tie_list);
  std::sort(ties.begin(), ties.end(), [](const Tie& a, const Tie& b) { return a.dof < b.dof; });
  for ([[maybe_unused]] const Tie& t : ties) LOOM_ASSERT(kind[std::size_t(t.dof)] == DofKind::tied, "tie on a dof that is not tied");
}

}  // namespace loom
