#include "engine/methods/model/build_solid_3d.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <sstream>

#include "engine/core/errors.hpp"
#include "engine/mesh/colouring.hpp"
#include "engine/mesh/generators.hpp"
#include "engine/mesh/gmsh_file.hpp"
#include "engine/mesh/tet_generators.hpp"
#include "engine/mesh/tet_mesh_from_gmsh.hpp"
#include "engine/methods/model/build_boundary_conditions.hpp"
#include "systems/assemble/elements/tet10.hpp"

namespace loom {
namespace {

CellType tet_type_of(Formulation f) { return f == Formulation::tri6 ? CellType::tet10 : CellType::tet4; }

// One body's cells: tet4 corners, or whole tet10 cells (then X holds the mid-nodes after the corners).
struct BodyTets {
  std::vector<Vec3> X;
  Index n_corners = 0;
  std::vector<Index> cells;  // 4 or 10 per cell
  std::vector<MeshRegion> regions;
};

// The mesh a spec names, unscaled and undistorted; a file's 10-node cells in `file_tet10`.
TetMeshData read_tet_mesh(const MeshSpec& spec, Tet10MeshData& file_tet10) {
  TetMeshData mesh;
  switch (spec.generator) {
    case MeshGenerator::box: {
      BoxSpec b;
      b.origin = Vec3(spec.origin.x(), spec.origin.y(), spec.origin_z);
      b.size = Vec3(spec.size.x(), spec.size.y(), spec.size_z);
      b.nx = spec.nx, b.ny = spec.ny, b.nz = spec.nz;
      mesh = spec.bcc ? generate_bcc_box(b) : generate_box(b);
      break;
    }
    case MeshGenerator::rectangle:
    case MeshGenerator::cooks_membrane: {
      MeshSpec plane = spec;
      plane.distortion = 0.0, plane.scale = 1.0;  // distorted and scaled in 3D below
      mesh = extrude(generate_body_mesh(plane), spec.depth, spec.layers);
      break;
    }
    case MeshGenerator::file: {
      std::ostringstream where;
      where << spec.file_where;
      TetMeshFile read = tet_mesh_of(read_gmsh_file(spec.file, where.str(), spec.key + ".file"), spec.surface, where.str(), spec.key + ".file");
      mesh = std::move(read.corners);
      file_tet10 = std::move(read.quadratic);
      break;
    }
  }
  return mesh;
}

BodyTets body_tets(const BodySpec& body) {
  const MeshSpec& spec = body.mesh;
  const bool quadratic = tet_type_of(body.element) == CellType::tet10;
  Tet10MeshData file_tet10;
  TetMeshData mesh = read_tet_mesh(spec, file_tet10);
  if (spec.distortion > 0.0) distort_interior_nodes(mesh, spec.distortion, std::uint64_t(spec.seed));
  BodyTets out;
  out.regions = mesh.regions;
  out.n_corners = Index(mesh.X.size());
  if (quadratic) {
    // A file's own mid-nodes (curved edges) if it has 10-node cells; else new ones on the straight edges.
    Tet10MeshData q = file_tet10.cells.empty() ? tet10_from_tet4(mesh) : std::move(file_tet10);
    out.X = std::move(q.X), out.cells = std::move(q.cells);
  } else {
    out.X = std::move(mesh.X), out.cells = std::move(mesh.tets);
  }
  if (spec.scale != 1.0)
    for (auto& x : out.X) x *= spec.scale;
  return out;
}

}  // namespace

TetMeshData tet4_mesh_of(const MeshSpec& spec) {
  Tet10MeshData unused;
  TetMeshData mesh = read_tet_mesh(spec, unused);
  if (spec.distortion > 0.0) distort_interior_nodes(mesh, spec.distortion, std::uint64_t(spec.seed));
  if (spec.scale != 1.0)
    for (auto& x : mesh.X) x *= spec.scale;
  return mesh;
}

std::vector<Index> build_mesh_3d(const SceneSpec& scene, Nodes<3>& nodes, std::vector<Cells>& cells, BodyRegions* regions) {
  std::vector<BodyTets> bodies;
  for (const BodySpec& b : scene.bodies) bodies.push_back(body_tets(b));
  // Corners of every body first, then the mid-nodes (as in 2D).
  std::vector<Index> corner_offset(bodies.size()), mid_offset(bodies.size());
  Index n = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b) corner_offset[b] = n, n += bodies[b].n_corners;
  for (std::size_t b = 0; b < bodies.size(); ++b) mid_offset[b] = n - bodies[b].n_corners, n += Index(bodies[b].X.size()) - bodies[b].n_corners;
  nodes.resize(n);
  std::vector<Index> node_body(static_cast<std::size_t>(n));
  if (regions) regions->assign(bodies.size(), {});
  cells.clear();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const BodyTets& t = bodies[b];
    auto global = [&](Index v) { return v < t.n_corners ? corner_offset[b] + v : mid_offset[b] + v; };
    for (Index v = 0; v < Index(t.X.size()); ++v) nodes.X[global(v)] = t.X[std::size_t(v)], node_body[std::size_t(global(v))] = Index(b);
    const Formulation element = scene.bodies[b].element;
    Cells* block = nullptr;
    for (auto& c : cells)
      if (c.formulation == element) block = &c;
    if (!block) {
      cells.emplace_back(tet_type_of(element), element);
      block = &cells.back();
    }
    for (Index v : t.cells) block->nodes.values().push_back(global(v));
    block->body.values().insert(block->body.values().end(), t.cells.size() / std::size_t(block->stride), Index(b));
    if (!regions) continue;
    for (auto r : t.regions) {
      for (Index& v : r.corners) v = global(v);
      (*regions)[b].push_back(std::move(r));
    }
  }
  for (auto& c : cells) colour_cells(c, nodes.size());
  return node_body;
}

