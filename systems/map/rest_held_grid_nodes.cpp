#include "systems/map/rest_held_grid_nodes.hpp"

namespace loom {

template <int D>
void rest_held_grid_nodes(const StepContext&, const BoundaryConditions<D>& bc, Nodes<D>& grid_nodes) {
  Nodes<D>& g = grid_nodes;
  if (!g.v_n.used() || !bc.increments) return;
  for (const auto& p : bc.prescribed) {
    const int component = int(p.dof % bc.per_node);
    if (component >= D || bc.target[p.dof] != 0.0) continue;  // a pressure dof, or a node that moves this step
    g.v_n[p.node][component] = 0.0, g.a_n[p.node][component] = 0.0;
    g.v[p.node][component] = 0.0, g.a[p.node][component] = 0.0;
  }
}

template void rest_held_grid_nodes<2>(const StepContext&, const BoundaryConditions<2>&, Nodes<2>&);
template void rest_held_grid_nodes<3>(const StepContext&, const BoundaryConditions<3>&, Nodes<3>&);

}  // namespace loom
