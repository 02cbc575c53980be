// The biquadratic Lagrange quadrilateral (quad9) of seed 004 §2.2: the background grids and FEM meshes of
// Aulisa & Capodaglio. Local nodes (0-based, the paper's FEMuS order): corners 0-3 counter-clockwise from
// (-1, -1), mid-sides 4 (0-1), 5 (1-2), 6 (2-3), 7 (3-0), centre 8. On the reference square [-1, 1]^2,
//   N_a(xi, eta) = L_i(xi) L_j(eta),  L_0 = s (s - 1) / 2,  L_1 = 1 - s^2,  L_2 = s (s + 1) / 2,
// with (i, j) the node's position in the 3 x 3 lattice. The map x(xi) = sum_a N_a x_a is isoparametric;
// gradients dN/dx = dN/dxi J^-1 with J = dx/dxi. Quadrature: the 3 x 3 Gauss rule (exact to degree 5 per
// direction, FEMuS's "fifth" order).
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>

#include "engine/core/types.hpp"

namespace loom {

using Quad9Values = Eigen::Matrix<double, 9, 1>;
using Quad9Gradients = Eigen::Matrix<double, 9, 2>;  // one row per node
using Quad9Coordinates = Eigen::Matrix<double, 9, 2>;

// Lattice position (0, 1, 2 along xi, eta) of each local node.
inline constexpr std::array<int, 9> kQuad9I = {0, 2, 2, 0, 1, 2, 1, 0, 1};
inline constexpr std::array<int, 9> kQuad9J = {0, 0, 2, 2, 0, 1, 2, 1, 1};

inline Eigen::Vector3d quadratic_lagrange(double s) { return {0.5 * s * (s - 1.0), 1.0 - s * s, 0.5 * s * (s + 1.0)}; }
inline Eigen::Vector3d quadratic_lagrange_derivative(double s) { return {s - 0.5, -2.0 * s, s + 0.5}; }

inline Quad9Values quad9_shape(const Vec2& xi) {
  const Eigen::Vector3d Lx = quadratic_lagrange(xi.x()), Ly = quadratic_lagrange(xi.y());
  Quad9Values N;
  for (int a = 0; a < 9; ++a) N[a] = Lx[kQuad9I[std::size_t(a)]] * Ly[kQuad9J[std::size_t(a)]];
  return N;
}

// dN/dxi on the reference square.
inline Quad9Gradients quad9_reference_gradients(const Vec2& xi) {
  const Eigen::Vector3d Lx = quadratic_lagrange(xi.x()), Ly = quadratic_lagrange(xi.y());
  const Eigen::Vector3d dLx = quadratic_lagrange_derivative(xi.x()), dLy = quadratic_lagrange_derivative(xi.y());
  Quad9Gradients dN;
  for (int a = 0; a < 9; ++a) {
    const int i = kQuad9I[std::size_t(a)], j = kQuad9J[std::size_t(a)];
    dN(a, 0) = dLx[i] * Ly[j];
    dN(a, 1) = Lx[i] * dLy[j];
  }
  return dN;
}

// dN/dx at xi of the cell with nodes x; det J in `det` (the area scale of the map).
inline Quad9Gradients quad9_gradients(const Quad9Coordinates& x, const Vec2& xi, double* det = nullptr) {
  const Quad9Gradients dNr = quad9_reference_gradients(xi);
  const Eigen::Matrix2d J = x.transpose() * dNr;  // J_ij = dx_i / dxi_j
  if (det) *det = J.determinant();
  return dNr * J.inverse();
}

// Inverse isoparametric map: xi with x(xi) = x by Newton from the centre (exact in one step for a cell
// whose nodes sit on a regular lattice of a rectangle). Returns false if it does not converge.
// Converged when the Newton correction of xi (of order 1 on the cell) is at round-off, which is that of the
// coordinates relative to the cell's size: a small cell far from the origin (x = 20, h = 0.05) resolves xi
// only to about 1e-13.
inline bool quad9_inverse_map(const Quad9Coordinates& nodes, const Vec2& x, Vec2& xi) {
  xi.setZero();
  const double size = (nodes.row(2) - nodes.row(0)).norm();
  const double tol = 1e-13 * std::max(1.0, (x.cwiseAbs().maxCoeff() + size) / size);
  for (int it = 0; it < 20; ++it) {
    const Vec2 r = nodes.transpose() * quad9_shape(xi) - x;
    const Eigen::Matrix2d J = nodes.transpose() * quad9_reference_gradients(xi);
    const Vec2 step = J.inverse() * r;
    xi -= step;
    if (step.norm() <= tol) return true;
  }
  return false;
}

// 3 x 3 Gauss rule on [-1, 1]^2: point q = 3 j + i at (g_i, g_j), weight w_i w_j.
struct Quad9Gauss {
  std::array<Vec2, 9> xi;
  std::array<double, 9> weight;
};
inline const Quad9Gauss& quad9_gauss() {
  static const Quad9Gauss rule = [] {
    Quad9Gauss r;
    const double g[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) r.xi[std::size_t(3 * j + i)] = Vec2(g[i], g[j]), r.weight[std::size_t(3 * j + i)] = w[i] * w[j];
    return r;
  }();
  return rule;
}

}  // namespace loom
