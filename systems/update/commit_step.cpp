#include "systems/update/commit_step.hpp"

#include "engine/core/errors.hpp"
#include "engine/core/parallel.hpp"
#include "systems/assemble/compute_geometry.hpp"

namespace loom {

void commit_step(const StepContext& ctx, const std::vector<Cells>& cells, Nodes<2>& nodes,
                 std::vector<QuadPoints<2>>& quad) {
  const bool dynamic = nodes.v.used();
  for_each_index(nodes.size(), [&](Index i) {
    if (dynamic) {
      const Vec2 v = (nodes.u[i] - nodes.u_n[i]) / ctx.dt;
      nodes.a[i] = (v - nodes.v_n[i]) / ctx.dt;
      nodes.v[i] = v;
      nodes.a_n[i] = nodes.a[i];
      nodes.v_n[i] = v;
    }
    nodes.u_n[i] = nodes.u[i];
    if (nodes.phi.used()) nodes.phi_n[i] = nodes.phi[i];
  });
  for (auto& q : quad) for_each_index(q.size(), [&](Index p) { q.F_n[p] = q.F[p]; });
  const Index bad = compute_geometry(nodes, cells, quad);
  // Newton accepted the state only if every cell had J > 0, so this is a contract, not user input.
  LOOM_CHECK(bad == 0, RunError, bad << " cells are inverted in the converged configuration of step " << ctx.step);
}

}  // namespace loom
