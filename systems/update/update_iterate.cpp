#include "systems/update/update_iterate.hpp"

#include "engine/core/parallel.hpp"

namespace loom {

void update_iterate(double step, const LinearSystem& system, Nodes<2>& nodes) {
  const int pn = system.dofs.per_node;
  const bool phi = pn == 3 && nodes.phi.used(), p = pn == 3 && nodes.p_n.used();
  for_each_index(nodes.size(), [&](Index i) {
    for (int d = 0; d < 2; ++d) nodes.u[i][d] += step * system.increment_full[i * pn + d];
    if (phi) nodes.phi[i] += step * system.increment_full[i * pn + 2];
    if (p) nodes.p[i] += step * system.increment_full[i * pn + 2];
  });
}

void reset_iterate(Nodes<2>& nodes) {
  const bool phi = nodes.phi.used(), p = nodes.p_n.used();
  for_each_index(nodes.size(), [&](Index i) {
    nodes.u[i] = nodes.u_n[i];
    if (phi) nodes.phi[i] = nodes.phi_n[i];
    if (p) nodes.p[i] = nodes.p_n[i];
  });
}

}  // namespace loom
