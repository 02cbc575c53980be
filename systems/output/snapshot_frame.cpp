#include "systems/output/snapshot_frame.hpp"

#include <cmath>

#include "engine/core/parallel.hpp"
#include "engine/mesh/triangle_geometry.hpp"

namespace loom {
namespace {

// Point data nodal_stress and nodal_von_mises: at each node the mean of the cell stresses `cell_stress` (9 per cell)
// of the cells that share it, weighted by their current volume (the sum of their points' dV_n); NaN at a node of no
// cell (a free particle). Summed cell by cell in order, so the result does not depend on the thread count.
template <int D>
void add_nodal_stress(Index n_nodes, const std::vector<Cells>& cells, const std::vector<QuadPoints<D>>& quad,
                      const std::vector<double>& cell_stress, std::vector<FrameArray>& point_arrays) {
  const std::size_t n = std::size_t(n_nodes);
  FrameArray nodal{"nodal_stress", 9, std::vector<double>(9 * n, 0.0)};
  FrameArray von_mises{"nodal_von_mises", 1, std::vector<double>(n, kNaN)};
  std::vector<double> weight(n, 0.0);
  std::size_t k = 0;
  for (std::size_t b = 0; b < cells.size(); ++b)
    for (Index c = 0; c < cells[b].size(); ++c, ++k) {
      double volume = 0.0;
      for (int q = 0; q < quad[b].per_cell; ++q) volume += quad[b].weight_n[c * quad[b].per_cell + q];
      if (!(volume > 0.0) || !std::isfinite(cell_stress[9 * k])) continue;
      for (int a = 0; a < cells[b].stride; ++a) {
        const std::size_t i = std::size_t(cells[b].node(c, a));
        weight[i] += volume;
        for (int j = 0; j < 9; ++j) nodal.values[9 * i + std::size_t(j)] += volume * cell_stress[9 * k + std::size_t(j)];
      }
    }
  for (std::size_t i = 0; i < n; ++i) {
    Mat3 sigma;
    for (int j = 0; j < 9; ++j) {
      double& value = nodal.values[9 * i + std::size_t(j)];
      value = weight[i] > 0.0 ? value / weight[i] : kNaN;
      sigma(j / 3, j % 3) = value;
    }
    von_mises.values[i] = std::sqrt(1.5 * (sigma - sigma.trace() / 3.0 * Mat3::Identity()).squaredNorm());
  }
  point_arrays.push_back(std::move(nodal));
  point_arrays.push_back(std::move(von_mises));
}

}  // namespace

template <int D>
void snapshot_frame(const StepContext& ctx, const std::vector<BodyMaterial>& materials, const Nodes<D>& nodes,
                    const std::vector<Cells>& cells, const std::vector<QuadPoints<D>>& quad, Frame& frame) {
  frame.step = ctx.step;
  frame.time = ctx.t;
  const Index n = nodes.size();
  frame.points.resize(3 * std::size_t(n));
  FrameArray displacement{"displacement", 3, std::vector<double>(3 * std::size_t(n), 0.0)};
  FrameArray velocity{"velocity", 3, {}};
  FrameArray phi{"phi", 1, {}};
  if (nodes.phi_n.used()) phi.values.assign(nodes.phi_n.values().begin(), nodes.phi_n.values().end());
  // u-p elements of seed 001: the nodal unknown p, the mean stress positive in tension (as MPM's mean_stress),
  // and the particles' volume ratio J^l of es_pfem.
  FrameArray mean_stress{"mean_stress", 1, {}}, nodal_J{"J_node", 1, {}};
  if (nodes.p_n.used()) mean_stress.values.assign(nodes.p_n.values().begin(), nodes.p_n.values().end());
  if (nodes.J_node.used()) nodal_J.values.assign(nodes.J_node.values().begin(), nodes.J_node.values().end());
  if (nodes.v_n.used()) velocity.values.assign(3 * std::size_t(n), 0.0);
  for_each_index(n, [&](Index i) {
    const Vec<D> x = nodes.position_n(i);
    for (int d = 0; d < 3; ++d) frame.points[3 * std::size_t(i) + std::size_t(d)] = d < D ? x[d] : 0.0;
    for (int d = 0; d < D; ++d) {
      displacement.values[3 * std::size_t(i) + std::size_t(d)] = nodes.u_n[i][d];
      if (nodes.v_n.used()) velocity.values[3 * std::size_t(i) + std::size_t(d)] = nodes.v_n[i][d];
    }
  });

  Index n_cells = 0;
  std::size_t n_conn = 0;
  for (const auto& cb : cells) n_cells += cb.size(), n_conn += std::size_t(cb.size()) * std::size_t(cb.stride);
  frame.connectivity.clear();
  frame.connectivity.reserve(n_conn);
  frame.offsets.clear();
  frame.cell_types.clear();
  FrameArray stress{"stress", 9, std::vector<double>(9 * std::size_t(n_cells), 0.0)};
  FrameArray pressure{"pressure", 1, std::vector<double>(std::size_t(n_cells), 0.0)};
  FrameArray J{"J", 1, std::vector<double>(std::size_t(n_cells), 0.0)};
  FrameArray von_mises{"von_mises", 1, std::vector<double>(std::size_t(n_cells), 0.0)};
  FrameArray body{"body", 1, std::vector<double>(std::size_t(n_cells), 0.0)};

  Index first = 0;
  for (std::size_t b = 0; b < cells.size(); ++b) {
    const Cells& cb = cells[b];
    const QuadPoints<D>& qb = quad[b];
    for (Index c = 0; c < cb.size(); ++c) {
      for (int a = 0; a < cb.stride; ++a) frame.connectivity.push_back(cb.node(c, a));
      frame.offsets.push_back(Index(frame.connectivity.size()));
      frame.cell_types.push_back(vtk_cell_type(cb.type));
    }
    for_each_index(cb.size(), [&](Index c) {
      const std::size_t k = std::size_t(first + c);
      Mat3 sigma_mean = Mat3::Zero();
      double J_mean = 0.0;
      for (int q = 0; q < qb.per_cell; ++q) {
        const Mat3& F = qb.F_n[c * qb.per_cell + q];
        Mat3 sigma = Mat3::Constant(kNaN);
        point_stress(materials[std::size_t(cb.body[c])], qb, c * qb.per_cell + q, sigma);
        sigma_mean += sigma / qb.per_cell;
        J_mean += F.determinant() / qb.per_cell;
      }
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) stress.values[9 * k + std::size_t(3 * i + j)] = sigma_mean(i, j);
      const double p = -sigma_mean.trace() / 3.0;
      const Mat3 dev = sigma_mean + p * Mat3::Identity();
      pressure.values[k] = p;
      // Seed 001's triangles: the volume ratio of the triangle itself, current over reference area (their F_n is a
      // per-triangle record that a remesh maps from a neighbour, not the triangle's own history).
      if constexpr (D == 2)
        if (integrates_on_domains(cb.formulation) && cb.measure.used() && !nodes.u_n.empty())
          J_mean = signed_area(nodes.position_n(cb.node(c, 0)), nodes.position_n(cb.node(c, 1)), nodes.position_n(cb.node(c, 2))) / cb.measure[c];
      J.values[k] = J_mean;
      von_mises.values[k] = std::sqrt(1.5 * dev.squaredNorm());
      body.values[k] = cb.body[c];
    });
    first += cb.size();
  }
  frame.point_arrays.clear();
  frame.point_arrays.push_back(std::move(displacement));
  if (!velocity.values.empty()) frame.point_arrays.push_back(std::move(velocity));
  if (!phi.values.empty()) frame.point_arrays.push_back(std::move(phi));
  if (!mean_stress.values.empty()) frame.point_arrays.push_back(std::move(mean_stress));
  if (!nodal_J.values.empty()) frame.point_arrays.push_back(std::move(nodal_J));
  if (ctx.scene && ctx.scene->output.nodal_stress) add_nodal_stress(nodes.size(), cells, quad, stress.values, frame.point_arrays);
  frame.cell_arrays = {std::move(stress), std::move(pressure), std::move(J), std::move(von_mises), std::move(body)};
  frame.notes = {{"pressure_definition", kPressureDefinition}};
}

template void snapshot_frame<2>(const StepContext&, const std::vector<BodyMaterial>&, const Nodes<2>&, const std::vector<Cells>&,
                                const std::vector<QuadPoints<2>>&, Frame&);
template void snapshot_frame<3>(const StepContext&, const std::vector<BodyMaterial>&, const Nodes<3>&, const std::vector<Cells>&,
                                const std::vector<QuadPoints<3>>&, Frame&);

}  // namespace loom
