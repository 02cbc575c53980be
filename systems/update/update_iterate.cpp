#include "systems/update/update_iterate.hpp"

#include "engine/core/parallel.hpp"

namespace loom {

template <int D>
void update_iterate(double step, const LinearSystem& system, Nodes<D>& nodes) {
  const int pn = system.dofs.per_node;
  // The node's dof after its D displacements is the dilatation phi or the pressure p (mixed formulations); in 3D a
  // node of 3 dofs has none ("3 dofs per node" meant "mixed" only in 2D).
  const bool extra = pn == D + 1;
  const bool phi = extra && nodes.phi.used(), p = extra && nodes.p_n.used();
  for_each_index(nodes.size(), [&](Index i) {
    for (int d = 0; d < D; ++d) nodes.u[i][d] += step * system.increment_full[i * pn + d];
    if (phi) nodes.phi[i] += step * system.increment_full[i * pn + D];
    if (p) nodes.p[i] += step * system.increment_full[i * pn + D];
  });
}

template <int D>
void reset_iterate(Nodes<D>& nodes) {
  const bool phi = nodes.phi.used(), p = nodes.p_n.used();
  for_each_index(nodes.size(), [&](Index i) {
    nodes.u[i] = nodes.u_n[i];
    if (phi) nodes.phi[i] = nodes.phi_n[i];
    if (p) nodes.p[i] = nodes.p_n[i];
  });
}

template <int D>
void predict_iterate(double dt, Nodes<D>& nodes) {
  reset_iterate(nodes);
  for_each_index(nodes.size(), [&](Index i) { nodes.u[i] += dt * nodes.v_n[i] + 0.5 * dt * dt * nodes.a_n[i]; });
}

template void update_iterate<2>(double, const LinearSystem&, Nodes<2>&);
template void update_iterate<3>(double, const LinearSystem&, Nodes<3>&);
template void reset_iterate<2>(Nodes<2>&);
template void reset_iterate<3>(Nodes<3>&);
template void predict_iterate<2>(double, Nodes<2>&);
template void predict_iterate<3>(double, Nodes<3>&);

}  // namespace loom
