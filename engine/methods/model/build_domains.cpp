#include "engine/methods/model/build_domains.hpp"

#include <algorithm>

#include "engine/mesh/smoothing_edges.hpp"
#include "engine/mesh/triangle_geometry.hpp"
#include "systems/assemble/smoothing_geometry.hpp"

namespace loom {

void build_domains(const Nodes<2>& nodes, const std::vector<Cells>& cells, const std::vector<char>& j_projection,
                   std::vector<Edges<2>>& edges) {
  for (std::size_t b = 0; b < cells.size(); ++b) {
    const Cells& cb = cells[b];
    if (!integrates_on_domains(cb.formulation)) continue;
    std::vector<Edges<2>> made;
    if (edge_smoothed(cb.formulation)) {
      EdgeDomains d = build_edge_domains(cb, nodes.size());
      made.push_back(std::move(d.interior)), made.push_back(std::move(d.boundary));
    } else {
      made.push_back(build_triangle_domains(cb, nodes.size()));
    }
    for (auto& e : made) {
      if (e.size() == 0) continue;
      e.cell_block = Index(b);
      if (std::count(j_projection.begin(), j_projection.end(), 1) > 0) e.j_projection = j_projection;
      compute_smoothing_geometry(nodes, cb, e);
      edges.push_back(std::move(e));
    }
  }
}

void set_reference_areas(const Nodes<2>& nodes, std::vector<Cells>& cells) {
  for (Cells& cb : cells) {
    if (!integrates_on_domains(cb.formulation)) continue;
    cb.measure.use();
    cb.measure.resize(cb.size());
    for (Index c = 0; c < cb.size(); ++c) cb.measure[c] = signed_area(nodes.X[cb.node(c, 0)], nodes.X[cb.node(c, 1)], nodes.X[cb.node(c, 2)]);
  }
}

}  // namespace loom
