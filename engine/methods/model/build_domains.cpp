#include "engine/methods/model/build_domains.hpp"

#include <algorithm>

#include "engine/mesh/cell_domains.hpp"
#include "engine/mesh/smoothing_edges.hpp"
#include "engine/mesh/smoothing_faces.hpp"
#include "engine/mesh/tet_mesh.hpp"
#include "engine/mesh/triangle_geometry.hpp"
#include "systems/assemble/smoothing_geometry.hpp"

namespace loom {
namespace {

// The smoothing domains of a block: interior and boundary edges (2D) or faces (3D), or one domain per simplex.
template <int D>
void smoothing_domains(const Cells& cb, Index n_nodes, std::vector<Edges<D>>& made) {
  if (!edge_smoothed(cb.formulation)) {
    made.push_back(build_cell_domains<D>(cb, n_nodes));
    return;
  }
  auto d = [&] {
    if constexpr (D == 2) return build_edge_domains(cb, n_nodes);
    else return build_face_domains(cb, n_nodes);
  }();
  made.push_back(std::move(d.interior)), made.push_back(std::move(d.boundary));
}

double reference_measure(const Nodes<2>& nodes, const Cells& cb, Index c) {
  return signed_area(nodes.X[cb.node(c, 0)], nodes.X[cb.node(c, 1)], nodes.X[cb.node(c, 2)]);
}
double reference_measure(const Nodes<3>& nodes, const Cells& cb, Index c) {
  return tet_volume(nodes.X[cb.node(c, 0)], nodes.X[cb.node(c, 1)], nodes.X[cb.node(c, 2)], nodes.X[cb.node(c, 3)]);
}

}  // namespace

template <int D>
void build_domains(const Nodes<D>& nodes, const std::vector<Cells>& cells, const std::vector<char>& j_projection,
                   std::vector<Edges<D>>& edges) {
  for (std::size_t b = 0; b < cells.size(); ++b) {
    const Cells& cb = cells[b];
    if (!integrates_on_domains(cb.formulation)) continue;
    std::vector<Edges<D>> made;
    smoothing_domains(cb, nodes.size(), made);
    for (auto& e : made) {
      if (e.size() == 0) continue;
      e.cell_block = Index(b);
      if (std::count(j_projection.begin(), j_projection.end(), 1) > 0) e.j_projection = j_projection;
      compute_smoothing_geometry(nodes, cb, e);
      edges.push_back(std::move(e));
    }
  }
}

template <int D>
void set_reference_areas(const Nodes<D>& nodes, std::vector<Cells>& cells) {
  for (Cells& cb : cells) {
    if (!integrates_on_domains(cb.formulation)) continue;
    cb.measure.use();
    cb.measure.resize(cb.size());
    for (Index c = 0; c < cb.size(); ++c) cb.measure[c] = reference_measure(nodes, cb, c);
  }
}

template void build_domains<2>(const Nodes<2>&, const std::vector<Cells>&, const std::vector<char>&, std::vector<Edges<2>>&);
template void build_domains<3>(const Nodes<3>&, const std::vector<Cells>&, const std::vector<char>&, std::vector<Edges<3>>&);
template void set_reference_areas<2>(const Nodes<2>&, std::vector<Cells>&);
template void set_reference_areas<3>(const Nodes<3>&, std::vector<Cells>&);

}  // namespace loom
