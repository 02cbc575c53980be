#include "systems/output/particle_probes.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "engine/mesh/quad9_shape.hpp"
#include "systems/output/coupled_cell.hpp"
#include "systems/output/elastic_energy.hpp"

namespace loom {
namespace {

// Method mpm_fem: the FEM cells' energies at their Gauss points on the undeformed cells (X^ = X - u_n, after the
// step's commit u_n is the FEM nodes' displacement): kinetic 1/2 rho_i V_0 |v_g|^2 (the consistent mass's quadratic
// form), elastic V_0 psi(F), F = dx/dX^, potential -rho V_0 b . u_g.
void add_fem_energy(const StepContext& ctx, const std::vector<BodyMaterial>& materials, const GridView<2>& g, const BoundaryConditions<2>& bc,
                    double& kinetic, double& elastic, double& potential) {
  const SceneSpec& scene = *ctx.scene;
  const Quad9Gauss& rule = quad9_gauss();
  const Index first = g.activity.always_active_from;
  for (Index c = first; c < g.grid.size(); ++c) {
    const Index b = g.grid.body[c];
    const double rho = scene.materials[std::size_t(scene.bodies[std::size_t(b)].material)].density;
    const double rho_i = scene.bodies[std::size_t(b)].unit_inertia ? 1.0 : rho;
    Quad9Coordinates x, X;
    coupled_cell_coordinates(g.grid, g.nodes, c, x, X);
    for (std::size_t q = 0; q < 9; ++q) {
      double det = 0.0;
      const Quad9Gradients dN = quad9_gradients(X, rule.xi[q], &det);
      const Quad9Values N = quad9_shape(rule.xi[q]);
      const double V0 = rule.weight[q] * det;
      Vec2 v = Vec2::Zero(), u = Vec2::Zero();
      for (int a = 0; a < 9; ++a) {
        const Index i = g.grid.node(c, a);
        v += N[a] * g.nodes.v[i], u += N[a] * (g.nodes.u_n[i] + g.nodes.u[i]);
      }
      Mat3 F = Mat3::Identity();
      F.topLeftCorner<2, 2>() = x.transpose() * dN;
      kinetic += 0.5 * rho_i * V0 * v.squaredNorm();
      elastic += V0 * elastic_energy(materials[std::size_t(b)], F, false, 0.0);
      if (!bc.fem_body_force.empty()) potential -= rho * V0 * bc.fem_body_force[std::size_t(9 * (c - first)) + q].dot(u);
    }
  }
}

// The largest (max) or smallest coordinate reached from the other end of the sorted coordinates without a step
// wider than gap.
double extent_before_gap(std::vector<double>& x, bool max, double gap) {
  if (x.empty()) return max ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
  std::sort(x.begin(), x.end());
  if (!max) std::reverse(x.begin(), x.end());
  std::size_t i = 0;
  while (i + 1 < x.size() && std::abs(x[i + 1] - x[i]) <= gap) ++i;
  return x[i];
}

}  // namespace

ParticleProbePlan plan_particle_probes(const SceneSpec& scene) {
  ParticleProbePlan plan;
  plan.probes = scene.probes;
  Index n_tracers = 0;
  for (const auto& p : scene.probes) plan.tracer.push_back(p.kind == ProbeKind::point ? n_tracers++ : kNoIndex);
  return plan;
}

double pressure_jump(const GridView<2>& g) {
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

template <int D>
void evaluate_particle_probes(const StepContext& ctx, const ParticleProbePlan& plan, const std::vector<BodyMaterial>& materials,
                              const Points<D>& particles, const Points<D>& probe_points, const Points<D>& traction_points,
                              const GridView<D>& grid,
                              const LinearSystem& system, const BoundaryConditions<D>& bc, int newton_iterations,
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
        std::vector<double> along;
        for (Index i = 0; i < particles.X.size(); ++i) {
          if (p.body != kNoIndex && particles.body[i] != p.body) continue;  // several bodies: the probe's
          const auto at = particles.position(i);
          const double x = p.component == 4 ? std::hypot(at[0], at[1]) : at[p.component];  // 4: r, the distance from the z axis
          e = p.max ? std::max(e, x) : std::min(e, x);
          if (p.gap > 0.0) along.push_back(x);
        }
        values[k] = p.gap > 0.0 ? extent_before_gap(along, p.max, p.gap) : e;
        break;
      }
      case ProbeKind::energy: {
        double kinetic = 0.0, elastic = 0.0, potential = 0.0;
        for (Index i = 0; i < particles.X.size(); ++i) {
          if (particles.v.used()) kinetic += 0.5 * particles.mass[i] * particles.v[i].squaredNorm();
          const BodyMaterial& m = materials[std::size_t(particles.body[i])];
          const auto* hp = std::get_if<HenckyPerzyna>(&m.model);
          elastic += particles.volume[i] * (hp && particles.be.used() ? hp->energy(particles.be[i])  // the stored part of b^e
                                                                      : elastic_energy(m, particles.F[i], mixed, mixed ? particles.pressure[i] : 0.0));
          if (!bc.particle_body_force.empty()) potential -= particles.mass[i] * bc.particle_body_force[std::size_t(i)].dot(particles.u[i]);
        }
        // Dead loads on the traction points: -f . u, the potential of a load held at its present value.
        for (std::size_t q = 0; q < bc.traction_point_force.size(); ++q)
          potential -= bc.traction_point_force[q].dot(traction_points.u[Index(q)]);
        if constexpr (D == 2)
          if (grid.activity.always_active_from != kNoIndex) add_fem_energy(ctx, materials, grid, bc, kinetic, elastic, potential);
        values[k] = p.energy == EnergyPart::kinetic     ? kinetic
                    : p.energy == EnergyPart::elastic   ? elastic
                    : p.energy == EnergyPart::potential ? potential
                    : p.energy == EnergyPart::total     ? kinetic + elastic
                                                        : kinetic + elastic + potential;
        break;
      }
      case ProbeKind::angular_momentum: {  // about `at`, of the particles (method mpm; the loader refuses mpm_fem)
        double L = 0.0;  // 2D: the out-of-plane moment; 3D: the moment's component
        for (Index i = 0; i < particles.X.size(); ++i) {
          if constexpr (D == 2) {
            const Vec2 r = particles.position(i) - p.at;
            L += particles.mass[i] * (r.x() * particles.v[i].y() - r.y() * particles.v[i].x());
          } else {
            const Vec3 r = particles.position(i) - Vec3(p.at.x(), p.at.y(), p.at_z);
            L += particles.mass[i] * r.cross(particles.v[i])[p.component];
          }
        }
        values[k] = L;
        break;
      }
      case ProbeKind::pressure_jump:  // 2D (the loader refuses it in 3D)
        if constexpr (D == 2) values[k] = grid.nodes.p.used() ? pressure_jump(grid) : kNaN;
        else values[k] = kNaN;
        break;
      case ProbeKind::volume:  // fem and pfem only (rejected by the scene checks for mpm)
      case ProbeKind::speed:
      case ProbeKind::mass:
      case ProbeKind::stress:
      case ProbeKind::wall_force:  // [[wall]] is refused for method mpm
      case ProbeKind::penetration:
      case ProbeKind::section:  // fem, pfem and es_pfem meshes only (the loader refuses it for mpm)
      case ProbeKind::remesh: values[k] = kNaN; break;
    }
  }
}


template void evaluate_particle_probes<2>(const StepContext&, const ParticleProbePlan&, const std::vector<BodyMaterial>&, const Points<2>&,
                                          const Points<2>&, const Points<2>&, const GridView<2>&, const LinearSystem&, const BoundaryConditions<2>&, int,
                                          std::vector<double>&);
template void evaluate_particle_probes<3>(const StepContext&, const ParticleProbePlan&, const std::vector<BodyMaterial>&, const Points<3>&,
                                          const Points<3>&, const Points<3>&, const GridView<3>&, const LinearSystem&, const BoundaryConditions<3>&, int,
                                          std::vector<double>&);

}  // namespace loom
