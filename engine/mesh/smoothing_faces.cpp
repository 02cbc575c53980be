#include "engine/mesh/smoothing_faces.hpp"

#include <vector>

#include "engine/core/errors.hpp"
#include "engine/mesh/colouring.hpp"
#include "engine/mesh/tet_adjacency.hpp"
#include "engine/mesh/tet_mesh.hpp"

namespace loom {

namespace {

// A face as the tetrahedron loop first meets it.
struct FaceRecord {
  std::array<Index, 3> nodes;  // outward from t0
  Index t0, opposite0;
  Index t1 = kNoIndex, opposite1 = kNoIndex;  // kNoIndex on the surface
};

std::vector<Index> corner_connectivity(const Cells& tets) {
  std::vector<Index> corners;
  corners.reserve(std::size_t(tets.size()) * 4);
  for (Index t = 0; t < tets.size(); ++t) {
    const Index* c = tets.cell_nodes(t);
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < a; ++b)
        LOOM_CHECK(c[a] != c[b], InputError, "mesh error: tetrahedron " << t << " uses node " << c[a] << " twice");
    corners.insert(corners.end(), c, c + 4);
  }
  return corners;
}

// Faces in order of first appearance: a face belongs to the tetrahedron with the smaller index (the neighbour
// list says which one that is, so no face is visited twice).
std::vector<FaceRecord> collect_faces(const Cells& tets) {
  const std::vector<Index> corners = corner_connectivity(tets);
  const std::vector<std::array<Index, 4>> across = tet_face_neighbours(corners);
  std::vector<FaceRecord> faces;
  faces.reserve(2 * across.size() + 4);
  for (std::size_t t = 0; t < across.size(); ++t) {
    const Index* v = corners.data() + 4 * t;
    for (int f = 0; f < 4; ++f) {
      const Index other = across[t][std::size_t(f)];
      LOOM_CHECK(other != kNonManifold, InputError,
                 "mesh error: a face of tetrahedron " << t << " (nodes " << v[kTetFaces[f][0]] << ", " << v[kTetFaces[f][1]] << ", "
                                                      << v[kTetFaces[f][2]] << ") is shared by more than two tetrahedra");
      if (other != kNoIndex && other < Index(t)) continue;  // met first from `other`
      FaceRecord r{{v[kTetFaces[f][0]], v[kTetFaces[f][1]], v[kTetFaces[f][2]]}, Index(t), v[f]};
      if (other != kNoIndex) {
        r.t1 = other;
        const Index* w = corners.data() + 4 * std::size_t(other);
        for (int a = 0; a < 4; ++a)
          if (w[a] != r.nodes[0] && w[a] != r.nodes[1] && w[a] != r.nodes[2]) r.opposite1 = w[a];
      }
      faces.push_back(r);
    }
  }
  return faces;
}

void fill_faces(Edges<3>& store, const std::vector<FaceRecord>& faces, bool interior, const Cells& tets, Index n_nodes) {
  store.stencil = Cells(interior ? CellType::stencil5 : CellType::stencil4, tets.formulation);
  const int S = store.stride();
  std::vector<Index>& nodes = store.stencil.nodes.values();
  std::vector<Index>& body = store.stencil.body.values();
  std::vector<const FaceRecord*> chosen;
  for (const FaceRecord& r : faces)
    if ((r.t1 != kNoIndex) == interior) chosen.push_back(&r);
  const Index n = Index(chosen.size());
  nodes.reserve(std::size_t(n) * std::size_t(S));
  body.reserve(std::size_t(n));
  for (const FaceRecord* r : chosen) {
    nodes.insert(nodes.end(), {r->nodes[0], r->nodes[1], r->nodes[2], r->opposite0});
    if (interior) nodes.push_back(r->opposite1);
    body.push_back(tets.body[r->t0]);
  }
  store.resize(n);
  for (Index k = 0; k < n; ++k) {
    store.triangles[2 * k] = chosen[std::size_t(k)]->t0;
    store.triangles[2 * k + 1] = chosen[std::size_t(k)]->t1;
    for (int a = 0; a < 3; ++a) store.pressure_weight[k * S + a] = 1.0 / 3.0;
  }
  colour_cells(store.stencil, n_nodes);
}

}  // namespace

FaceDomains build_face_domains(const Cells& tets, Index n_nodes) {
  const std::vector<FaceRecord> faces = collect_faces(tets);
  FaceDomains domains;
  fill_faces(domains.interior, faces, true, tets, n_nodes);
  fill_faces(domains.boundary, faces, false, tets, n_nodes);
  return domains;
}

}  // namespace loom
