#include "systems/map/project_residuals.hpp"

#include "engine/core/parallel.hpp"
#include "engine/mesh/grid_shape.hpp"
#include "systems/update/grid_newmark.hpp"

namespace loom {

namespace {

// One cell's points: sum_p V_n N_I R(x_p) into the nodes (R_u = rho (b - a_h) + grad p_h, R_p = (J - 1) - p_h / kappa).
template <int NC, int D>
void project_cell(const StepContext& ctx, bool dynamic, const std::vector<BodyMaterial>& materials, const Cells& grid,
                  const Points<D>& particles, const PointLocations& loc, const BoundaryConditions<D>& bc, Nodes<D>& g, Index c) {
  const Index* corner = grid.cell_nodes(c);
  Eigen::Matrix<double, NC, 1> p;
  Eigen::Matrix<double, NC, D> a = Eigen::Matrix<double, NC, D>::Zero(), du;
  for (int i = 0; i < NC; ++i) {
    p[i] = g.p[corner[i]];
    du.row(i) = g.u[corner[i]].transpose();
    if (dynamic) a.row(i) = newmark_acceleration(g, corner[i], ctx.dt).transpose();
  }
  const Index* pts = loc.points_in(c);
  for (Index n = 0; n < loc.count_in(c); ++n) {
    const Index q = pts[n];
    const Eigen::Matrix<double, NC, 1> N = loc.N[q].template head<NC>();
    const CornerGradients<NC, D> dN = grid_shape_gradients<NC>(grid, g, c, loc.N[q]);
    const Mat3& F_n = particles.F[q];
    Mat3 dF = Mat3::Identity();
    dF.topLeftCorner<D, D>() += du.transpose() * dN;
    const double J = (dF * F_n).determinant();
    const double Vn = particles.volume[q] * F_n.determinant();
    const double rho = particles.mass[q] / Vn;
    const double ik = std::get<NeoHookeSplit>(materials[std::size_t(particles.body[q])].model).inv_kappa;
    const Vec<D> b = bc.particle_body_force.empty() ? Vec<D>::Zero() : bc.particle_body_force[std::size_t(q)];
    const Vec<D> Ru = rho * (b - a.transpose() * N) + dN.transpose() * p;
    const double Rp = (J - 1.0) - N.dot(p) * ik;
    for (int i = 0; i < NC; ++i) {
      const double w = Vn * N[i];
      g.proj_u[corner[i]] += w * Ru;
      g.proj_p[corner[i]] += w * Rp;
    }
  }
}

}  // namespace

template <int D>
void project_residuals(const StepContext& ctx, const std::vector<BodyMaterial>& materials, const Cells& grid,
                       const GridActivity& activity, const Points<D>& particles, const PointLocations& loc,
                       const BoundaryConditions<D>& bc, Nodes<D>& g) {
  const bool dynamic = ctx.scene->time.integrator == Integrator::newmark;
  for_each_index(g.size(), [&](Index i) { g.proj_u[i].setZero(), g.proj_p[i] = 0.0; });
  for (std::size_t k = 0; k + 1 < activity.colour_offsets.size(); ++k) {
    const Index* cells = activity.active_by_colour.data() + activity.colour_offsets[k];
    const auto ahead = [&](Index c) {
      loc.prefetch_points_in(c, loc.N, particles.F, particles.volume, particles.mass, particles.body, bc.particle_body_force);
    };
    for_each_in_looking_ahead(cells, activity.colour_offsets[k + 1] - activity.colour_offsets[k], ahead, [&](Index c) {
      if (grid.stride == 4) project_cell<4, D>(ctx, dynamic, materials, grid, particles, loc, bc, g, c);
      else if constexpr (D == 2) project_cell<3, 2>(ctx, dynamic, materials, grid, particles, loc, bc, g, c);
    });
  }
  for_each_index(g.size(), [&](Index i) {
    const double w = g.lumped_volume[i];  // sum_p V_n N_I, from project_to_grid
    if (w > 0.0) g.proj_u[i] /= w, g.proj_p[i] /= w;
  });
}


template void project_residuals<2>(const StepContext&, const std::vector<BodyMaterial>&, const Cells&, const GridActivity&, const Points<2>&,
                                   const PointLocations&, const BoundaryConditions<2>&, Nodes<2>&);
template void project_residuals<3>(const StepContext&, const std::vector<BodyMaterial>&, const Cells&, const GridActivity&, const Points<3>&,
                                   const PointLocations&, const BoundaryConditions<3>&, Nodes<3>&);

}  // namespace loom
