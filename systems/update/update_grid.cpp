#include "systems/update/update_grid.hpp"

#include "engine/core/parallel.hpp"
#include "systems/update/grid_newmark.hpp"

namespace loom {

template <int D>
void update_grid_iterate(const StepContext& ctx, double step, const LinearSystem& system, Nodes<D>& g) {
  const int pn = system.dofs.per_node;
  for_each_index(g.size(), [&](Index i) {
    for (int d = 0; d < D; ++d) g.u[i][d] += step * system.increment_full[i * pn + d];
    if (pn == D + 1) g.p[i] += step * system.increment_full[i * pn + D];
  });
  update_grid_kinematics(ctx, g);
}

template <int D>
void update_grid_kinematics(const StepContext& ctx, Nodes<D>& g) {
  if (!g.a.used() || !g.lumped_mass.used()) return;  // particle Newmark: no grid kinematics (mpm_fem's FEM nodes update at commit)
  for_each_index(g.size(), [&](Index i) {
    if (!(g.lumped_mass[i] > 0.0)) return;
    g.a[i] = newmark_acceleration(g, i, ctx.dt);
    g.v[i] = newmark_velocity(g, i, g.a[i], ctx.dt);
  });
}


template void update_grid_iterate<2>(const StepContext&, double, const LinearSystem&, Nodes<2>&);
template void update_grid_iterate<3>(const StepContext&, double, const LinearSystem&, Nodes<3>&);
template void update_grid_kinematics<2>(const StepContext&, Nodes<2>&);
template void update_grid_kinematics<3>(const StepContext&, Nodes<3>&);

}  // namespace loom
