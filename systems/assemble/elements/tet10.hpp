// Quadratic tetrahedron (tri6's counterpart), in VTK_QUADRATIC_TETRA's order: corners 0 1 2 3, then the
// mid-nodes of edges 01, 12, 20, 03, 13, 23 (nodes 4 .. 9). With barycentric coordinates l0 .. l3:
//   corner A: N = l_A (2 l_A - 1),   mid-node of edge (a, b): N = 4 l_a l_b.
// Isoparametric: the map uses the same functions, so cells may be curved in B_n after deformation.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

#include "engine/core/types.hpp"

namespace loom {

using Tet10Values = Eigen::Matrix<double, 10, 1>;
using Tet10Gradients = Eigen::Matrix<double, 10, 3>;  // row A: dN^A/d(xi, eta, zeta) or dN^A/dx
using Tet10Nodes = Eigen::Matrix<double, 10, 3>;      // row A: node A

inline constexpr int kTet10Edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};

// l: barycentric point with l0 + l1 + l2 + l3 = 1.
inline Tet10Values tet10_values(const double l[4]) {
  Tet10Values N;
  for (int a = 0; a < 4; ++a) N[a] = l[a] * (2 * l[a] - 1);
  for (int e = 0; e < 6; ++e) N[4 + e] = 4 * l[kTet10Edges[e][0]] * l[kTet10Edges[e][1]];
  return N;
}

// d/d(xi, eta, zeta) with l0 = 1 - xi - eta - zeta, l1 = xi, l2 = eta, l3 = zeta.
inline Tet10Gradients tet10_reference_gradients(const double l[4]) {
  Eigen::Matrix<double, 4, 3> dl;  // row a: d l_a / d xi
  dl << -1, -1, -1, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  Tet10Gradients d;
  for (int a = 0; a < 4; ++a) d.row(a) = (4 * l[a] - 1) * dl.row(a);
  for (int e = 0; e < 6; ++e) {
    const int a = kTet10Edges[e][0], b = kTet10Edges[e][1];
    d.row(4 + e) = 4 * (l[b] * dl.row(a) + l[a] * dl.row(b));
  }
  return d;
}

// Spatial gradients at a point from the ten node positions; returns det of the Jacobian of the map from the
// reference tetrahedron (the volume element is det / 6 of a unit weight; <= 0: the cell is inverted there).
inline double tet10_gradients(const Tet10Nodes& x, const double l[4], Tet10Gradients& dN) {
  const Tet10Gradients dref = tet10_reference_gradients(l);
  const Mat3 J = x.transpose() * dref;  // J_ij = d x_i / d xi_j
  const double det = J.determinant();
  dN = dref * J.inverse();
  return det;
}

// Fourteen-point rule of degree 5 with positive weights (two (a, a, a, 1 - 3a) orbits and one
// (b, b, 1/2 - b, 1/2 - b) orbit; the six moment equations of the symmetric polynomials of degree <= 5 solved
// to round-off): barycentric points and weights summing to 1 (multiply by the volume). Exact for the tet10
// mass matrix on straight cells (degree 4).
struct TetrahedronPoint {
  double l[4];
  double w;
};
inline constexpr double kT5a1 = 0.09273525031089191, kT5w1 = 0.07349304311636307;
inline constexpr double kT5a2 = 0.3108859192633009, kT5w2 = 0.11268792571801792;
inline constexpr double kT5b = 0.04550370412564707, kT5w3 = 0.04254602077707932;
inline constexpr double kT5c1 = 1 - 3 * kT5a1, kT5c2 = 1 - 3 * kT5a2, kT5d = 0.5 - kT5b;
inline constexpr TetrahedronPoint kTetrahedronRule14[14] = {
    {{kT5c1, kT5a1, kT5a1, kT5a1}, kT5w1}, {{kT5a1, kT5c1, kT5a1, kT5a1}, kT5w1},
    {{kT5a1, kT5a1, kT5c1, kT5a1}, kT5w1}, {{kT5a1, kT5a1, kT5a1, kT5c1}, kT5w1},
    {{kT5c2, kT5a2, kT5a2, kT5a2}, kT5w2}, {{kT5a2, kT5c2, kT5a2, kT5a2}, kT5w2},
    {{kT5a2, kT5a2, kT5c2, kT5a2}, kT5w2}, {{kT5a2, kT5a2, kT5a2, kT5c2}, kT5w2},
    {{kT5b, kT5b, kT5d, kT5d}, kT5w3},     {{kT5b, kT5d, kT5b, kT5d}, kT5w3},
    {{kT5b, kT5d, kT5d, kT5b}, kT5w3},     {{kT5d, kT5b, kT5b, kT5d}, kT5w3},
    {{kT5d, kT5b, kT5d, kT5b}, kT5w3},     {{kT5d, kT5d, kT5b, kT5b}, kT5w3}};

}  // namespace loom