BoundaryConditions<3> build_boundary_conditions_3d(const SceneSpec& scene, const Nodes<3>& nodes, const std::vector<Cells>& cells,
                                                   const std::vector<Index>& node_body, const BodyRegions& regions, int dofs_per_node,
                                                   bool tie_mid_nodes, const std::vector<TractionFace>* frozen_tractions) {
  BoundaryConditions<3> bc;
  bc.per_node = dofs_per_node;
  std::vector<Vec3> lo(scene.bodies.size(), Vec3::Constant(1e300)), hi(scene.bodies.size(), Vec3::Constant(-1e300));
  for (Index i = 0; i < nodes.size(); ++i) {
    const auto b = std::size_t(node_body[std::size_t(i)]);
    lo[b] = lo[b].cwiseMin(nodes.X[i]), hi[b] = hi[b].cwiseMax(nodes.X[i]);
  }
  // Boundary faces of every block with their mid-nodes (tet10: the edge nodes between the face's corners).
  std::vector<TractionFace> faces;
  std::vector<std::pair<Index, Index>> mid_corners(std::size_t(nodes.size()), {kNoIndex, kNoIndex});
  for (const Cells& cb : cells) {
    const bool quadratic = cb.type == CellType::tet10;
    std::vector<Index> corners;
    for (Index c = 0; c < cb.size(); ++c)
      for (int a = 0; a < 4; ++a) corners.push_back(cb.node(c, a));
    auto mid = [&](Index c, int i, int j) {
      for (int e = 0; e < 6; ++e)
        if ((kTet10Edges[e][0] == i && kTet10Edges[e][1] == j) || (kTet10Edges[e][0] == j && kTet10Edges[e][1] == i)) return cb.node(c, 4 + e);
      return kNoIndex;
    };
    if (quadratic)
      for (Index c = 0; c < cb.size(); ++c)
        for (int e = 0; e < 6; ++e) mid_corners[std::size_t(cb.node(c, 4 + e))] = {cb.node(c, kTet10Edges[e][0]), cb.node(c, kTet10Edges[e][1])};
    for (const BoundaryFace& f : boundary_faces(corners)) {
      TractionFace t{{f.nodes[0], f.nodes[1], f.nodes[2], kNoIndex, kNoIndex, kNoIndex}, {kNoIndex, kNoIndex, kNoIndex}};
      if (quadratic) {
        const int* l = kTetFaces[f.local];
        for (int s = 0; s < 3; ++s) t.nodes[std::size_t(3 + s)] = mid(f.tet, l[s], l[(s + 1) % 3]);
      }
      faces.push_back(t);
    }
  }
  // The nodes of each region: in the box, or in the group (a mid-node when both corners of its edge are).
  std::vector<std::vector<char>> member(scene.boundaries.size(), std::vector<char>(std::size_t(nodes.size()), 0));
  for (std::size_t k = 0; k < scene.boundaries.size(); ++k) {
    const BoundarySpec& spec = scene.boundaries[k];
    const auto body = std::size_t(spec.body);
    std::vector<char>& in = member[k];
    if (spec.group.empty()) {
      const double tol = 1e-9 * std::max(1.0, (hi[body] - lo[body]).norm());
      const Vec3 bmin(spec.box_min.x(), spec.box_min.y(), spec.box_min_z), bmax(spec.box_max.x(), spec.box_max.y(), spec.box_max_z);
      for (Index i = 0; i < nodes.size(); ++i)
        in[std::size_t(i)] = node_body[std::size_t(i)] == spec.body && (nodes.X[i] - bmin).minCoeff() >= -tol && (bmax - nodes.X[i]).minCoeff() >= -tol;
      continue;
    }
    const MeshRegion* region = &boundary_group(scene, regions, k);
    for (Index v : region->corners) in[std::size_t(v)] = 1;
    for (Index i = 0; i < nodes.size(); ++i) {
      const auto [a, b] = mid_corners[std::size_t(i)];
      if (a != kNoIndex && region->dim >= 2 && in[std::size_t(a)] && in[std::size_t(b)]) in[std::size_t(i)] = 1;
    }
  }

  // [Schewe 2024] eq 24 in 3D: the mid-nodes of the edges of boundary faces that carry a condition follow their corners.
  std::map<Index, std::array<Index, 2>> tied;  // mid-node -> corners
  if (tie_mid_nodes)
    for (std::size_t k = 0; k < scene.boundaries.size(); ++k) {
      const BoundarySpec& spec = scene.boundaries[k];
      if (!spec.has_traction && !spec.displacement.any()) continue;
      for (const TractionFace& f : faces) {
        if (f.nodes[3] == kNoIndex || !member[k][std::size_t(f.nodes[0])] || !member[k][std::size_t(f.nodes[1])] || !member[k][std::size_t(f.nodes[2])])
          continue;
        for (int s = 0; s < 3; ++s) tied[f.nodes[std::size_t(3 + s)]] = {f.nodes[std::size_t(s)], f.nodes[std::size_t((s + 1) % 3)]};
      }
    }
  for (const auto& [mid, corner] : tied)
    for (int d = 0; d < 3; ++d) bc.ties.push_back({mid * dofs_per_node + d, {corner[0] * dofs_per_node + d, corner[1] * dofs_per_node + d}});

  PrescribedDofs seen;
  for (std::size_t k = 0; k < scene.boundaries.size(); ++k) {
    const BoundarySpec& spec = scene.boundaries[k];
    const auto body = std::size_t(spec.body);
    const std::vector<char>& in = member[k];
    std::vector<Index> selected;
    for (Index i = 0; i < nodes.size(); ++i)
      if (in[std::size_t(i)]) selected.push_back(i);
    const char* by = spec.group.empty() ? "box" : "group";
    LOOM_CHECK(!selected.empty(), InputError,
               spec.region_where << ": error: boundary[" << k << "].region." << by << ": the region selects no node of body \""
                                 << scene.bodies[body].name << "\" (its nodes span [" << lo[body].x() << ", " << lo[body].y() << ", "
                                 << lo[body].z() << "] to [" << hi[body].x() << ", " << hi[body].y() << ", " << hi[body].z() << "])");
    bc.boundary_names.push_back(spec.name);
    bc.boundary_nodes.push_back(selected);
    bc.boundary_prescribed.emplace_back();
    prescribe_displacements(scene, k, selected, tied, nodes, seen, bc);
    if (!spec.has_traction) continue;
    std::array<Index, 3> expr{kNoIndex, kNoIndex, kNoIndex};
    for (int d = 0; d < 3; ++d)
      if (spec.traction[d]) expr[std::size_t(d)] = add_expression(bc, *spec.traction[d]);
    if (frozen_tractions) continue;  // compiled in every build, so that the frozen faces' expression indices hold
    // region.normal: the faces' corners run counter-clockwise seen from outside (boundary_faces of positively
    // oriented tetrahedra), so (x1 - x0) x (x2 - x0) is the outward normal, in the reference configuration.
    const std::optional<Vec3> direction = region_normal<3>(spec);
    std::size_t n_faces = 0, n_in_region = 0;  // loaded; in the region, before region.normal's filter
    for (TractionFace f : faces) {
      if (!in[std::size_t(f.nodes[0])] || !in[std::size_t(f.nodes[1])] || !in[std::size_t(f.nodes[2])]) continue;
      ++n_in_region;
      const Vec3 &x0 = nodes.X[f.nodes[0]], &x1 = nodes.X[f.nodes[1]], &x2 = nodes.X[f.nodes[2]];
      if (direction && !faces_direction<3>((x1 - x0).cross(x2 - x0), *direction)) continue;
      f.expression = expr;
      bc.traction_faces.push_back(f), ++n_faces;
    }
    check_traction_support(scene, k, n_faces, n_in_region, "boundary faces with every corner in the region");
    for (Index e : expr)
      if (e != kNoIndex) bc.has_loads = true, bc.loads_depend_on_time |= bc.expressions[std::size_t(e)].depends_on_time();
  }
  if (frozen_tractions) {
    bc.traction_faces = *frozen_tractions;
    for (const TractionFace& f : bc.traction_faces)
      for (Index e : f.expression)
        if (e != kNoIndex) bc.has_loads = true, bc.loads_depend_on_time |= bc.expressions[std::size_t(e)].depends_on_time();
  }
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    std::array<Index, 3> expr{kNoIndex, kNoIndex, kNoIndex};
    for (int d = 0; d < 3; ++d)
      if (const auto e = combine(scene.body_force[d], scene.bodies[b].body_force[d])) expr[std::size_t(d)] = add_expression(bc, *e);
    for (Index e : expr)
      if (e != kNoIndex) bc.has_loads = true, bc.loads_depend_on_time |= bc.expressions[std::size_t(e)].depends_on_time();
    bc.body_force.push_back(expr);
  }
  const Index n_dofs = nodes.size() * dofs_per_node;
  bc.target = Eigen::VectorXd::Zero(n_dofs);
  bc.external = Eigen::VectorXd::Zero(n_dofs);
  return bc;
}

}  // namespace loom
