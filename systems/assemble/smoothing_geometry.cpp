#include "systems/assemble/smoothing_geometry.hpp"

#include <atomic>

#include "engine/core/errors.hpp"
#include "engine/core/parallel.hpp"
#include "systems/assemble/elements/tri3.hpp"

namespace loom {

namespace {

// Up to 4 stencil slots; row I accumulates the weighted gradient of slot I.
using StencilGradients = Eigen::Matrix<double, 4, 2>;

int slot_of(const Index* stencil, int S, Index node) {
  for (int I = 0; I < S; ++I)
    if (stencil[I] == node) return I;
  return -1;
}

}  // namespace

Index compute_smoothing_geometry(const Nodes<2>& nodes, const Cells& triangles, Edges<2>& edges) {
  const int S = edges.stride();
  LOOM_ASSERT(S == 3 || S == 4, "smoothing domains have 3 or 4 stencil nodes, not " << S);
  std::atomic<Index> bad{0};
  for_each_index(edges.size(), [&](Index k) {
    const Index* s = edges.stencil.cell_nodes(k);
    // An edge domain holds the sub-triangle (a, b, centroid) of each adjacent triangle, a third of its
    // area; a triangle domain the whole triangle.
    const bool whole_triangle = edges.whole_triangles;
    const double share = whole_triangle ? 1.0 : 1.0 / 3.0;
    // Linear N_I^e make grad N_I^e constant over each sub-triangle, so the smoothed gradient
    // (1/V^k) int_{Omega^k} grad N_I dV (seed 001 eq 33) is the area-weighted mean of the triangles' ones;
    // a stencil node that is not a corner of e gets nothing from e.
    StencilGradients G = StencilGradients::Zero();
    double volume = 0.0;
    bool ok = true;
    for (int j = 0; j < 2; ++j) {
      const Index t = edges.triangles[2 * k + j];
      if (t == kNoIndex) continue;
      const Index* c = triangles.cell_nodes(t);
      Tri3Gradients dN;
      const double area = tri3_gradients(nodes.position_n(c[0]), nodes.position_n(c[1]), nodes.position_n(c[2]), dN);
      ok = ok && area > 0.0;
      const double w = share * area;
      volume += w;
      for (int a = 0; a < 3; ++a) {
        const int I = slot_of(s, S, c[a]);
        LOOM_ASSERT(I >= 0, "corner " << c[a] << " of triangle " << t << " is not in the stencil of domain " << k);
        G.row(I) += w * dN.row(a);
      }
    }
    if (!ok) bad.fetch_add(1, std::memory_order_relaxed);
    edges.volume_n[k] = volume;
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 2>>(edges.gradient(k), S, 2) = G.topRows(S) / volume;
    edges.midpoint[k] = whole_triangle ? Vec2((nodes.position_n(s[0]) + nodes.position_n(s[1]) + nodes.position_n(s[2])) / 3.0)
                                       : Vec2(0.5 * (nodes.position_n(s[0]) + nodes.position_n(s[1])));
  });
  return bad.load();
}

}  // namespace loom
