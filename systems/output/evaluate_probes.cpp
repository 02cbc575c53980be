#include "systems/output/evaluate_probes.hpp"

#include <limits>

namespace loom {

ProbePlan plan_probes(const SceneSpec& scene, const Nodes<2>& nodes, const std::vector<Index>& node_body) {
  ProbePlan plan;
  plan.probes = scene.probes;
  for (const auto& p : scene.probes) {
    Index best = kNoIndex;
    if (p.kind == ProbeKind::point) {
      double best_d = std::numeric_limits<double>::max();
      for (Index i = 0; i < nodes.size(); ++i) {
        if (p.body != kNoIndex && node_body[std::size_t(i)] != p.body) continue;
        const double d = (nodes.X[i] - p.at).squaredNorm();
        if (d < best_d) best_d = d, best = i;
      }
    }
    plan.node.push_back(best);
  }
  return plan;
}

void evaluate_probes(const StepContext&, const ProbePlan& plan, const Nodes<2>& nodes, const LinearSystem& system,
                     const BoundaryConditions<2>& bc, int newton_iterations, std::vector<double>& values) {
  values.assign(plan.probes.size(), 0.0);
  for (std::size_t k = 0; k < plan.probes.size(); ++k) {
    const ProbeSpec& p = plan.probes[k];
    switch (p.kind) {
      case ProbeKind::reaction: {
        double sum = 0.0;
        for (Index e : bc.boundary_prescribed[std::size_t(p.boundary)]) {
          const Index dof = bc.prescribed[std::size_t(e)].dof;
          if (dof % system.dofs.per_node == p.component) sum += system.residual_full[dof];
        }
        values[k] = sum;
        break;
      }
      case ProbeKind::point:
        values[k] = nodes.u_n[plan.node[k]][p.component];
        break;
      case ProbeKind::newton:
        values[k] = newton_iterations;
        break;
    }
  }
}

}  // namespace loom
