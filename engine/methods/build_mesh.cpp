#include "engine/methods/build_mesh.hpp"

#include "engine/mesh/colouring.hpp"
#include "engine/mesh/generators.hpp"
#include "engine/mesh/mid_nodes.hpp"

namespace loom {

MeshData generate_body_mesh(const MeshSpec& spec) {
  MeshData mesh;
  switch (spec.generator) {
    case MeshGenerator::rectangle: {
      RectangleSpec r;
      r.origin = spec.origin, r.size = spec.size, r.nx = spec.nx, r.ny = spec.ny, r.pattern = spec.pattern;
      mesh = generate_rectangle(r);
      break;
    }
    case MeshGenerator::cooks_membrane:
      mesh = generate_cooks_membrane(spec.nx, spec.ny, spec.pattern);
      break;
  }
  distort_interior_nodes(mesh, spec.distortion, std::uint64_t(spec.seed));
  if (spec.scale != 1.0) scale_mesh(mesh, spec.scale);
  return mesh;
}

std::vector<Index> build_mesh(const SceneSpec& scene, Nodes<2>& nodes, std::vector<Cells>& cells) {
  std::vector<Index> node_body;
  std::vector<Vec2> X;
  cells.clear();
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodySpec& body = scene.bodies[b];
    MeshData mesh = generate_body_mesh(body.mesh);
    const CellType type = cell_type_of(body.element);
    const std::vector<Index> connectivity = type == CellType::tri6 ? add_mid_nodes(mesh.X, mesh.triangles) : mesh.triangles;
    const int stride = nodes_per_cell(type);
    const Index offset = Index(X.size());
    X.insert(X.end(), mesh.X.begin(), mesh.X.end());
    node_body.insert(node_body.end(), mesh.X.size(), Index(b));
    Cells* block = nullptr;
    for (auto& c : cells)
      if (c.formulation == body.element) block = &c;
    if (!block) {
      cells.emplace_back(type, body.element);
      block = &cells.back();
    }
    for (std::size_t t = 0; t < connectivity.size() / std::size_t(stride); ++t) {
      for (int a = 0; a < stride; ++a) block->nodes.values().push_back(offset + connectivity[t * std::size_t(stride) + std::size_t(a)]);
      block->body.values().push_back(Index(b));
    }
  }
  nodes.resize(Index(X.size()));
  for (Index i = 0; i < Index(X.size()); ++i) nodes.X[i] = X[std::size_t(i)];
  for (auto& c : cells) colour_cells(c, nodes.size());
  return node_body;
}

}  // namespace loom
