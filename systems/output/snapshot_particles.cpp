#include "systems/output/snapshot_particles.hpp"

#include <cmath>

#include "engine/core/parallel.hpp"
#include "engine/mesh/quad9_shape.hpp"
#include "systems/output/coupled_cell.hpp"

namespace loom {

bool particle_stress(const BodyMaterial& material, const Mat3& F, bool mixed, double pressure, Mat3& sigma, const Mat3* be) {
  if (const auto* hp = std::get_if<HenckyPerzyna>(&material.model); hp && be) {
    const double J = F.determinant();
    if (!(J > 0.0)) return false;
    sigma = hp->kirchhoff(*be) / J;
    return true;
  }
  if (!mixed) return cauchy_stress(material.model, F, sigma);
  Mat3 P_dev;
  if (!std::get<NeoHookeSplit>(material.model).deviatoric_stress(F, P_dev)) return false;
  sigma = P_dev * F.transpose() / F.determinant() + pressure * Mat3::Identity();
  return true;
}

template <int D>
void snapshot_particles(const StepContext& ctx, const std::vector<BodyMaterial>& materials, const Points<D>& particles, Frame& frame) {
  frame.step = ctx.step;
  frame.time = ctx.t;
  const Index n = particles.X.size();
  const std::size_t un = std::size_t(n);
  const bool mixed = particles.pressure.used(), dynamic = particles.v.used();
  frame.points.assign(3 * un, 0.0);
  frame.connectivity.clear(), frame.offsets.clear(), frame.cell_types.clear(), frame.cell_arrays.clear();
  FrameArray displacement{"displacement", 3, std::vector<double>(3 * un, 0.0)};
  FrameArray velocity{"velocity", 3, std::vector<double>(dynamic ? 3 * un : 0, 0.0)};
  FrameArray pressure{"pressure", 1, std::vector<double>(un, 0.0)};
  FrameArray mean_stress{"mean_stress", 1, std::vector<double>(mixed ? un : 0, 0.0)};
  FrameArray J{"J", 1, std::vector<double>(un, 0.0)};
  FrameArray stress{"stress", 9, std::vector<double>(9 * un, 0.0)};
  FrameArray von_mises{"von_mises", 1, std::vector<double>(un, 0.0)};
  for_each_index(n, [&](Index p) {
    const std::size_t k = std::size_t(p);
    const Vec<D> x = particles.position(p);
    for (int d = 0; d < D; ++d) frame.points[3 * k + std::size_t(d)] = x[d];
    for (int d = 0; d < D; ++d) {
      displacement.values[3 * k + std::size_t(d)] = particles.u[p][d];
      if (dynamic) velocity.values[3 * k + std::size_t(d)] = particles.v[p][d];
    }
    const Mat3& F = particles.F[p];
    Mat3 sigma = Mat3::Constant(kNaN);
    particle_stress(materials[std::size_t(particles.body[p])], F, mixed, mixed ? particles.pressure[p] : 0.0, sigma,
                    particles.be.used() ? &particles.be[p] : nullptr);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) stress.values[9 * k + std::size_t(3 * i + j)] = sigma(i, j);
    const double mean = sigma.trace() / 3.0;  // = the particle's p when mixed (tr dev = 0)
    pressure.values[k] = -(mixed ? particles.pressure[p] : mean);
    if (mixed) mean_stress.values[k] = particles.pressure[p];
    J.values[k] = F.determinant();
    von_mises.values[k] = std::sqrt(1.5 * (sigma - mean * Mat3::Identity()).squaredNorm());
  });
  frame.point_arrays.clear();
  frame.point_arrays.push_back(std::move(displacement));
  if (dynamic) frame.point_arrays.push_back(std::move(velocity));
  frame.point_arrays.push_back(std::move(pressure));
  if (mixed) frame.point_arrays.push_back(std::move(mean_stress));
  for (auto* a : {&J, &stress, &von_mises}) frame.point_arrays.push_back(std::move(*a));
  frame.notes = {{"pressure_definition", kPressureDefinition}};
  if (mixed) frame.notes.emplace_back("mean_stress_definition", kMeanStressDefinition);
}

