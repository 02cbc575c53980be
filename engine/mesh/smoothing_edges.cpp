#include "engine/mesh/smoothing_edges.hpp"

#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "engine/core/errors.hpp"
#include "engine/mesh/colouring.hpp"

namespace loom {

namespace {

// An edge as the triangle loop finds it: first (and second) adjacent triangle and opposite vertex.
struct EdgeRecord {
  Index a, b;                                 // counter-clockwise in triangle t0
  Index t0, opposite0;
  Index t1 = kNoIndex, opposite1 = kNoIndex;  // kNoIndex on the boundary
};

// Edges in order of first appearance. A hash map on the sorted node pair finds the second visit; the
// order comes from the triangle loop, never from the map, so it is deterministic.
std::vector<EdgeRecord> collect_edges(const Cells& triangles) {
  const Index n = triangles.size();
  std::vector<EdgeRecord> edges;
  // Each triangle has 3 sides and each interior edge is counted twice: E = (3T + B) / 2, so 2T + 3 holds
  // every edge while B <= T + 6 (a strip of triangles has B = T + 2; a full mesh far fewer).
  const std::size_t capacity = 2 * std::size_t(n) + 3;
  edges.reserve(capacity);
  std::unordered_map<std::uint64_t, Index> index_of;
  index_of.reserve(capacity);
  for (Index t = 0; t < n; ++t) {
    const Index* c = triangles.cell_nodes(t);
    for (int s = 0; s < 3; ++s) {
      const Index a = c[s], b = c[(s + 1) % 3], opposite = c[(s + 2) % 3];
      LOOM_CHECK(a != b, InputError, "mesh error: triangle " << t << " uses node " << a << " twice");
      const auto lo = std::uint64_t(std::uint32_t(std::min(a, b))), hi = std::uint64_t(std::uint32_t(std::max(a, b)));
      const auto [it, inserted] = index_of.try_emplace((lo << 32) | hi, Index(edges.size()));
      if (inserted) {
        edges.push_back({a, b, t, opposite});
        continue;
      }
      EdgeRecord& e = edges[std::size_t(it->second)];
      LOOM_CHECK(e.t1 == kNoIndex, InputError,
                 "mesh error: the edge between nodes " << e.a << " and " << e.b << " is shared by more than two triangles ("
                                                       << e.t0 << ", " << e.t1 << ", " << t << ")");
      e.t1 = t;
      e.opposite1 = opposite;
    }
  }
  return edges;
}

// Fills one store from the records whose interior-ness matches the store's stencil size.
void fill_edges(Edges<2>& store, const std::vector<EdgeRecord>& edges, bool interior, const Cells& triangles, Index n_nodes) {
  store.stencil = Cells(interior ? CellType::stencil4 : CellType::stencil3, triangles.formulation);
  const int S = store.stride();
  std::vector<Index>& nodes = store.stencil.nodes.values();
  std::vector<Index>& body = store.stencil.body.values();
  std::vector<const EdgeRecord*> chosen;
  for (const EdgeRecord& e : edges)
    if ((e.t1 != kNoIndex) == interior) chosen.push_back(&e);
  const Index n = Index(chosen.size());
  nodes.reserve(std::size_t(n) * std::size_t(S));
  body.reserve(std::size_t(n));
  for (const EdgeRecord* e : chosen) {
    nodes.insert(nodes.end(), {e->a, e->b, e->opposite0});
    if (interior) nodes.push_back(e->opposite1);
    body.push_back(triangles.body[e->t0]);
  }
  store.resize(n);
  for (Index k = 0; k < n; ++k) {
    store.triangles[2 * k] = chosen[std::size_t(k)]->t0;
    store.triangles[2 * k + 1] = chosen[std::size_t(k)]->t1;
    // The pressure of an edge domain is that of the edge's midpoint: linear p along the edge.
    store.pressure_weight[k * S] = store.pressure_weight[k * S + 1] = 0.5;
  }
  colour_cells(store.stencil, n_nodes);
}

}  // namespace

EdgeDomains build_edge_domains(const Cells& triangles, Index n_nodes) {
  const std::vector<EdgeRecord> edges = collect_edges(triangles);
  EdgeDomains domains;
  fill_edges(domains.interior, edges, true, triangles, n_nodes);
  fill_edges(domains.boundary, edges, false, triangles, n_nodes);
  return domains;
}

}  // namespace loom
