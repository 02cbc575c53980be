#include "engine/linalg/dof_map.hpp"

#include "engine/core/errors.hpp"

namespace loom {

void DofMap::build(int dofs_per_node, std::vector<DofKind> kinds) {
  LOOM_ASSERT(dofs_per_node > 0 && kinds.size() % std::size_t(dofs_per_node) == 0, "dof kinds do not match nodes");
  per_node = dofs_per_node;
  kind = std::move(kinds);
  equation.assign(kind.size(), kNoIndex);
  n_free = 0;
  for (std::size_t k = 0; k < kind.size(); ++k)
    if (kind[k] == DofKind::free) equation[k] = n_free++;
}

}  // namespace loom
