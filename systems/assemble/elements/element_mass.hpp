// Mass matrices of the displacement fields (seed 000 eq 5), per unit density, on the reference volume.
//  tri3 (p1, p1p1_uphi): consistent M^AB = A_0 (1 + d_AB) / 12, lumped m^A = A_0 / 3.
//  tri6: consistent M^AB = int N^A N^B with the degree-4 six-point rule (exact on straight cells);
//        lumped by HRZ (diagonal of the consistent matrix scaled to the total mass): the row sum would give
//        zero corner masses.
//  quad9: consistent M^AB = sum_q N^A N^B dV_0q at the 3 x 3 Gauss points (exact on parallelograms);
//        lumped by the row sum m^A = int N^A dV_0, positive for quad9 (on a rectangle the tensor product of
//        Simpson's 1/6, 2/3, 1/6: corners 1/36, mid-sides 1/9, centre 4/9 of the area).
//  tet4: consistent M^AB = V_0 (1 + d_AB) / 20, lumped m^A = V_0 / 4.
//  tet10: as tri6 (degree-5 fourteen-point rule, exact on straight cells; HRZ lumping: the row sum gives
//        corners -1/20 of the volume).
#pragma once

#include <Eigen/Core>

#include "engine/mesh/quad9_shape.hpp"
#include "systems/assemble/elements/tet10.hpp"
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
template <int N>
Eigen::Matrix<double, N, 1> hrz_lumped_mass(const Eigen::Matrix<double, N, N>& M, double total) {
  return M.diagonal() * (total / M.trace());
}

inline Eigen::Matrix<double, 6, 1> tri6_lumped_mass(double area0) { return hrz_lumped_mass<6>(tri6_consistent_mass(area0), area0); }

inline Eigen::Matrix4d tet4_consistent_mass(double volume0) {
  Eigen::Matrix4d M = Eigen::Matrix4d::Constant(volume0 / 20.0);
  M.diagonal().setConstant(volume0 / 10.0);
  return M;
}

inline Eigen::Matrix<double, 10, 10> tet10_consistent_mass(double volume0) {
  Eigen::Matrix<double, 10, 10> M = Eigen::Matrix<double, 10, 10>::Zero();
  for (const auto& p : kTetrahedronRule14) {
    const Tet10Values N = tet10_values(p.l);
    M += p.w * volume0 * N * N.transpose();
  }
  return M;
}

inline Tet10Values tet10_lumped_mass(double volume0) { return hrz_lumped_mass<10>(tet10_consistent_mass(volume0), volume0); }

// dV0[q]: the reference volume of Gauss point q (quad9_gauss order).
inline Eigen::Matrix<double, 9, 9> quad9_consistent_mass(const double* dV0) {
  Eigen::Matrix<double, 9, 9> M = Eigen::Matrix<double, 9, 9>::Zero();
  for (int q = 0; q < 9; ++q) {
    const Quad9Values N = quad9_shape(quad9_gauss().xi[std::size_t(q)]);
    M += dV0[q] * N * N.transpose();
  }
  return M;
}

inline Quad9Values quad9_lumped_mass(const double* dV0) {
  Quad9Values m = Quad9Values::Zero();
  for (int q = 0; q < 9; ++q) m += dV0[q] * quad9_shape(quad9_gauss().xi[std::size_t(q)]);
  return m;
}

}  // namespace loom
