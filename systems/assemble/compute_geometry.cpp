#include "systems/assemble/compute_geometry.hpp"

#include <atomic>

#include "engine/core/parallel.hpp"
#include "engine/mesh/quad9_shape.hpp"
#include "systems/assemble/elements/tri3.hpp"
#include "systems/assemble/elements/tri6.hpp"

namespace loom {

void allocate_quad_points(const std::vector<Cells>& cells, std::vector<QuadPoints<2>>& quad) {
  quad.resize(cells.size());
  for (std::size_t b = 0; b < cells.size(); ++b) {
    // p1: one point; tri6 and p1p1_uphi: the three-point rule (seed 000 Fig 5); quad9: 3 x 3 Gauss. Seed 001's formulations
    // integrate on their domains; the one point of a triangle carries its P1 F and stored stress for output.
    const Formulation f = cells[b].formulation;
    quad[b].per_cell = f == Formulation::p1 || integrates_on_domains(f) ? 1 : f == Formulation::quad9 ? 9 : 3;
    quad[b].stress_n.use(integrates_on_domains(f));
    quad[b].nodes_per_cell = cells[b].stride;
    quad[b].resize(cells[b].size() * quad[b].per_cell);
  }
}

Index compute_geometry(const Nodes<2>& nodes, const std::vector<Cells>& cells, std::vector<QuadPoints<2>>& quad) {
  std::atomic<Index> bad{0};
  for (std::size_t b = 0; b < cells.size(); ++b) {
    const Cells& cb = cells[b];
    QuadPoints<2>& qb = quad[b];
    const int per_cell = qb.per_cell;
    if (cb.type == CellType::tri3) {
      // Constant gradients; every point of the cell gets the same gradients and area / per_cell.
      for_each_index(cb.size(), [&](Index c) {
        const Index* n = cb.cell_nodes(c);
        Tri3Gradients dN;
        const double area = tri3_gradients(nodes.position_n(n[0]), nodes.position_n(n[1]), nodes.position_n(n[2]), dN);
        if (!(area > 0.0)) bad.fetch_add(1, std::memory_order_relaxed);
        for (int q = 0; q < per_cell; ++q) {
          Eigen::Map<Tri3Gradients>(qb.grad(c * per_cell + q)) = dN;
          qb.weight_n[c * per_cell + q] = area / per_cell;
        }
      });
    } else if (cb.type == CellType::quad9) {
      // Isoparametric biquadratic map: gradients and Jacobian at each Gauss point.
      const Quad9Gauss& rule = quad9_gauss();
      for_each_index(cb.size(), [&](Index c) {
        const Index* n = cb.cell_nodes(c);
        Quad9Coordinates x;
        for (int a = 0; a < 9; ++a) x.row(a) = nodes.position_n(n[a]).transpose();
        bool ok = true;
        for (int q = 0; q < 9; ++q) {
          double det = 0.0;
          Eigen::Map<Quad9Gradients>(qb.grad(c * 9 + q)) = quad9_gradients(x, rule.xi[std::size_t(q)], &det);
          ok = ok && det > 0.0;
          qb.weight_n[c * 9 + q] = det * rule.weight[std::size_t(q)];
        }
        if (!ok) bad.fetch_add(1, std::memory_order_relaxed);
      });
    } else {
      // Isoparametric P2 map: gradients and Jacobian at each of the three points (weights 1/6 each on the
      // reference triangle of area 1/2).
      for_each_index(cb.size(), [&](Index c) {
        const Index* n = cb.cell_nodes(c);
        Eigen::Matrix<double, 6, 2> x;
        for (int a = 0; a < 6; ++a) x.row(a) = nodes.position_n(n[a]).transpose();
        bool ok = true;
        for (int q = 0; q < per_cell; ++q) {
          const double* l = kTri3Rule3[q];
          Tri6Gradients dN;
          const double det = tri6_gradients(x, l[0], l[1], l[2], dN);
          ok = ok && det > 0.0;
          Eigen::Map<Tri6Gradients>(qb.grad(c * per_cell + q)) = dN;
          qb.weight_n[c * per_cell + q] = det / 6.0;
        }
        if (!ok) bad.fetch_add(1, std::memory_order_relaxed);
      });
    }
  }
  return bad.load();
}

}  // namespace loom
