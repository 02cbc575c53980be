#include "engine/methods/model/build_mesh.hpp"

#include <sstream>

#include "engine/core/errors.hpp"
#include "engine/mesh/colouring.hpp"
#include "engine/mesh/generators.hpp"
#include "engine/mesh/gmsh_file.hpp"
#include "engine/mesh/mesh_from_gmsh.hpp"
#include "engine/mesh/mid_nodes.hpp"

namespace loom {

MeshData generate_body_mesh(const MeshSpec& spec) {
  MeshData mesh;
  switch (spec.generator) {
    case MeshGenerator::rectangle: {
      RectangleSpec r;
      r.origin = spec.origin, r.size = spec.size, r.nx = spec.nx, r.ny = spec.ny, r.pattern = spec.pattern, r.quads = spec.quads;
      mesh = generate_rectangle(r);
      break;
    }
    case MeshGenerator::cooks_membrane:
      mesh = generate_cooks_membrane(spec.nx, spec.ny, spec.pattern, spec.quads);
      break;
    case MeshGenerator::file: {
      std::ostringstream where;
      where << spec.file_where;
      mesh = triangle_mesh_of(read_gmsh_file(spec.file, where.str(), spec.key + ".file"), spec.surface, where.str(), spec.key + ".file");
      if (spec.scale != 1.0) {
        scale_mesh(mesh, spec.scale);
        for (auto& x : mesh.mid_X) x *= spec.scale;
      }
      return mesh;
    }
    case MeshGenerator::box:  // the scene checks refuse it in 2D (dimension_options.cpp)
      LOOM_CHECK(false, RunError, "generate_body_mesh: generator box is three-dimensional (build_mesh_3d)");
  }
  distort_interior_nodes(mesh, spec.distortion, std::uint64_t(spec.seed));
  if (spec.scale != 1.0) scale_mesh(mesh, spec.scale);
  return mesh;
}

std::vector<Index> build_mesh(const SceneSpec& scene, Nodes<2>& nodes, std::vector<Cells>& cells, BodyRegions* regions) {
  // Corner nodes of every body first, then the mid-nodes of quadratic bodies: the corners are the
  // particles PFEM keeps across remeshes, the mid-nodes are dropped and re-created (seed 000 §4.1).
  // Quadrilateral bodies (quad9) come from the generators as corner quadrilaterals.
  std::vector<Index> node_body;
  std::vector<Vec2> X;
  std::vector<std::vector<Index>> corner_triangles(scene.bodies.size()), corner_quads(scene.bodies.size());
  std::vector<MeshData> meshes(scene.bodies.size());
  if (regions) regions->assign(scene.bodies.size(), {});
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    MeshData& mesh = meshes[b];
    mesh = generate_body_mesh(scene.bodies[b].mesh);
    const Index offset = Index(X.size());
    X.insert(X.end(), mesh.X.begin(), mesh.X.end());
    node_body.insert(node_body.end(), mesh.X.size(), Index(b));
    for (Index v : mesh.triangles) corner_triangles[b].push_back(offset + v);
    for (Index v : mesh.quads) corner_quads[b].push_back(offset + v);
    if (!regions) continue;
    for (auto r : mesh.regions) {
      for (Index& v : r.corners) v += offset;
      for (auto& e : r.edges) e[0] += offset, e[1] += offset;
      (*regions)[b].push_back(std::move(r));
    }
  }
  cells.clear();
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const Formulation element = scene.bodies[b].element;
    const CellType type = cell_type_of(element);
    const std::size_t before = X.size();
    std::vector<Index> connectivity;
    if (type == CellType::tri6 && !meshes[b].mid_nodes.empty()) {  // the file's own mid-nodes
      const Index offset = Index(X.size());
      X.insert(X.end(), meshes[b].mid_X.begin(), meshes[b].mid_X.end());
      for (std::size_t t = 0; t < corner_triangles[b].size() / 3; ++t) {
        connectivity.insert(connectivity.end(), corner_triangles[b].begin() + std::ptrdiff_t(3 * t), corner_triangles[b].begin() + std::ptrdiff_t(3 * t + 3));
        for (int s = 0; s < 3; ++s) connectivity.push_back(offset + meshes[b].mid_nodes[3 * t + std::size_t(s)]);
      }
    } else if (type == CellType::quad9) {
      connectivity = add_quad9_nodes(X, corner_quads[b]);
    } else {
      connectivity = type == CellType::tri6 ? add_mid_nodes(X, corner_triangles[b]) : corner_triangles[b];
    }
    node_body.insert(node_body.end(), X.size() - before, Index(b));
    Cells* block = nullptr;
    for (auto& c : cells)
      if (c.formulation == element) block = &c;
    if (!block) {
      cells.emplace_back(type, element);
      block = &cells.back();
    }
    block->nodes.values().insert(block->nodes.values().end(), connectivity.begin(), connectivity.end());
    block->body.values().insert(block->body.values().end(), connectivity.size() / std::size_t(block->stride), Index(b));
  }
  nodes.resize(Index(X.size()));
  for (Index i = 0; i < Index(X.size()); ++i) nodes.X[i] = X[std::size_t(i)];
  for (auto& c : cells) colour_cells(c, nodes.size());
  return node_body;
}

}  // namespace loom
