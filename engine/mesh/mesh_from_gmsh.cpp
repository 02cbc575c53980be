#include "engine/mesh/mesh_from_gmsh.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "engine/core/errors.hpp"
#include "engine/mesh/triangle_geometry.hpp"

namespace loom {
namespace {

constexpr int kTriangle3 = 2, kTriangle6 = 9;

// det of the isoparametric map of a 6-node triangle at barycentric (l0, l1, l2), corners and mid-nodes x[6].
double tri6_jacobian(const Vec2 x[6], double l1, double l2) {
  const double l0 = 1 - l1 - l2;
  // dN/dl1 and dN/dl2 with l0 = 1 - l1 - l2; nodes: c0 c1 c2 m01 m12 m20.
  const double d1[6] = {-(4 * l0 - 1), 4 * l1 - 1, 0, 4 * (l0 - l1), 4 * l2, -4 * l2};
  const double d2[6] = {-(4 * l0 - 1), 0, 4 * l2 - 1, -4 * l1, 4 * l1, 4 * (l0 - l2)};
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();
  for (int k = 0; k < 6; ++k) a += d1[k] * x[k], b += d2[k] * x[k];
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

MeshData triangle_mesh_of(const GmshFile& file, const std::string& surface, const std::string& where, const std::string& key) {
  auto fail = [&](const std::string& why) { throw InputError(where + ": error: " + key + ": " + file.path + ": " + why); };

  // Which 2D elements make the body.
  const std::unordered_set<std::size_t> selected = elements_of_group(file, surface, 2, where, key);
  const GmshElementBlock* tri = nullptr;
  for (const auto& b : file.blocks) {
    if (b.dim == 3) fail("it holds volume elements (" + b.name + "): a three-dimensional body needs scene.dimension = 3 (this scene is two-dimensional)");
    if (b.dim != 2) continue;
    if (b.type != kTriangle3 && b.type != kTriangle6) {
      std::ostringstream os;
      os << "it holds " << b.name << " elements (gmsh element type " << b.type << "): loom reads 3- and 6-node triangles";
      fail(os.str());
    }
    if (tri && tri->type != b.type) fail("it mixes 3- and 6-node triangles: mesh it with one Mesh.ElementOrder");
    tri = &b;
  }
  if (!tri) fail("it holds no triangles (mesh the surfaces: gmsh -2)");
  const bool quadratic = tri->type == kTriangle6;
  const int npe = tri->nodes_per_element;

  // Corners first, numbered in order of first use; then mid-nodes.
  MeshData mesh;
  std::vector<Index> corner_of(file.nodes.size(), kNoIndex), mid_of(file.nodes.size(), kNoIndex);
  std::vector<std::size_t> elements;
  for (std::size_t e = 0; e < tri->tags.size(); ++e)
    if (surface.empty() || selected.count(tri->tags[e])) elements.push_back(e);
  if (elements.empty()) fail("the physical surface \"" + surface + "\" holds no triangles");
  double extent = 0.0;
  for (std::size_t e : elements)
    for (int a = 0; a < npe; ++a) {
      const auto& p = file.nodes[std::size_t(tri->nodes[e * std::size_t(npe) + std::size_t(a)])];
      extent = std::max({extent, std::abs(p[0]), std::abs(p[1])});
    }
  for (std::size_t e : elements)
    for (int a = 0; a < npe; ++a) {
      const Index n = tri->nodes[e * std::size_t(npe) + std::size_t(a)];
      const auto& p = file.nodes[std::size_t(n)];
      if (std::abs(p[2]) > 1e-9 * std::max(1.0, extent)) {
        std::ostringstream os;
        os << "node at (" << p[0] << ", " << p[1] << ", " << p[2] << ") is off the plane z = 0: a 2D mesh lies in the x-y plane";
        fail(os.str());
      }
      std::vector<Index>& index = a < 3 ? corner_of : mid_of;
      std::vector<Vec2>& X = a < 3 ? mesh.X : mesh.mid_X;
      if (index[std::size_t(n)] == kNoIndex) index[std::size_t(n)] = Index(X.size()), X.emplace_back(p[0], p[1]);
    }
  for (Index n = 0; n < Index(file.nodes.size()); ++n)
    if (corner_of[std::size_t(n)] != kNoIndex && mid_of[std::size_t(n)] != kNoIndex) fail("a node is a corner of one triangle and a mid-node of another");

  // Orientation: counter-clockwise is the mesh's majority; a cell of the other sign is inverted.
  std::vector<double> area(elements.size());
  int positive = 0;
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const Index* v = tri->nodes.data() + elements[k] * std::size_t(npe);
    area[k] = signed_area(mesh.X[std::size_t(corner_of[std::size_t(v[0])])], mesh.X[std::size_t(corner_of[std::size_t(v[1])])],
                          mesh.X[std::size_t(corner_of[std::size_t(v[2])])]);
    positive += area[k] > 0;
  }
  const double sign = 2 * positive >= int(elements.size()) ? 1.0 : -1.0;
  double mean_area = 0.0;
  for (double a : area) mean_area += std::abs(a) / double(area.size());
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const std::size_t tag = tri->tags[elements[k]];
    if (std::abs(area[k]) <= 1e-12 * mean_area) fail("triangle " + std::to_string(tag) + " (element tag) has zero area");
    if (sign * area[k] < 0)
      fail("triangle " + std::to_string(tag) + " (element tag) is inverted: its corners run the other way round than those of the rest of the mesh");
    const Index* v = tri->nodes.data() + elements[k] * std::size_t(npe);
    // gmsh order c0 c1 c2 (m01 m12 m20); a clockwise mesh is turned: c0 c2 c1 (m20 m12 m01).
    const Index c[3] = {corner_of[std::size_t(v[0])], corner_of[std::size_t(v[sign > 0 ? 1 : 2])], corner_of[std::size_t(v[sign > 0 ? 2 : 1])]};
    mesh.triangles.insert(mesh.triangles.end(), c, c + 3);
    mesh.source_tag.push_back(tag);
    if (!quadratic) continue;
    const Index m[3] = {mid_of[std::size_t(v[sign > 0 ? 3 : 5])], mid_of[std::size_t(v[4])], mid_of[std::size_t(v[sign > 0 ? 5 : 3])]};
    mesh.mid_nodes.insert(mesh.mid_nodes.end(), m, m + 3);
    const Vec2 x[6] = {mesh.X[std::size_t(c[0])], mesh.X[std::size_t(c[1])], mesh.X[std::size_t(c[2])],
                       mesh.mid_X[std::size_t(m[0])], mesh.mid_X[std::size_t(m[1])], mesh.mid_X[std::size_t(m[2])]};
    // A curved 6-node triangle folds where the determinant of its map changes sign: check corners and midpoints.
    const double at[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};
    for (const auto& l : at)
      if (!(tri6_jacobian(x, l[0], l[1]) > 0.0))
        fail("6-node triangle " + std::to_string(tag) + " (element tag) is inverted: its curved edges fold it over (move its mid-nodes toward the straight edges)");
  }

