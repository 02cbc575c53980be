#include "systems/assemble/compute_geometry.hpp"

#include <atomic>

#include "engine/core/parallel.hpp"
#include "systems/assemble/elements/tri3.hpp"

namespace loom {

void allocate_quad_points(const std::vector<Cells>& cells, std::vector<QuadPoints<2>>& quad) {
  quad.resize(cells.size());
  for (std::size_t b = 0; b < cells.size(); ++b) {
    switch (cells[b].formulation) {
      case Formulation::p1:
        quad[b].per_cell = 1;
        quad[b].nodes_per_cell = 3;
        break;
    }
    quad[b].resize(cells[b].size() * quad[b].per_cell);
  }
}

Index compute_geometry(const Nodes<2>& nodes, const std::vector<Cells>& cells, std::vector<QuadPoints<2>>& quad) {
  std::atomic<Index> bad{0};
  for (std::size_t b = 0; b < cells.size(); ++b) {
    const Cells& cb = cells[b];
    QuadPoints<2>& qb = quad[b];
    switch (cb.formulation) {
      case Formulation::p1:
        for_each_index(cb.size(), [&](Index c) {
          const Index* n = cb.cell_nodes(c);
          Tri3Gradients dN;
          const double area = tri3_gradients(nodes.position_n(n[0]), nodes.position_n(n[1]), nodes.position_n(n[2]), dN);
          if (!(area > 0.0)) bad.fetch_add(1, std::memory_order_relaxed);
          Eigen::Map<Tri3Gradients>(qb.grad(c)) = dN;
          qb.weight_n[c] = area;
        });
        break;
    }
  }
  return bad.load();
}

}  // namespace loom
