#include "systems/assemble/compute_geometry.hpp"

#include <atomic>
#include <stdexcept>

#include "engine/core/parallel.hpp"
#include "engine/mesh/quad9_shape.hpp"
#include "systems/assemble/elements/tet10.hpp"
#include "systems/assemble/elements/tet4.hpp"
#include "systems/assemble/elements/tri3.hpp"
#include "systems/assemble/elements/tri6.hpp"

namespace loom {

template <int D>
void allocate_quad_points(const std::vector<Cells>& cells, std::vector<QuadPoints<D>>& quad) {
  quad.resize(cells.size());
  for (std::size_t b = 0; b < cells.size(); ++b) {
    // p1: one point; tri6 and p1p1_uphi: the three-point rule (seed 000 Fig 5), on tetrahedra the four-point one;
    // quad9: 3 x 3 Gauss. Seed 001's formulations integrate on their domains; the one point of a triangle carries
    // its P1 F and stored stress for output.
    const Formulation f = cells[b].formulation;
    quad[b].per_cell = f == Formulation::p1 || integrates_on_domains(f) ? 1 : f == Formulation::quad9 ? 9 : D + 1;
    quad[b].stress_n.use(integrates_on_domains(f));
    quad[b].nodes_per_cell = cells[b].stride;
    quad[b].resize(cells[b].size() * quad[b].per_cell);
  }
}

namespace {

// Tetrahedra: tet4 has constant gradients (every point gets them and V / per_cell); tet10 is isoparametric,
// its gradients and Jacobian taken at each point of the four-point rule (weight 1/4 of det J / 6).
Index compute_tet_geometry(const Nodes<3>& nodes, const Cells& cb, QuadPoints<3>& qb) {
  std::atomic<Index> bad{0};
  const int per_cell = qb.per_cell;
  if (cb.type == CellType::tet4) {
    for_each_index(cb.size(), [&](Index c) {
      const Index* n = cb.cell_nodes(c);
      Tet4Corners x;
      for (int a = 0; a < 4; ++a) x.row(a) = nodes.position_n(n[a]).transpose();
      Tet4Gradients dN;
      const double volume = tet4_gradients(x, dN);
      if (!(volume > 0.0)) bad.fetch_add(1, std::memory_order_relaxed);
      for (int q = 0; q < per_cell; ++q) {
        Eigen::Map<Tet4Gradients>(qb.grad(c * per_cell + q)) = dN;
        qb.weight_n[c * per_cell + q] = volume / per_cell;
      }
    });
  } else {
    if (per_cell != 4) throw std::logic_error("compute_geometry: tet10 cells are integrated by the four-point rule");
    for_each_index(cb.size(), [&](Index c) {
      const Index* n = cb.cell_nodes(c);
      Tet10Nodes x;
      for (int a = 0; a < 10; ++a) x.row(a) = nodes.position_n(n[a]).transpose();
      bool ok = true;
      for (int q = 0; q < per_cell; ++q) {
        Tet10Gradients dN;
        const double det = tet10_gradients(x, kTet4Rule4[q], dN);
        ok = ok && det > 0.0;
        Eigen::Map<Tet10Gradients>(qb.grad(c * per_cell + q)) = dN;
        qb.weight_n[c * per_cell + q] = det / 24.0;
      }
      if (!ok) bad.fetch_add(1, std::memory_order_relaxed);
    });
  }
  return bad.load();
}

}  // namespace

template <>
Index compute_geometry<3>(const Nodes<3>& nodes, const std::vector<Cells>& cells, std::vector<QuadPoints<3>>& quad) {
  Index bad = 0;
  for (std::size_t b = 0; b < cells.size(); ++b) bad += compute_tet_geometry(nodes, cells[b], quad[b]);
  return bad;
}

template <>
Index compute_geometry<2>(const Nodes<2>& nodes, const std::vector<Cells>& cells, std::vector<QuadPoints<2>>& quad) {
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

template void allocate_quad_points<2>(const std::vector<Cells>&, std::vector<QuadPoints<2>>&);
template void allocate_quad_points<3>(const std::vector<Cells>&, std::vector<QuadPoints<3>>&);

}  // namespace loom
