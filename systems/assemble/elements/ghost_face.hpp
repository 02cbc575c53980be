// Face ghost penalty of an MPM background grid (Burman's ghost penalty as used for the MPM by Coombs et al.,
// IJNME 2020, and for mixed u-p MPM by arXiv 2405.12814): on a face F shared by two active cells, at least one
// of which is cut by the body's boundary,
//   g(u, v) = gamma_u int_F [[du/dn]] . [[dv/dn]] ds,   g_p(p, q) = gamma_p int_F [[dp/dn]] [[dq/dn]] ds,
// with [[dw/dn]] = grad w|_L . n - grad w|_R . n (n: the unit normal of F out of the left cell L), and
//   gamma_u = gamma_0 mu h_F,   gamma_p = gamma_0 h_F^3 / (2 mu)
// so that g is of the size of the stiffness (mu int grad u : grad v) and g_p of the pressure stabilisation
// tau1 int grad p . grad q (tau1 = h^2 / (2 mu)) of one cell. The penalty vanishes for fields that are linear
// across the face (their gradient does not jump), so it does not touch a solution a linear grid represents
// exactly, and it ties the nodes of nearly empty cells, whose particles near the far side give them almost
// no mass and, for bilinear cells, almost no stiffness (the gradient of N_a vanishes on the sides away from
// corner a), to their neighbours. It is linear in the step displacement and the pressure: residual K w,
// tangent K.
//
// Local nodes: the NC corners of L, then the NC - 2 corners of R not on F (NF = 2 NC - 2); local dofs
// node-major with PN per node (2: u; 3: u and p).
#pragma once

#include <Eigen/Core>
#include <array>

#include "engine/core/types.hpp"
#include "engine/mesh/grid_shape.hpp"

namespace loom {

template <int NC>
inline constexpr int kGhostFaceNodes = 2 * NC - 2;

template <int NC>
struct GhostFace {
  Index left = kNoIndex, right = kNoIndex;          // cells
  std::array<Index, 2 * NC - 2> nodes{};            // local nodes (see above)
  std::array<int, NC> right_local{};                // local index of each corner of R
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();          // the face's end points
};

// The local nodes of the face between cells L and R (sharing the side with corners i, j).
template <int NC>
GhostFace<NC> ghost_face(const Cells& grid, const Nodes<2>& nodes, Index left, Index right, Index i, Index j) {
  GhostFace<NC> f;
  f.left = left, f.right = right;
  for (int c = 0; c < NC; ++c) f.nodes[std::size_t(c)] = grid.node(left, c);
  int next = NC;
  for (int c = 0; c < NC; ++c) {
    const Index n = grid.node(right, c);
    int k = 0;
    while (k < NC && grid.node(left, k) != n) ++k;
    if (k == NC) f.nodes[std::size_t(next)] = n, k = next++;
    f.right_local[std::size_t(c)] = k;
  }
  f.a = nodes.X[i], f.b = nodes.X[j];
  return f;
}

// Jump coefficients at x on the face: [[dw/dn]] = sum_k w_k value_k over the local nodes.
template <int NC>
Eigen::Matrix<double, 2 * NC - 2, 1> ghost_jump(const Cells& grid, const Nodes<2>& nodes, const GhostFace<NC>& f, const Vec2& x,
                                                const Vec2& n) {
  Eigen::Matrix<double, 2 * NC - 2, 1> w = Eigen::Matrix<double, 2 * NC - 2, 1>::Zero();
  const CornerGradients<NC> gl = grid_shape_gradients<NC>(grid, nodes, f.left, grid_shape_at(grid, nodes, f.left, x));
  const CornerGradients<NC> gr = grid_shape_gradients<NC>(grid, nodes, f.right, grid_shape_at(grid, nodes, f.right, x));
  for (int c = 0; c < NC; ++c) {
    w[c] += gl.row(c).dot(n);
    w[f.right_local[std::size_t(c)]] -= gr.row(c).dot(n);
  }
  return w;
}

// The face's penalty matrix over its local dofs (PN per node), integrated with two Gauss points (exact:
// the jump is at most linear along the face).
template <int NC, int PN>
Eigen::Matrix<double, PN*(2 * NC - 2), PN*(2 * NC - 2)> ghost_penalty_matrix(const Cells& grid, const Nodes<2>& nodes,
                                                                             const GhostFace<NC>& f, double gamma_0, double mu) {
  constexpr int NF = 2 * NC - 2;
  Eigen::Matrix<double, PN * NF, PN * NF> K = Eigen::Matrix<double, PN * NF, PN * NF>::Zero();
  const Vec2 t = f.b - f.a;
  const double h = t.norm();
  // Out of L: the side of the face away from L's centroid.
  Vec2 centre = Vec2::Zero();
  for (int c = 0; c < NC; ++c) centre += nodes.X[grid.node(f.left, c)] / NC;
  Vec2 n(t.y() / h, -t.x() / h);
  if (n.dot(0.5 * (f.a + f.b) - centre) < 0.0) n = -n;
  const double gamma_u = gamma_0 * mu * h, gamma_p = gamma_0 * h * h * h / (2.0 * mu);
  for (const double s : {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)}) {
    const Eigen::Matrix<double, NF, 1> w = ghost_jump<NC>(grid, nodes, f, f.a + s * t, n);
    const Eigen::Matrix<double, NF, NF> ww = 0.5 * h * w * w.transpose();  // Gauss weight h / 2
    for (int a = 0; a < NF; ++a)
      for (int b = 0; b < NF; ++b) {
        for (int d = 0; d < 2; ++d) K(PN * a + d, PN * b + d) += gamma_u * ww(a, b);
        if constexpr (PN == 3) K(PN * a + 2, PN * b + 2) += gamma_p * ww(a, b);
      }
  }
  return K;
}

}  // namespace loom
