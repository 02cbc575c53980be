// Geometry of the smoothing domains in B_n (seed 001 §3.3, eqs 30-35): volume V^k, smoothed gradients b~_I
// and midpoint of every domain of an Edges store, from the node positions X + u_n. Run at set-up and at
// every commit, like compute_geometry for quadrature points.
//
// Layout of edges.gradient(k): the same as QuadPoints' shape gradients, a column-major S x D matrix
// (S = edges.stride()) whose row I is b~_I of stencil slot I:
//   Eigen::Map<Eigen::Matrix<double, S, D>>(edges.gradient(k)).row(I) = b~_I^T,
// i.e. component d of slot I at edges.gradient(k)[I + d * S].
//
// 2D: an edge domain holds the sub-triangle (a, b, centroid) of each adjacent triangle, a third of its area.
// 3D: a face domain holds the sub-tetrahedron (face, centroid) of each adjacent tetrahedron, a quarter of its
// volume. Linear shape functions make grad N^e constant over each simplex, so the smoothed gradient
// (1/V^k) int_{Omega^k} grad N_I dV (seed 001 eq 33) is the volume-weighted mean of the simplices' ones.
#pragma once

#include "engine/core/types.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/edges.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

// `cells` is the block the domains were built from (engine/mesh/smoothing_edges, smoothing_faces). Works for
// edge and face domains and for whole-simplex domains. Returns the number of domains with an adjacent simplex
// of non-positive volume in B_n (inverted or degenerate); their values are not usable.
template <int D>
Index compute_smoothing_geometry(const Nodes<D>& nodes, const Cells& cells, Edges<D>& edges);

}  // namespace loom
