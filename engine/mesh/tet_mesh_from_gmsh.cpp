#include "engine/mesh/tet_mesh_from_gmsh.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "engine/core/errors.hpp"

namespace loom {
namespace {

constexpr int kTetrahedron4 = 4, kTetrahedron10 = 11;
// VTK slot k of a 10-node cell takes gmsh's node kGmshOfVtk[k]: gmsh numbers the last two edges 32, 31.
constexpr int kGmshOfVtk[10] = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};

// det of the map of a 10-node tetrahedron (VTK order) at barycentric l, times 1 (6 V for a straight cell).
double tet10_jacobian(const Vec3 x[10], const double l[4]) {
  static constexpr int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  const double dl[4][3] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  Mat3 J = Mat3::Zero();  // J_ij = sum_A x^A_i dN^A/dxi_j
  for (int a = 0; a < 4; ++a)
    for (int j = 0; j < 3; ++j) J.col(j) += (4 * l[a] - 1) * dl[a][j] * x[a];
  for (int e = 0; e < 6; ++e) {
    const int a = edges[e][0], b = edges[e][1];
    for (int j = 0; j < 3; ++j) J.col(j) += 4 * (l[b] * dl[a][j] + l[a] * dl[b][j]) * x[4 + e];
  }
  return J.determinant();
}

}  // namespace

TetMeshFile tet_mesh_of(const GmshFile& file, const std::string& volume, const std::string& where, const std::string& key) {
  auto fail = [&](const std::string& why) { throw InputError(where + ": error: " + key + ": " + file.path + ": " + why); };
  const std::unordered_set<std::size_t> selected = elements_of_group(file, volume, 3, where, key);
  const GmshElementBlock* tets = nullptr;
  for (const auto& b : file.blocks) {
    if (b.dim != 3) continue;
    if (b.type != kTetrahedron4 && b.type != kTetrahedron10)
      fail("it holds " + b.name + " elements (gmsh element type " + std::to_string(b.type) + "): loom reads 4- and 10-node tetrahedra");
    if (tets && tets->type != b.type) fail("it mixes 4- and 10-node tetrahedra: mesh it with one Mesh.ElementOrder");
    tets = &b;
  }
  if (!tets) fail("it holds no tetrahedra (mesh the volumes: gmsh -3)");
  const int npe = tets->nodes_per_element;
  std::vector<std::size_t> elements;
  for (std::size_t e = 0; e < tets->tags.size(); ++e)
    if (volume.empty() || selected.count(tets->tags[e])) elements.push_back(e);
  if (elements.empty()) fail("the physical volume \"" + volume + "\" holds no tetrahedra");

  TetMeshFile out;
  TetMeshData& mesh = out.corners;
  std::vector<Index> corner_of(file.nodes.size(), kNoIndex), mid_of(file.nodes.size(), kNoIndex);
  std::vector<Vec3> mid_X;
  for (std::size_t e : elements)
    for (int a = 0; a < npe; ++a) {
      const Index n = tets->nodes[e * std::size_t(npe) + std::size_t(a)];
      const auto& p = file.nodes[std::size_t(n)];
      std::vector<Index>& index = a < 4 ? corner_of : mid_of;
      std::vector<Vec3>& X = a < 4 ? mesh.X : mid_X;
      if (index[std::size_t(n)] == kNoIndex) index[std::size_t(n)] = Index(X.size()), X.emplace_back(p[0], p[1], p[2]);
    }
  double mean_volume = 0.0;
  for (std::size_t e : elements) {
    const Index* v = tets->nodes.data() + e * std::size_t(npe);
    auto x = [&](int a) { return mesh.X[std::size_t(corner_of[std::size_t(v[a])])]; };
    mean_volume += std::abs(tet_volume(x(0), x(1), x(2), x(3))) / double(elements.size());
  }
  const Index n_corners = Index(mesh.X.size());
  if (npe == 10) {
    out.quadratic.X = mesh.X;
    out.quadratic.X.insert(out.quadratic.X.end(), mid_X.begin(), mid_X.end());
    out.quadratic.n_corners = n_corners;
  }
  for (std::size_t e : elements) {
    const Index* v = tets->nodes.data() + e * std::size_t(npe);
    const std::size_t tag = tets->tags[e];
    Index c[4];
    for (int a = 0; a < 4; ++a) c[a] = corner_of[std::size_t(v[a])];
    const double V = tet_volume(mesh.X[std::size_t(c[0])], mesh.X[std::size_t(c[1])], mesh.X[std::size_t(c[2])], mesh.X[std::size_t(c[3])]);
    if (std::abs(V) <= 1e-12 * mean_volume) fail("tetrahedron " + std::to_string(tag) + " (element tag) has zero volume");
    if (V < 0.0) fail("tetrahedron " + std::to_string(tag) + " (element tag) is inverted: its corners are ordered the other way round than gmsh's");
    mesh.tets.insert(mesh.tets.end(), c, c + 4);
    mesh.source_tag.push_back(tag);
    if (npe != 10) continue;
    Vec3 x[10];
    Index cell[10];
    for (int k = 0; k < 10; ++k) {
      const Index n = v[kGmshOfVtk[k]];
      cell[k] = k < 4 ? c[k] : n_corners + mid_of[std::size_t(n)];
      x[k] = out.quadratic.X[std::size_t(cell[k])];
    }
    // A curved 10-node tetrahedron folds where the determinant of its map changes sign: check corners and centroid.
    const double at[5][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}, {0.25, 0.25, 0.25, 0.25}};
    for (const auto& l : at)
      if (!(tet10_jacobian(x, l) > 0.0))
        fail("10-node tetrahedron " + std::to_string(tag) + " (element tag) is inverted: its curved edges fold it over");
    out.quadratic.cells.insert(out.quadratic.cells.end(), cell, cell + 10);
  }
  for (Index n = 0; n < Index(file.nodes.size()); ++n)
    if (corner_of[std::size_t(n)] != kNoIndex && mid_of[std::size_t(n)] != kNoIndex) fail("a node is a corner of one tetrahedron and a mid-node of another");

  for (const GmshGroup& g : file.groups) {
    MeshRegion r;
    r.name = g.name;
    r.dim = g.dim;
    for (Index n : g.nodes)
      if (corner_of[std::size_t(n)] != kNoIndex) r.corners.push_back(corner_of[std::size_t(n)]);
    std::sort(r.corners.begin(), r.corners.end());
    mesh.regions.push_back(std::move(r));
  }
  out.quadratic.regions = mesh.regions;
  return out;
}

}  // namespace loom
