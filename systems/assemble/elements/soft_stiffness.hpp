// Seed 004's soft stiffness (Aulisa & Capodaglio eq 26): on an active cell at the body's edge, a small
// linear-elastic-like term in the step displacement u~ that keeps the nodes with little particle support
// in check,
//   r_A,i = mu C_E int_E (grad u~ + grad u~^T)_ij dN_A/dx_j dV,
//   K_AiBk = mu C_E int_E (delta_ik dN_A . dN_B + dN_A/dx_k dN_B/dx_i) dV        (constant, symmetric),
// on the undeformed (start-of-step) cell. A rigid translation has grad u~ = 0 and feels nothing; a rigid
// rotation does feel it (the symmetric gradient of an infinitesimal rotation is zero, of a finite one not).
// C_E follows the cell's flag M_E (nodes not shared with an empty cell): C1 for M_E < 5, C2 for 5 <= M_E < 9,
// 0 for M_E = 9 (the paper's tables 50-58).
#pragma once

#include "systems/assemble/elements/displacement_point.hpp"

namespace loom {

struct SoftStiffness {
  double c1 = 0.0, c2 = 0.0;
  double factor(int inside_nodes, int nodes) const { return inside_nodes >= nodes ? 0.0 : inside_nodes < 5 ? c1 : c2; }
};

// Adds weight * (the integrand above) at one quadrature point with gradients dN (rows: nodes).
template <int NEN>
void add_soft_stiffness_point(const NodalVectors<NEN>& dN, double weight, ElementMatrix<NEN>& K) {
  const Eigen::Matrix<double, NEN, NEN> dot = weight * dN * dN.transpose();
  for (int a = 0; a < NEN; ++a)
    for (int b = 0; b < NEN; ++b)
      for (int i = 0; i < 2; ++i) {
        K(2 * a + i, 2 * b + i) += dot(a, b);
        for (int k = 0; k < 2; ++k) K(2 * a + i, 2 * b + k) += weight * dN(a, k) * dN(b, i);
      }
}

}  // namespace loom
