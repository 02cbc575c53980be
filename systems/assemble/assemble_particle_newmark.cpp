#include "systems/assemble/assemble_particle_newmark.hpp"

#include <atomic>

#include "engine/mesh/grid_point_shape.hpp"
#include "engine/mesh/quad9_shape.hpp"
#include "systems/assemble/elements/particle_newmark_point.hpp"
#include "systems/assemble/elements/receding_contact.hpp"
#include "systems/assemble/elements/soft_stiffness.hpp"
#include "systems/assemble/materials/history_point.hpp"
#include "systems/assemble/grid_scatter.hpp"

namespace loom {

template <int NEN>
Eigen::Matrix<double, NEN, 2> particle_trial_gradients(const Eigen::Matrix<double, NEN, 2>& dN, Index receding_side, double c_c) {
  if constexpr (NEN == 9) {
    if (receding_side != kNoIndex && c_c > 0.0) return receding_trial_gradients(dN, int(receding_side), c_c);
  }
  return dN;
}

namespace {

// An FEM cell of method mpm_fem (seed 004 eqs 38-43, total Lagrangian on the undeformed cell, X^ = X - u_n):
// each 3 x 3 Gauss point is a particle of the step's reference configuration X~ = X^ + u_n, with
// F_n = dX~/dX^, volume V_0 = w det J^, inertia mass rho_i V_0 and the nodal Newmark state interpolated (the
// rule is linear in it, so the nodal accelerations interpolate to the point's): the particle kernel then gives
// the consistent mass rho_i int N_A N_B and the stress term int P : grad^ N_A. rho_i is the material's density
// or one (the paper's eq 41, `inertia = "unit_density"`); the body force is rho b either way.
template <class MaterialT>
bool add_fem_cell(const MaterialT& material, const ParticleNewmark& tn, const Nodes<2>& g, const Cells& grid, Index c, double rho_inertia,
                  double rho, const Vec2* body_force, const NodalVectors<9>& du, ElementVector<9>& r, ElementMatrix<9>& K, bool tangent) {
  Quad9Coordinates X, X0;
  for (int a = 0; a < 9; ++a) {
    const Index i = grid.node(c, a);
    X.row(a) = g.X[i].transpose();
    X0.row(a) = (g.X[i] - g.u_n[i]).transpose();
  }
  const Quad9Gauss& rule = quad9_gauss();
  for (std::size_t q = 0; q < 9; ++q) {
    double det0 = 0.0;
    const Quad9Gradients dN0 = quad9_gradients(X0, rule.xi[q], &det0);
    ParticlePoint<9> pt;
    pt.N = quad9_shape(rule.xi[q]);
    pt.dN = quad9_gradients(X, rule.xi[q]);
    pt.dN_trial = pt.dN;
    pt.V0 = rule.weight[q] * det0;
    pt.mass = rho_inertia * pt.V0;
    const Eigen::Matrix2d Fn = X.transpose() * dN0;  // dX~/dX^
    pt.F_n.topLeftCorner<2, 2>() = Fn;
    pt.v_n.setZero(), pt.a_n.setZero();
    for (int a = 0; a < 9; ++a) pt.v_n += pt.N[a] * g.v[grid.node(c, a)], pt.a_n += pt.N[a] * g.a[grid.node(c, a)];
    pt.b = body_force ? Vec2(body_force[q] * (rho / rho_inertia)) : Vec2::Zero();
    Mat3 F;
    if (!add_particle_newmark_point<9>(material, tn, pt, du, F, r, tangent ? &K : nullptr)) return false;
  }
  return true;
}

enum class CellPass { all, particle_cells, fem_cells };

template <int NEN>
void assemble_cells(const StepContext& ctx, bool tangent, const std::vector<BodyMaterial>& materials, const Cells& grid,
                    const GridActivity& act, const Nodes<2>& g, const Points<2>& particles, const BoundaryConditions<2>& bc,
                    PointLocations& loc, LinearSystem& system, std::atomic<Index>& inverted, CellPass pass) {
  const SceneSpec& scene = *ctx.scene;
  const ParticleNewmark tn{scene.time.beta, scene.time.gamma, ctx.dt};
  const SoftStiffness soft{scene.mpm.soft_c1, scene.mpm.soft_c2};
  const double c_c = scene.mpm.receding_contact;
  const bool receding = c_c > 0.0 && loc.receding.used();
  const double mu = scene.materials[std::size_t(scene.bodies[std::size_t(mpm_body_index(scene))].material)].mu;
  const Index fem_from = act.always_active_from;
  const bool carries_history = particles.be.used();  // b^e at the particles: the step's return map, b^e kept at the iterate
  // About 64 particles' work per task: cells of a fine body hold tens to thousands of them.
  const Index grain = std::max<Index>(1, 64 * act.n_active_cells() / std::max<Index>(1, particles.X.size()));
  const auto ahead = [&](Index c) {
    loc.prefetch_points_in(c, loc.N, loc.xi, loc.F, loc.receding, particles.mass, particles.volume, particles.F, particles.v, particles.a,
                           particles.body, bc.particle_body_force, particles.be);
  };
  for_each_active_cell_by_colour_looking_ahead(act, ahead, [&](Index c) {
    const bool fem_cell = fem_from != kNoIndex && c >= fem_from;
    if ((pass == CellPass::particle_cells && fem_cell) || (pass == CellPass::fem_cells && !fem_cell)) return;
    const Index entry = act.scatter_entry[std::size_t(c)];
    NodalVectors<NEN> du;
    for (int a = 0; a < NEN; ++a) du.row(a) = g.u[grid.node(c, a)].transpose();
    ElementVector<NEN> r = ElementVector<NEN>::Zero();
    ElementMatrix<NEN> K = ElementMatrix<NEN>::Zero();
    const bool need_K = tangent || cell_lags(entry, system.scatter[0], bc, g, system.dofs);  // the Dirichlet lift needs K
    if constexpr (NEN == 9) {
      if (fem_cell) {
        const Index b = grid.body[c];
        const MaterialSpec& ms = scene.materials[std::size_t(scene.bodies[std::size_t(b)].material)];
        const double rho_inertia = scene.bodies[std::size_t(b)].unit_inertia ? 1.0 : ms.density;
        const Vec2* bf = bc.fem_body_force.empty() ? nullptr : &bc.fem_body_force[std::size_t(9 * (c - fem_from))];
        const bool ok = std::visit([&](const auto& m) { return add_fem_cell(m, tn, g, grid, c, rho_inertia, ms.density, bf, du, r, K, need_K); },
                                   materials[std::size_t(b)].model);
        if (!ok) return void(inverted.fetch_add(1, std::memory_order_relaxed));
        scatter_cell<2 * NEN>(entry, system.scatter[0], bc, g, tangent, r, K, system);
        return;
      }
    }
    // 1. Soft stiffness (constant and linear: K du), on the flags of the step's active set.
    const double C = act.inside_nodes.empty() ? 0.0 : soft.factor(act.inside_nodes[std::size_t(act.active_index[std::size_t(c)])], NEN);
    if (C > 0.0) {
      ElementMatrix<NEN> Ks = ElementMatrix<NEN>::Zero();
      for_each_cell_gauss_point<NEN>(grid, g, c, [&](const NodalVectors<NEN>& dN, double w) { add_soft_stiffness_point<NEN>(dN, mu * C * w, Ks); });
      ElementVector<NEN> u;
      for (int a = 0; a < NEN; ++a) u.template segment<2>(2 * a) = du.row(a).transpose();
      r += Ks * u;
      K += Ks;
    }
    // 2. The particles.
    const Index* pts = loc.points_in(c);
    for (Index k = 0; k < loc.count_in(c); ++k) {
      const Index p = pts[k];
      const PointShape<NEN> s = point_shape<NEN>(grid, g, c, loc, p);
      ParticlePoint<NEN> pt;
      pt.N = s.N;
      pt.dN = s.dN;
      pt.dN_trial = receding ? particle_trial_gradients<NEN>(s.dN, loc.receding[p], c_c) : s.dN;
      pt.mass = particles.mass[p], pt.V0 = particles.volume[p];
      pt.F_n = particles.F[p];
      pt.v_n = particles.v[p], pt.a_n = particles.a[p];
      pt.b = bc.particle_body_force.empty() ? Vec2::Zero() : bc.particle_body_force[std::size_t(p)];
      const PointHistory history = carries_history ? PointHistory{&pt.F_n, &particles.be[p], ctx.dt, &loc.be[p]} : PointHistory{};
      const bool ok = visit_point_material(materials[std::size_t(particles.body[p])].model, history,
                                           [&](const auto& m) { return add_particle_newmark_point<NEN>(m, tn, pt, du, loc.F[p], r, need_K ? &K : nullptr); });
      if (!ok) return void(inverted.fetch_add(1, std::memory_order_relaxed));
    }
    scatter_cell<2 * NEN>(entry, system.scatter[0], bc, g, tangent, r, K, system);
  }, grain);
}

}  // namespace

template Eigen::Matrix<double, 4, 2> particle_trial_gradients<4>(const Eigen::Matrix<double, 4, 2>&, Index, double);
template Eigen::Matrix<double, 9, 2> particle_trial_gradients<9>(const Eigen::Matrix<double, 9, 2>&, Index, double);

AssemblyResult assemble_particle_newmark(const StepContext& ctx, bool tangent, const std::vector<BodyMaterial>& materials, const Cells& grid,
                                         const GridActivity& activity, const Nodes<2>& grid_nodes, const Points<2>& particles,
                                         const BoundaryConditions<2>& bc, PointLocations& loc, LinearSystem& system, Timers* timers) {
  auto& A = system.pattern.matrix;
  if (tangent) zero_in_parallel(A.valuePtr(), A.nonZeros());
  system.residual_full.setZero();
  std::atomic<Index> inverted{0};
  if (grid.stride == 9 && activity.always_active_from != kNoIndex && timers) {
    // Method mpm_fem: the FEM cells, then the cells with particles, each pass timed (both passes colour by colour).
    {
      ScopedTimer t(*timers, "newton/assemble/fem_cells");
      assemble_cells<9>(ctx, tangent, materials, grid, activity, grid_nodes, particles, bc, loc, system, inverted, CellPass::fem_cells);
    }
    ScopedTimer t(*timers, "newton/assemble/particle_cells");
    assemble_cells<9>(ctx, tangent, materials, grid, activity, grid_nodes, particles, bc, loc, system, inverted, CellPass::particle_cells);
  } else if (grid.stride == 9) {
    assemble_cells<9>(ctx, tangent, materials, grid, activity, grid_nodes, particles, bc, loc, system, inverted, CellPass::all);
  } else {
    assemble_cells<4>(ctx, tangent, materials, grid, activity, grid_nodes, particles, bc, loc, system, inverted, CellPass::all);
  }
  // External nodal loads (none yet: body forces act at the particles) and the free rows.
  const DofMap& dofs = system.dofs;
  for_each_index(dofs.n_dofs(), [&](Index dof) {
    const Index eq = dofs.equation[std::size_t(dof)];
    if (dofs.kind[std::size_t(dof)] != DofKind::absent) system.residual_full[dof] -= bc.external[dof];
    if (eq != kNoIndex) system.residual[eq] = system.residual_full[dof];
  });
  pin_dormant_dofs(activity, tangent, system);
  return {inverted.load()};
}

}  // namespace loom