  // Regions: every physical group, by its corner nodes in this body (and a curve's edges).
  std::unordered_map<std::size_t, std::pair<const GmshElementBlock*, std::size_t>> line_of;  // element tag -> line element
  for (const auto& b : file.blocks)
    if (b.dim == 1)
      for (std::size_t e = 0; e < b.tags.size(); ++e) line_of[b.tags[e]] = {&b, e};
  for (std::size_t k = 0; k < file.groups.size(); ++k) {
    const GmshGroup& g = file.groups[k];
    MeshRegion r;
    r.name = g.name;
    r.dim = g.dim;
    for (Index n : g.nodes)
      if (corner_of[std::size_t(n)] != kNoIndex) r.corners.push_back(corner_of[std::size_t(n)]);
    std::sort(r.corners.begin(), r.corners.end());
    if (g.dim == 1)
      for (std::size_t tag : file.group_elements[k]) {
        auto it = line_of.find(tag);
        if (it == line_of.end()) continue;
        const auto& [block, e] = it->second;
        const Index a = corner_of[std::size_t(block->nodes[e * std::size_t(block->nodes_per_element)])];
        const Index b = corner_of[std::size_t(block->nodes[e * std::size_t(block->nodes_per_element) + 1])];
        if (a != kNoIndex && b != kNoIndex) r.edges.push_back({std::min(a, b), std::max(a, b)});
      }
    mesh.regions.push_back(std::move(r));
  }
  return mesh;
}

}  // namespace loom
