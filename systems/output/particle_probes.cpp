#include "systems/output/particle_probes.hpp"

#include <cmath>
#include <limits>

namespace loom {
namespace {

double elastic_energy(const BodyMaterial& material, const Mat3& F, bool mixed, double pressure) {
  if (const auto* split = std::get_if<NeoHookeSplit>(&material.model)) {
    if (!mixed) return split->energy(F);
    NeoHookeSplit dev{split->mu, 0.0};
    return dev.energy(F) + 0.5 * pressure * pressure * split->inv_kappa;
  }
  if (const auto* nh = std::get_if<NeoHooke>(&material.model)) {
    const double lnJ = std::log(F.determinant());
    return 0.5 * nh->lambda * lnJ * lnJ + 0.5 * nh->mu * (F.squaredNorm() - 3.0) - nh->mu * lnJ;
  }
  const auto& le = std::get<LinearElastic>(material.model);
  const Mat3 eps = 0.5 * (F + F.transpose()) - Mat3::Identity();
  return 0.5 * le.lambda * eps.trace() * eps.trace() + le.mu * eps.squaredNorm();
}

}  // namespace

ParticleProbePlan plan_particle_probes(const SceneSpec& scene) {
  ParticleProbePlan plan;
  plan.probes = scene.probes;
  Index n_tracers = 0;
  for (const auto& p : scene.probes) plan.tracer.push_back(p.kind == ProbeKind::point ? n_tracers++ : kNoIndex);
  return plan;
}

double pressure_jump(const GridView& g) {
  double sum = 0.0;
  long long n = 0;
  for (Index c : g.activity.active_cells)
    for (int a = 0; a < g.grid.sides(); ++a) {
      const Index other = g.grid.neighbour[g.grid.sides() * c + a];
      if (other != kNoIndex && g.activity.cell_active[std::size_t(other)] && other < c) continue;  // counted from `other`
      const auto [i, j] = g.grid.side_corners(c, a);
      sum += std::abs(g.nodes.p[i] - g.nodes.p[j]);
      ++n;
    }
  return n ? sum / double(n) : 0.0;
}

void evaluate_particle_probes(const StepContext&, const ParticleProbePlan& plan, const std::vector<BodyMaterial>& materials,
                              const Points<2>& particles, const Points<2>& probe_points, const GridView& grid,
                              const LinearSystem& system, const BoundaryConditions<2>& bc, int newton_iterations,
                              std::vector<double>& values) {
  values.assign(plan.probes.size(), 0.0);
  const bool mixed = particles.pressure.used();
  for (std::size_t k = 0; k < plan.probes.size(); ++k) {
    const ProbeSpec& p = plan.probes[k];
    switch (p.kind) {
      case ProbeKind::reaction: {
        double sum = 0.0;
        for (Index e : bc.boundary_prescribed[std::size_t(p.boundary)]) {
          const Index dof = bc.prescribed[std::size_t(e)].dof;
          if (dof % bc.per_node == p.component && std::size_t(dof) < std::size_t(system.residual_full.size())) sum += system.residual_full[dof];
        }
        values[k] = sum;
        break;
      }
      case ProbeKind::point: values[k] = probe_points.u[plan.tracer[k]][p.component]; break;
      case ProbeKind::newton: values[k] = newton_iterations; break;
      case ProbeKind::extent: {
        double e = p.max ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
        for (Index i = 0; i < particles.X.size(); ++i) {
          const double x = particles.position(i)[p.component];
          e = p.max ? std::max(e, x) : std::min(e, x);
        }
        values[k] = e;
        break;
      }
      case ProbeKind::energy: {
        double kinetic = 0.0, elastic = 0.0;
        for (Index i = 0; i < particles.X.size(); ++i) {
          if (particles.v.used()) kinetic += 0.5 * particles.mass[i] * particles.v[i].squaredNorm();
          elastic += particles.volume[i] *
                     elastic_energy(materials[std::size_t(particles.body[i])], particles.F[i], mixed, mixed ? particles.pressure[i] : 0.0);
        }
        values[k] = p.energy == EnergyPart::kinetic ? kinetic : p.energy == EnergyPart::elastic ? elastic : kinetic + elastic;
        break;
      }
      case ProbeKind::pressure_jump: values[k] = grid.nodes.p.used() ? pressure_jump(grid) : kNaN; break;
      case ProbeKind::volume:  // fem and pfem only (rejected by the scene checks for mpm)
      case ProbeKind::speed:
      case ProbeKind::mass:
      case ProbeKind::stress:
      case ProbeKind::wall_force:  // [[wall]] is refused for method mpm
      case ProbeKind::penetration:
      case ProbeKind::remesh: values[k] = kNaN; break;
    }
  }
}

}  // namespace loom
