// Quadratic triangle (seed 000 §4.1, Fig 5): corners 0 1 2, mid-nodes 3 (edge 01), 4 (edge 12), 5 (edge 20).
// With barycentric coordinates l0 = 1 - xi - eta, l1 = xi, l2 = eta:
//   N0 = l0 (2 l0 - 1), N1 = l1 (2 l1 - 1), N2 = l2 (2 l2 - 1), N3 = 4 l0 l1, N4 = 4 l1 l2, N5 = 4 l2 l0.
// The isoparametric map uses the same functions, so cells may be curved in B_n after deformation.
#pragma once

#include <Eigen/Core>

#include "engine/core/types.hpp"

namespace loom {

using Tri6Values = Eigen::Matrix<double, 6, 1>;
using Tri6Gradients = Eigen::Matrix<double, 6, 2>;  // row A: dN^A/d(xi, eta) or dN^A/dx

// Barycentric point (l0, l1, l2) with l0 + l1 + l2 = 1.
inline Tri6Values tri6_values(double l0, double l1, double l2) {
  Tri6Values N;
  N << l0 * (2 * l0 - 1), l1 * (2 * l1 - 1), l2 * (2 * l2 - 1), 4 * l0 * l1, 4 * l1 * l2, 4 * l2 * l0;
  return N;
}

inline Tri6Gradients tri6_reference_gradients(double l0, double l1, double l2) {
  Tri6Gradients d;
  d << -(4 * l0 - 1), -(4 * l0 - 1),
       4 * l1 - 1, 0.0,
       0.0, 4 * l2 - 1,
       4 * (l0 - l1), -4 * l1,
       4 * l2, 4 * l1,
       -4 * l2, 4 * (l0 - l2);
  return d;
}

// Spatial gradients at a point from the six node positions (rows of x); returns det of the Jacobian of
// the map from the reference triangle (<= 0: the cell is inverted there).
inline double tri6_gradients(const Eigen::Matrix<double, 6, 2>& x, double l0, double l1, double l2, Tri6Gradients& dN) {
  const Tri6Gradients dref = tri6_reference_gradients(l0, l1, l2);
  const Eigen::Matrix2d J = x.transpose() * dref;  // J_ij = d x_i / d xi_j
  const double det = J.determinant();
  dN = dref * J.inverse();
  return det;
}

// Six-point rule of degree 4 on the triangle (Dunavant): barycentric points and weights summing to 1
// (multiply by the area). Exact for the P2 x P2 mass matrix.
struct TrianglePoint {
  double l[3];
  double w;
};
inline constexpr double kD4a1 = 0.816847572980459, kD4b1 = 0.091576213509771, kD4w1 = 0.109951743655322;
inline constexpr double kD4a2 = 0.108103018168070, kD4b2 = 0.445948490915965, kD4w2 = 0.223381589678011;
inline constexpr TrianglePoint kTriangleRule6[6] = {
    {{kD4a1, kD4b1, kD4b1}, kD4w1}, {{kD4b1, kD4a1, kD4b1}, kD4w1}, {{kD4b1, kD4b1, kD4a1}, kD4w1},
    {{kD4a2, kD4b2, kD4b2}, kD4w2}, {{kD4b2, kD4a2, kD4b2}, kD4w2}, {{kD4b2, kD4b2, kD4a2}, kD4w2}};

}  // namespace loom
