// Linear tetrahedron: shape functions N = (1 - xi - eta - zeta, xi, eta, zeta) on the reference tetrahedron
// (the barycentric coordinates); gradients are constant over the cell. Corners 0 1 2 3 ordered so that
// (x1 - x0) . ((x2 - x0) x (x3 - x0)) > 0 (VTK_TETRA's orientation).
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

#include "engine/core/types.hpp"

namespace loom {

using Tet4Gradients = Eigen::Matrix<double, 4, 3>;  // row A: dN^A/dx
using Tet4Corners = Eigen::Matrix<double, 4, 3>;    // row A: corner A

// Gradients and signed volume of the tetrahedron; volume <= 0 means degenerate or inverted. With
// J = [x1 - x0, x2 - x0, x3 - x0] (columns), dN = dN_ref J^-1 and V = det J / 6.
inline double tet4_gradients(const Tet4Corners& x, Tet4Gradients& dN) {
  Mat3 J;
  for (int j = 0; j < 3; ++j) J.col(j) = (x.row(j + 1) - x.row(0)).transpose();
  const double det = J.determinant();
  const Mat3 Jinv = J.inverse();
  dN.row(0) = -Jinv.colwise().sum();
  dN.bottomRows<3>() = Jinv;
  return det / 6.0;
}

// Four-point rule exact for quadratics: barycentric points (a, b, b, b) and permutations with
// a = (5 + 3 sqrt 5) / 20, b = (5 - sqrt 5) / 20, weights 1/4 of the volume. Point q sits nearest corner q.
inline constexpr double kTet4RuleA = 0.58541019662496845446, kTet4RuleB = 0.13819660112501051518;
inline constexpr double kTet4Rule4[4][4] = {{kTet4RuleA, kTet4RuleB, kTet4RuleB, kTet4RuleB},
                                            {kTet4RuleB, kTet4RuleA, kTet4RuleB, kTet4RuleB},
                                            {kTet4RuleB, kTet4RuleB, kTet4RuleA, kTet4RuleB},
                                            {kTet4RuleB, kTet4RuleB, kTet4RuleB, kTet4RuleA}};

}  // namespace loom