namespace {

// Method mpm_fem: the FEM cells' Cauchy stress, the mean over their Gauss points of F = dx/dX^ (coupled_cell.hpp),
// appended to the cell data of the cells written.
void add_fem_cell_stress(const std::vector<BodyMaterial>& materials, const Cells& grid, const GridActivity& activity, const Nodes<2>& g,
                         std::vector<FrameArray>& cell_arrays) {
  const std::size_t n = activity.active_cells.size();
  FrameArray body{"body", 1, std::vector<double>(n, -1.0)};
  FrameArray stress{"stress", 9, std::vector<double>(9 * n, kNaN)};
  FrameArray von_mises{"von_mises", 1, std::vector<double>(n, kNaN)};
  const Quad9Gauss& rule = quad9_gauss();
  for (std::size_t k = 0; k < n; ++k) {
    const Index c = activity.active_cells[k];
    if (c < activity.always_active_from) continue;
    const Index b = grid.body[c];
    Quad9Coordinates x, X;
    coupled_cell_coordinates(grid, g, c, x, X);
    Mat3 mean = Mat3::Zero();
    for (std::size_t q = 0; q < 9; ++q) {
      const Quad9Gradients dN = quad9_gradients(X, rule.xi[q], nullptr);
      Mat3 F = Mat3::Identity(), sigma;
      F.topLeftCorner<2, 2>() = x.transpose() * dN;
      if (!particle_stress(materials[std::size_t(b)], F, false, 0.0, sigma)) sigma.setConstant(kNaN);
      mean += sigma / 9.0;
    }
    body.values[k] = double(b);
    for (int j = 0; j < 9; ++j) stress.values[9 * k + std::size_t(j)] = mean(j / 3, j % 3);
    von_mises.values[k] = std::sqrt(1.5 * (mean - mean.trace() / 3.0 * Mat3::Identity()).squaredNorm());
  }
  for (auto* a : {&body, &stress, &von_mises}) cell_arrays.push_back(std::move(*a));
}

}  // namespace

template <int D>
void snapshot_grid(const StepContext& ctx, const std::vector<BodyMaterial>& materials, const Cells& grid, const GridActivity& activity,
                   const Nodes<D>& g, const PointLocations& particle_loc, Frame& frame) {
  frame.step = ctx.step;
  frame.time = ctx.t;
  const std::size_t n = std::size_t(g.size());
  frame.points.assign(3 * n, 0.0);
  FrameArray displacement{"displacement", 3, std::vector<double>(3 * n, 0.0)};
  FrameArray velocity{"velocity", 3, std::vector<double>(g.v.used() ? 3 * n : 0, 0.0)};
  FrameArray pressure{"pressure", 1, std::vector<double>(g.p.used() ? n : 0, 0.0)};
  FrameArray mean_stress{"mean_stress", 1, std::vector<double>(g.p.used() ? n : 0, 0.0)};
  FrameArray mass{"mass", 1, std::vector<double>(n, 0.0)};
  for (std::size_t i = 0; i < n; ++i) {
    const Index node = Index(i);
    // Method mpm_fem: the undeformed grid and the whole displacement (reset or FEM, and the step's).
    const Vec<D> X = g.u_n.used() ? Vec<D>(g.X[node] - g.u_n[node]) : g.X[node];
    const Vec<D> u = g.u_n.used() ? Vec<D>(g.u_n[node] + g.u[node]) : g.u[node];
    for (int d = 0; d < D; ++d) frame.points[3 * i + std::size_t(d)] = X[d];
    for (int d = 0; d < D; ++d) {
      displacement.values[3 * i + std::size_t(d)] = u[d];
      if (g.v.used()) velocity.values[3 * i + std::size_t(d)] = g.v[node][d];
    }
    if (g.p.used()) pressure.values[i] = -g.p[node], mean_stress.values[i] = g.p[node];
    if (g.lumped_mass.used()) mass.values[i] = g.lumped_mass[node];
  }
  frame.connectivity.clear(), frame.offsets.clear(), frame.cell_types.clear();
  FrameArray count{"particles", 1, {}};
  for (Index c : activity.active_cells) {
    for (int a = 0; a < grid.stride; ++a) frame.connectivity.push_back(grid.node(c, a));
    frame.offsets.push_back(Index(frame.connectivity.size()));
    frame.cell_types.push_back(D == 3 ? kVtkTetra : grid.stride == 9 ? kVtkBiquadraticQuad : grid.stride == 4 ? kVtkQuad : kVtkTriangle);
    count.values.push_back(particle_loc.count_in(c));
  }
  frame.point_arrays.clear();
  frame.point_arrays.push_back(std::move(displacement));
  if (!velocity.values.empty()) frame.point_arrays.push_back(std::move(velocity));
  if (!pressure.values.empty()) frame.point_arrays.push_back(std::move(pressure));
  if (!mean_stress.values.empty()) frame.point_arrays.push_back(std::move(mean_stress));
  if (g.lumped_mass.used()) frame.point_arrays.push_back(std::move(mass));  // particle Newmark: the grid carries no mass
  frame.cell_arrays = {std::move(count)};
  if constexpr (D == 2)
    if (activity.always_active_from != kNoIndex) add_fem_cell_stress(materials, grid, activity, g, frame.cell_arrays);
  frame.notes.clear();
  if (g.p.used()) frame.notes = {{"pressure_definition", kPressureDefinition}, {"mean_stress_definition", kMeanStressDefinition}};
}


template void snapshot_particles<2>(const StepContext&, const std::vector<BodyMaterial>&, const Points<2>&, Frame&);
template void snapshot_particles<3>(const StepContext&, const std::vector<BodyMaterial>&, const Points<3>&, Frame&);
template void snapshot_grid<2>(const StepContext&, const std::vector<BodyMaterial>&, const Cells&, const GridActivity&, const Nodes<2>&, const PointLocations&, Frame&);
template void snapshot_grid<3>(const StepContext&, const std::vector<BodyMaterial>&, const Cells&, const GridActivity&, const Nodes<3>&, const PointLocations&, Frame&);

}  // namespace loom
