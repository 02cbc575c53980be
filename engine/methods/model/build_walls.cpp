#include "engine/methods/model/build_walls.hpp"

#include <algorithm>

#include "engine/mesh/boundary_edges.hpp"
#include "engine/mesh/tet_adjacency.hpp"

namespace loom {

namespace {

// Per body: the sum and count of its boundary edge lengths (corner to corner) in the reference configuration.
void boundary_lengths(const Nodes<2>& nodes, const std::vector<Cells>& cells, const std::vector<Index>& node_body, std::vector<double>& length,
                      std::vector<double>& count) {
  for (const Cells& cb : cells)
    for (const BoundaryEdge& e : boundary_edges(cb.nodes.values(), cb.stride)) {
      const auto b = std::size_t(node_body[std::size_t(e.a)]);
      length[b] += (nodes.X[e.b] - nodes.X[e.a]).norm(), count[b] += 1.0;
    }
}
// 3D: the edges of the surface triangles (each counted once per face: an edge's two faces weigh it twice, evenly).
void boundary_lengths(const Nodes<3>& nodes, const std::vector<Cells>& cells, const std::vector<Index>& node_body, std::vector<double>& length,
                      std::vector<double>& count) {
  for (const Cells& cb : cells) {
    std::vector<Index> corners;
    corners.reserve(std::size_t(cb.size()) * 4);
    for (Index c = 0; c < cb.size(); ++c) corners.insert(corners.end(), cb.cell_nodes(c), cb.cell_nodes(c) + 4);
    for (const BoundaryFace& f : boundary_faces(corners)) {
      const auto b = std::size_t(node_body[std::size_t(f.nodes[0])]);
      for (int j = 0; j < 3; ++j) length[b] += (nodes.X[f.nodes[(j + 1) % 3]] - nodes.X[f.nodes[j]]).norm(), count[b] += 1.0;
    }
  }
}

}  // namespace

template <int D>
WallsT<D> build_walls(const SceneSpec& scene, const Nodes<D>& nodes, const std::vector<Cells>& cells, const std::vector<Index>& node_body) {
  WallsT<D> walls;
  std::vector<double> length(scene.bodies.size(), 0.0), count(scene.bodies.size(), 0.0);
  boundary_lengths(nodes, cells, node_body, length, count);
  for (const WallSpec& spec : scene.walls) {
    Wall w;
    w.name = spec.name, w.stick = spec.stick, w.body = spec.body, w.k_n = spec.penalty;
    if (w.k_n == 0.0) {
      double E = 0.0, L = 0.0, n = 0.0;
      for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
        if (spec.body != kNoIndex && Index(b) != spec.body) continue;
        E = std::max(E, scene.materials[std::size_t(scene.bodies[b].material)].E);
        L += length[b], n += count[b];
      }
      w.k_n = n > 0.0 ? 100.0 * E / (L / n) : 0.0;
    }
    const Index index = Index(walls.walls.size());
    walls.walls.push_back(w);
    for (const auto& [point, normal] : spec.planes) walls.planes.push_back({Vec<D>(point.template head<D>()), Vec<D>(normal.template head<D>()), index});
  }
  return walls;
}

template WallsT<2> build_walls<2>(const SceneSpec&, const Nodes<2>&, const std::vector<Cells>&, const std::vector<Index>&);
template WallsT<3> build_walls<3>(const SceneSpec&, const Nodes<3>&, const std::vector<Cells>&, const std::vector<Index>&);

}  // namespace loom
