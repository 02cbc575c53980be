#include "systems/assemble/assemble_grid_system.hpp"

#include <atomic>
#include <cmath>

#include "engine/core/parallel.hpp"
#include "engine/mesh/grid_shape.hpp"
#include "systems/assemble/elements/displacement_point.hpp"
#include "systems/assemble/grid_scatter.hpp"
#include "systems/assemble/elements/ghost_face.hpp"
#include "systems/assemble/elements/mixed_up_point.hpp"
#include "systems/assemble/materials/history_point.hpp"
#include "systems/update/grid_newmark.hpp"

namespace loom {
namespace {

template <int D>
struct Args {
  const StepContext& ctx;
  const GridAssemblyOptions& opt;
  const std::vector<BodyMaterial>& materials;
  const Cells& grid;
  const GridActivity& act;
  const Nodes<D>& g;
  const Points<D>& particles;
  const BoundaryConditions<D>& bc;
  PointLocations& loc;
  LinearSystem& system;
  std::atomic<Index>& inverted;
  bool dynamic;
};

template <int D>
Vec<D> body_force_of(const BoundaryConditions<D>& bc, Index p) {
  return bc.particle_body_force.empty() ? Vec<D>::Zero() : bc.particle_body_force[std::size_t(p)];
}

template <int NC, int D>
void assemble_displacement(const Args<D>& x) {
  // Materials with history (b^e at the particles): the step's return map from b^e_n, its b^e kept at the iterate.
  const bool carries_history = x.particles.be.used();
  const Column<Mat3>& history_n = x.particles.be;
  Column<Mat3>& history_step = x.loc.be;
  const auto ahead = [&](Index c) {
    x.loc.prefetch_points_in(c, x.particles.F, x.loc.N, x.loc.F, x.particles.volume, x.particles.body, x.particles.be);
    if (x.opt.tangent) prefetch_scatter_row(x.act.scatter_entry[std::size_t(c)], x.system.scatter[0]);
  };
  for_each_active_cell_by_colour_looking_ahead(x.act, ahead, [&](Index c) {
    const Index entry = x.act.scatter_entry[std::size_t(c)];
    if (x.opt.tangent) prefetch_scatter_entries(entry, x.system.scatter[0], x.system);
    NodalVectors<NC, D> du;
    for (int a = 0; a < NC; ++a) du.row(a) = x.g.u[x.grid.node(c, a)].transpose();
    ElementVector<NC, D> r = ElementVector<NC, D>::Zero();
    ElementMatrix<NC, D> K = ElementMatrix<NC, D>::Zero();
    ElementMatrix<NC, D>* K_needed = x.opt.tangent || cell_lags(entry, x.system.scatter[0], x.bc, x.g, x.system.dofs) ? &K : nullptr;
    const Index* pts = x.loc.points_in(c);
    for (Index k = 0; k < x.loc.count_in(c); ++k) {
      const Index p = pts[k];
      const Mat3& F_n = x.particles.F[p];
      const double Vn = x.particles.volume[p] * F_n.determinant();
      const CornerGradients<NC, D> dN = grid_shape_gradients<NC>(x.grid, x.g, c, x.loc.N[p]);
      const PointHistory history = carries_history ? PointHistory{&F_n, &history_n[p], x.ctx.dt, &history_step[p]} : PointHistory{};
      const bool ok = visit_point_material(x.materials[std::size_t(x.particles.body[p])].model, history,
                                           [&](const auto& m) { return add_displacement_point<NC, D>(m, du, dN, Vn, F_n, x.loc.F[p], r, K_needed); });
      if (!ok) return void(x.inverted.fetch_add(1, std::memory_order_relaxed));
    }
    scatter_cell<D * NC>(entry, x.system.scatter[0], x.bc, x.g, x.opt.tangent, r, K, x.system);
  });
}

// The length scale of tau1 (seed 003 eq 21): h^2 = the cell's area in 2D, V^(2/3) in 3D (h = V^(1/3)).
template <int D>
double cell_size_squared(double measure) {
  if constexpr (D == 2) return measure;
  else return std::cbrt(measure) * std::cbrt(measure);
}

template <int NC, int D>
void assemble_mixed(const Args<D>& x) {
  const double dt = x.ctx.dt;
  const auto ahead = [&](Index c) {
    x.loc.prefetch_points_in(c, x.particles.F, x.loc.N, x.loc.F, x.particles.volume, x.particles.body, x.particles.mass, x.bc.particle_body_force);
    if (x.opt.tangent) prefetch_scatter_row(x.act.scatter_entry[std::size_t(c)], x.system.scatter[0]);
  };
  for_each_active_cell_by_colour_looking_ahead(x.act, ahead, [&](Index c) {
    if (x.opt.tangent) prefetch_scatter_entries(x.act.scatter_entry[std::size_t(c)], x.system.scatter[0], x.system);
    UpCellValues<NC, D> cell;
    for (int a = 0; a < NC; ++a) {
      const Index i = x.grid.node(c, a);
      cell.du.row(a) = x.g.u[i].transpose();
      cell.p[a] = x.g.p[i];
      if (x.dynamic) cell.a.row(a) = newmark_acceleration(x.g, i, dt).transpose();
      if (x.g.proj_u.used()) cell.proj_u.row(a) = x.g.proj_u[i].transpose(), cell.proj_p[a] = x.g.proj_p[i];
    }
    UpVector<NC, D> r = UpVector<NC, D>::Zero();
    UpMatrix<NC, D> K = UpMatrix<NC, D>::Zero();
    const Index entry = x.act.scatter_entry[std::size_t(c)];
    UpMatrix<NC, D>* K_needed = x.opt.tangent || cell_lags(entry, x.system.scatter[0], x.bc, x.g, x.system.dofs) ? &K : nullptr;
    PppAccumulator<NC, D> ppp;
    const double h2 = cell_size_squared<D>(x.grid.measure[c]);  // once per cell: the cube roots are not free
    const Index* pts = x.loc.points_in(c);
    double inv_mu = 0.0;
    bool use_ppp = false;
    for (Index k = 0; k < x.loc.count_in(c); ++k) {
      const Index p = pts[k];
      const Index body = x.particles.body[p];
      const BodySpec& spec = x.ctx.scene->bodies[std::size_t(body)];
      const NeoHookeSplit& m = std::get<NeoHookeSplit>(x.materials[std::size_t(body)].model);
      UpPoint<NC, D> pt;
      pt.N = x.loc.N[p].template head<NC>();
      pt.dN = grid_shape_gradients<NC>(x.grid, x.g, c, x.loc.N[p]);
      pt.V0 = x.particles.volume[p];
      pt.F_n = x.particles.F[p];
      const double Vn = pt.V0 * pt.F_n.determinant();
      pt.rho_n = x.particles.mass[p] / Vn;
      pt.b = body_force_of(x.bc, p);
      UpStabilisation st;
      st.vms = spec.stabilisation == Stabilisation::asgs || spec.stabilisation == Stabilisation::osgs;
      st.projected = spec.stabilisation == Stabilisation::osgs;
      st.tau1 = spec.tau_c1 * h2 / (2.0 * m.mu);  // eq 21
      st.tau2 = 2.0 * spec.tau_c2 * m.mu;
      st.c_a = x.dynamic ? newmark_stiffness(dt) : 0.0;
      if (!add_up_point<NC, D>(m, st, pt, cell, x.loc.F[p], r, K_needed)) return void(x.inverted.fetch_add(1, std::memory_order_relaxed));
      if (spec.stabilisation == Stabilisation::ppp) ppp.add(pt.N, Vn), inv_mu = 1.0 / m.mu, use_ppp = true;
    }
    if (use_ppp) ppp.apply(inv_mu, cell.p, r, K_needed);
    scatter_cell<(D + 1) * NC>(entry, x.system.scatter[0], x.bc, x.g, x.opt.tangent, r, K, x.system);
  });
}

// Faces worth one task: a colour holds a hundred or two faces at 10^4 particles, fewer than kParallelGrain, and a face's
// 12 x 12 matrix is a particle cell's work.
constexpr Index kGhostFaceGrain = 32;

// Face ghost penalty (grid.ghost_penalty): residual K w and tangent K of every listed face, by colour.
template <int NC, int PN>
void assemble_ghost(const Args<2>& x) {
  const SceneSpec& scene = *x.ctx.scene;
  const double gamma_0 = scene.grid.ghost_penalty;
  const double mu = scene.materials[std::size_t(scene.bodies[std::size_t(mpm_body_index(scene))].material)].mu;
  const Cells& faces = x.act.ghost_faces;
  constexpr int NE = PN * kGhostFaceNodes<NC>;
  const CellScatter& sc = x.system.scatter[1];
  const auto ahead = [&](Index f) {
    if (x.opt.tangent) prefetch_scatter_row(f, sc);
  };
  for (std::size_t k = 0; k + 1 < faces.colour_offsets.size(); ++k)
    for_each_in_looking_ahead(faces.by_colour.data() + faces.colour_offsets[k], faces.colour_offsets[k + 1] - faces.colour_offsets[k], ahead, [&](Index f) {
      if (x.opt.tangent) prefetch_scatter_entries(f, sc, x.system);
      const auto s = std::size_t(f);
      const GhostFace<NC> face =
          ghost_face<NC>(x.grid, x.g, x.act.ghost_cells[2 * s], x.act.ghost_cells[2 * s + 1], x.act.ghost_ends[2 * s], x.act.ghost_ends[2 * s + 1]);
      const Eigen::Matrix<double, NE, NE> K = ghost_penalty_matrix<NC, PN>(x.grid, x.g, face, gamma_0, mu);
      Eigen::Matrix<double, NE, 1> w;
      for (int a = 0; a < kGhostFaceNodes<NC>; ++a) {
        const Index i = face.nodes[std::size_t(a)];
        w.template segment<2>(PN * a) = x.g.u[i];
        if constexpr (PN == 3) w[PN * a + 2] = x.g.p[i];
      }
      Eigen::Matrix<double, NE, 1> r = K * w;
      scatter_cell<NE>(f, sc, x.bc, x.g, x.opt.tangent, r, K, x.system);
    }, Execution::parallel, kGhostFaceGrain);
}

}  // namespace

template <int D>
AssemblyResult assemble_grid_system(const StepContext& ctx, const GridAssemblyOptions& opt,
                                    const std::vector<BodyMaterial>& materials, const Cells& grid, const GridActivity& activity,
                                    const Nodes<D>& grid_nodes, const Points<D>& particles, const BoundaryConditions<D>& bc,
                                    PointLocations& loc, LinearSystem& system) {
  auto& A = system.pattern.matrix;
  if (opt.tangent) zero_in_parallel(A.valuePtr(), A.nonZeros());
  system.residual_full.setZero();
  std::atomic<Index> inverted{0};
  const bool dynamic = ctx.scene->time.integrator == Integrator::newmark;
  const Args<D> args{ctx, opt, materials, grid, activity, grid_nodes, particles, bc, loc, system, inverted, dynamic};
  const bool mixed = system.dofs.per_node == D + 1;
  if constexpr (D == 3) {  // tet4
    mixed ? assemble_mixed<4, 3>(args) : assemble_displacement<4, 3>(args);
  } else {
    const bool quad = grid.stride == 4;
    if (mixed) quad ? assemble_mixed<4, 2>(args) : assemble_mixed<3, 2>(args);
    else quad ? assemble_displacement<4, 2>(args) : assemble_displacement<3, 2>(args);
    if (activity.ghost_faces.size() > 0 && system.scatter.size() > 1) {
      if (mixed) quad ? assemble_ghost<4, 3>(args) : assemble_ghost<3, 3>(args);
      else quad ? assemble_ghost<4, 2>(args) : assemble_ghost<3, 2>(args);
    }
  }

  // Nodal terms on active nodes: lumped inertia (Newmark) and external loads.
  const DofMap& dofs = system.dofs;
  const int pn = dofs.per_node;
  const bool inertia = dynamic && opt.inertia;
  const double c_a = dynamic ? newmark_stiffness(ctx.dt) : 0.0;
  double* values = A.valuePtr();
  for_each_index(grid_nodes.size(), [&](Index i) {
    if (dofs.kind[std::size_t(i) * std::size_t(pn)] == DofKind::absent) return;
    const Vec<D> a = inertia ? newmark_acceleration(grid_nodes, i, ctx.dt) : Vec<D>::Zero();
    for (int d = 0; d < D; ++d) {
      const Index dof = dofs.dof(i, d);
      double r = -bc.external[dof];
      if (inertia) {
        r += grid_nodes.lumped_mass[i] * a[d];
        const Index eq = dofs.equation[std::size_t(dof)];
        if (opt.tangent && eq != kNoIndex) values[system.pattern.diagonal_slot[std::size_t(eq)]] += grid_nodes.lumped_mass[i] * c_a;
      }
      system.residual_full[dof] += r;
    }
  });
  for_each_index(dofs.n_dofs(), [&](Index dof) {
    const Index eq = dofs.equation[std::size_t(dof)];
    if (eq != kNoIndex) system.residual[eq] = system.residual_full[dof];
  });
  pin_dormant_dofs(activity, opt.tangent, system);
  return {inverted.load()};
}

template AssemblyResult assemble_grid_system<2>(const StepContext&, const GridAssemblyOptions&, const std::vector<BodyMaterial>&, const Cells&,
                                                const GridActivity&, const Nodes<2>&, const Points<2>&, const BoundaryConditions<2>&,
                                                PointLocations&, LinearSystem&);
template AssemblyResult assemble_grid_system<3>(const StepContext&, const GridAssemblyOptions&, const std::vector<BodyMaterial>&, const Cells&,
                                                const GridActivity&, const Nodes<3>&, const Points<3>&, const BoundaryConditions<3>&,
                                                PointLocations&, LinearSystem&);

}  // namespace loom
