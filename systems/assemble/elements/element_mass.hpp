// Mass matrices of the displacement fields (seed 000 eq 5), per unit density, on the reference volume.
//  tri3 (p1, p1p1_uphi): consistent M^AB = A_0 (1 + d_AB) / 12, lumped m^A = A_0 / 3.
//  tri6: consistent M^AB = int N^A N^B with the degree-4 six-point rule (exact on straight cells);
//        lumped by HRZ (diagonal of the consistent matrix scaled to the total mass): the row sum would give
//        zero corner masses.
#pragma once

#include <Eigen/Core>

#include "systems/assemble/elements/tri6.hpp"

namespace loom {

inline Eigen::Matrix3d tri3_consistent_mass(double area0) {
  Eigen::Matrix3d M = Eigen::Matrix3d::Constant(area0 / 12.0);
  M.diagonal().setConstant(area0 / 6.0);
  return M;
}

// Consistent mass of a straight-sided reference cell of area `area0` (shape functions only).
inline Eigen::Matrix<double, 6, 6> tri6_consistent_mass(double area0) {
  Eigen::Matrix<double, 6, 6> M = Eigen::Matrix<double, 6, 6>::Zero();
  for (const auto& p : kTriangleRule6) {
    const Tri6Values N = tri6_values(p.l[0], p.l[1], p.l[2]);
    M += p.w * area0 * N * N.transpose();
  }
  return M;
}

// HRZ lumping: m^A = M^AA * total / trace(M).
inline Eigen::Matrix<double, 6, 1> tri6_lumped_mass(double area0) {
  const Eigen::Matrix<double, 6, 6> M = tri6_consistent_mass(area0);
  return M.diagonal() * (area0 / M.trace());
}

}  // namespace loom
