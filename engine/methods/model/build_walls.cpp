#include "engine/methods/model/build_walls.hpp"

#include <algorithm>

#include "engine/mesh/boundary_edges.hpp"

namespace loom {

Walls build_walls(const SceneSpec& scene, const Nodes<2>& nodes, const std::vector<Cells>& cells, const std::vector<Index>& node_body) {
  Walls walls;
  // Per body: the sum and count of its boundary edge lengths (corner to corner) in the reference configuration.
  std::vector<double> length(scene.bodies.size(), 0.0), count(scene.bodies.size(), 0.0);
  for (const Cells& cb : cells)
    for (const BoundaryEdge& e : boundary_edges(cb.nodes.values(), cb.stride)) {
      const auto b = std::size_t(node_body[std::size_t(e.a)]);
      length[b] += (nodes.X[e.b] - nodes.X[e.a]).norm(), count[b] += 1.0;
    }
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
    for (const auto& [point, normal] : spec.planes) walls.planes.push_back({point, normal, index});
  }
  return walls;
}

}  // namespace loom
