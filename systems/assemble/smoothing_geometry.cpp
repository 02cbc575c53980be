#include "systems/assemble/smoothing_geometry.hpp"

#include <atomic>

#include "engine/core/errors.hpp"
#include "engine/core/parallel.hpp"
#include "systems/assemble/elements/tet4.hpp"
#include "systems/assemble/elements/tri3.hpp"

namespace loom {

namespace {

int slot_of(const Index* stencil, int S, Index node) {
  for (int I = 0; I < S; ++I)
    if (stencil[I] == node) return I;
  return -1;
}

// Gradients of the corners of simplex t (rows) and its volume in B_n.
double simplex_gradients(const Nodes<2>& nodes, const Index* c, Eigen::Matrix<double, 3, 2>& dN) {
  Tri3Gradients g;
  const double area = tri3_gradients(nodes.position_n(c[0]), nodes.position_n(c[1]), nodes.position_n(c[2]), g);
  dN = g;
  return area;
}
double simplex_gradients(const Nodes<3>& nodes, const Index* c, Eigen::Matrix<double, 4, 3>& dN) {
  Tet4Corners x;
  for (int a = 0; a < 4; ++a) x.row(a) = nodes.position_n(c[a]).transpose();
  Tet4Gradients g;
  const double volume = tet4_gradients(x, g);
  dN = g;
  return volume;
}

// The point the domain's pressure is read at: the edge's midpoint or the face's centroid, the simplex's centroid.
Vec2 domain_point(const Nodes<2>& nodes, const Index* s, bool whole) {
  return whole ? Vec2((nodes.position_n(s[0]) + nodes.position_n(s[1]) + nodes.position_n(s[2])) / 3.0)
               : Vec2(0.5 * (nodes.position_n(s[0]) + nodes.position_n(s[1])));
}
Vec3 domain_point(const Nodes<3>& nodes, const Index* s, bool whole) {
  return whole ? Vec3((nodes.position_n(s[0]) + nodes.position_n(s[1]) + nodes.position_n(s[2]) + nodes.position_n(s[3])) / 4.0)
               : Vec3((nodes.position_n(s[0]) + nodes.position_n(s[1]) + nodes.position_n(s[2])) / 3.0);
}

}  // namespace

template <int D>
Index compute_smoothing_geometry(const Nodes<D>& nodes, const Cells& cells, Edges<D>& edges) {
  constexpr int kCorners = D + 1, kMaxSlots = D + 2;
  using StencilGradients = Eigen::Matrix<double, kMaxSlots, D>;  // row I accumulates the weighted gradient of slot I
  const int S = edges.stride();
  LOOM_ASSERT(S == kCorners || S == kMaxSlots, "smoothing domains have " << kCorners << " or " << kMaxSlots << " stencil nodes, not " << S);
  std::atomic<Index> bad{0};
  for_each_index(edges.size(), [&](Index k) {
    const Index* s = edges.stencil.cell_nodes(k);
    const bool whole = edges.whole_triangles;
    const double share = whole ? 1.0 : 1.0 / double(kCorners);
    // A stencil node that is not a corner of e gets nothing from e.
    StencilGradients G = StencilGradients::Zero();
    double volume = 0.0;
    bool ok = true;
    for (int j = 0; j < 2; ++j) {
      const Index t = edges.triangles[2 * k + j];
      if (t == kNoIndex) continue;
      const Index* c = cells.cell_nodes(t);
      Eigen::Matrix<double, kCorners, D> dN;
      const double measure = simplex_gradients(nodes, c, dN);
      ok = ok && measure > 0.0;
      const double w = share * measure;
      volume += w;
      for (int a = 0; a < kCorners; ++a) {
        const int I = slot_of(s, S, c[a]);
        LOOM_ASSERT(I >= 0, "corner " << c[a] << " of cell " << t << " is not in the stencil of domain " << k);
        G.row(I) += w * dN.row(a);
      }
    }
    if (!ok) bad.fetch_add(1, std::memory_order_relaxed);
    edges.volume_n[k] = volume;
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, D>>(edges.gradient(k), S, D) = G.topRows(S) / volume;
    edges.midpoint[k] = domain_point(nodes, s, whole);
  });
  return bad.load();
}

template Index compute_smoothing_geometry<2>(const Nodes<2>&, const Cells&, Edges<2>&);
template Index compute_smoothing_geometry<3>(const Nodes<3>&, const Cells&, Edges<3>&);

}  // namespace loom
