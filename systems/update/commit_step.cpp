#include "systems/update/commit_step.hpp"

#include "engine/core/errors.hpp"
#include "engine/core/parallel.hpp"
#include "systems/assemble/compute_geometry.hpp"
#include "systems/assemble/elements/displacement_point.hpp"
#include "systems/update/time_integrator.hpp"

namespace loom {

template <int D>
void commit_step(const StepContext& ctx, const std::vector<Cells>& cells, Nodes<D>& nodes, std::vector<QuadPoints<D>>& quad) {
  // Simplices of seed 001's formulations are integrated on their domains (commit_domains); their one point
  // carries the triangle's P1 deformation gradient for output, advanced here while u_n is the old one.
  for (std::size_t b = 0; b < cells.size(); ++b) {
    if (!integrates_on_domains(cells[b].formulation)) continue;
    QuadPoints<D>& q = quad[b];
    for_each_index(cells[b].size(), [&](Index c) {
      NodalVectors<D + 1, D> du;
      for (int a = 0; a < D + 1; ++a) du.row(a) = (nodes.u[cells[b].node(c, a)] - nodes.u_n[cells[b].node(c, a)]).transpose();
      q.F[c] = deformation_gradient<D + 1, D>(du, Eigen::Map<const NodalVectors<D + 1, D>>(q.grad(c)), q.F_n[c]);
    });
  }
  const bool dynamic = nodes.v.used();
  const TimeIntegrator integrator = time_integrator_of(ctx.scene->time, ctx.dt);
  for_each_index(nodes.size(), [&](Index i) {
    if (dynamic && integrator.second_order()) {
      const Vec<D> du = nodes.u[i] - nodes.u_n[i];
      nodes.a[i] = integrator.template acceleration<D>(du, nodes.v_n[i], nodes.a_n[i]);
      nodes.v[i] = integrator.template velocity<D>(du, nodes.v_n[i], nodes.a_n[i], nodes.a[i]);
      nodes.a_n[i] = nodes.a[i];
      nodes.v_n[i] = nodes.v[i];
    } else if (dynamic) {
      const Vec<D> v = (nodes.u[i] - nodes.u_n[i]) / ctx.dt;
      nodes.a[i] = (v - nodes.v_n[i]) / ctx.dt;
      nodes.v[i] = v;
      nodes.a_n[i] = nodes.a[i];
      nodes.v_n[i] = v;
    }
    nodes.u_n[i] = nodes.u[i];
    if (nodes.phi.used()) nodes.phi_n[i] = nodes.phi[i];
    if (nodes.p_n.used()) nodes.p_n[i] = nodes.p[i];
  });
  for (auto& q : quad)
    for_each_index(q.size(), [&](Index p) {
      q.F_n[p] = q.F[p];
      if (q.be_n.used()) q.be_n[p] = q.be[p];  // the return map of the converged iterate (the last assembly's)
    });
  const Index bad = compute_geometry(nodes, cells, quad);
  // Newton accepted the state only if every cell had J > 0, so this is a contract, not user input.
  LOOM_CHECK(bad == 0, RunError, bad << " cells are inverted in the converged configuration of step " << ctx.step);
}

template void commit_step<2>(const StepContext&, const std::vector<Cells>&, Nodes<2>&, std::vector<QuadPoints<2>>&);
template void commit_step<3>(const StepContext&, const std::vector<Cells>&, Nodes<3>&, std::vector<QuadPoints<3>>&);

}  // namespace loom
