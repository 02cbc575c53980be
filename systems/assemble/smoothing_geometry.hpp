// Geometry of the smoothing domains in B_n (seed 001 §3.3, eqs 30-35): volume V^k, smoothed gradients b~_I
// and midpoint of every domain of an Edges store, from the node positions X + u_n. Run at set-up and at
// every commit, like compute_geometry for quadrature points.
//
// Layout of edges.gradient(k): the same as QuadPoints' shape gradients, a column-major S x 2 matrix
// (S = edges.stride()) whose row I is b~_I of stencil slot I:
//   Eigen::Map<Eigen::Matrix<double, S, 2>>(edges.gradient(k)).row(I) = b~_I^T,
// i.e. component d of slot I at edges.gradient(k)[I + d * S].
#pragma once

#include "engine/core/types.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/edges.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

// `triangles` is the block the domains were built from (engine/mesh/smoothing_edges). Works for edge
// domains (stencil4 interior, stencil3 boundary) and triangle domains. Returns the number of domains with
// an adjacent triangle of non-positive area in B_n (inverted or degenerate); their values are not usable.
Index compute_smoothing_geometry(const Nodes<2>& nodes, const Cells& triangles, Edges<2>& edges);

}  // namespace loom
