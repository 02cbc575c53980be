// Mixed P1P1 u-phi triangle with polynomial pressure projection (seed 000 §4.2, eqs 25-44).
// Unknowns per node: u_x, u_y and the volume dilatation phi; local dofs node-major [u_x, u_y, phi].
// History: the modified deformation gradient F~_n (eq 28), so that at each of the three points
//   F = dF F~_n,  J = det F,  phi_q = N^A phi^A,  c = (phi_q / J)^(1/3),  F~ = c F,  P~ = P(F~).
// Residuals (eqs 38-39), with G^A = F~_n^T dN^A/dX_n and dV_0 = dV_n / det F~_n (the push-back of eq 9-10
// with the history the element carries):
//   f_u^A   = sum_q P~ G^A dV_0
//   f_phi^A = -sum_q N^A J dV_0 + K_phiphi^AB phi^B,
//   K_phiphi^AB = M^AB + (alpha_s / G)(M^AB - (1/3) m^B),  M^AB = int N^A N^B,  m^B = int N^B  (eqs 39, 43;
//   the condensed projection onto constants, N-check^A = 1/3).
// Tangent blocks (eqs 40-44), with A = dP~/dF~ and a = A : F (contraction over the last pair):
//   dF~_ij/dF_kl = c (d_ik d_jl - 1/3 F_ij F^-1_lk)  =>  (A : dF~/dF)_ijkl = c (A_ijkl - 1/3 a_ij F^-1_lk)
//   dF~/dphi_q = F~ / (3 phi_q)                       =>  A : dF~/dphi = c a / (3 phi_q)
//   K_uu^AB_ik   = sum_q G^A_j (A : dF~/dF)_ijkl G^B_l dV_0                      (eq 40)
//   K_uphi^AB_i  = sum_q G^A_j (A : dF~/dphi)_ij N^B dV_0                        (eq 41)
//   K_phiu^AB_k  = -sum_q N^A J F^-1_lk G^B_l dV_0    (dJ/dF = J F^-T)            (eq 42)
//   K_phiphi^AB  as above                                                        (eq 43)
// F33 of F~_n is not 1 in plane strain (F~ scales all three directions): the 3x3 kinematics carry it.
#pragma once

#include <cmath>

#include "engine/core/types.hpp"
#include "systems/assemble/elements/displacement_point.hpp"
#include "systems/assemble/elements/tri3.hpp"
#include "systems/assemble/materials/tensor9.hpp"

namespace loom {

using UPhiVector = Eigen::Matrix<double, 9, 1>;
using UPhiMatrix = Eigen::Matrix<double, 9, 9>;

struct UPhiCell {
  NodalVectors<3> du;          // u - u_n at the corners
  Eigen::Vector3d phi;         // nodal phi (iterate)
  NodalVectors<3> dN;          // dN/dX_n, constant over the cell
  double dV_n[3] = {0, 0, 0};  // point weights in B_n
  Mat3 F_n[3];                 // history F~_n at the points
};

// Adds the cell's residual (and tangent if K) to r, K; F~ of each point goes to Ft. False if J <= 0 or
// phi_q <= 0 at a point (the state does not exist).
template <class MaterialT>
bool uphi_internal(const MaterialT& material, double alpha_over_G, const UPhiCell& cell, Mat3 Ft[3], UPhiVector& r,
                   UPhiMatrix* K) {
  Mat3 dF = Mat3::Identity();
  dF.topLeftCorner<2, 2>() += cell.du.transpose() * cell.dN;
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (int q = 0; q < 3; ++q) {
    const double* N = kTri3Rule3[q];  // barycentric coordinates = linear shape functions at the point
    const Mat3 F = dF * cell.F_n[q];
    const double J = F.determinant();
    const double phi_q = N[0] * cell.phi[0] + N[1] * cell.phi[1] + N[2] * cell.phi[2];
    if (!(J > 0.0) || !(phi_q > 0.0)) return false;
    const double dV0 = cell.dV_n[q] / cell.F_n[q].determinant();
    const double c = std::cbrt(phi_q / J);
    Ft[q] = c * F;
    Mat3 P;
    Mat9 A;
    if (K ? !material.stress_tangent(Ft[q], P, A) : !material.stress(Ft[q], P)) return false;
    const NodalVectors<3> G = cell.dN * cell.F_n[q].topLeftCorner<2, 2>();
    const NodalVectors<3> f = dV0 * G * P.topLeftCorner<2, 2>().transpose();  // f(A, i) = P~_ij G^A_j
    for (int a = 0; a < 3; ++a) {
      r[3 * a] += f(a, 0);
      r[3 * a + 1] += f(a, 1);
      r[3 * a + 2] -= N[a] * J * dV0;
      for (int b = 0; b < 3; ++b) M(a, b) += N[a] * N[b] * dV0;
      m[a] += N[a] * dV0;
    }
    if (!K) continue;
    const Mat3 Finv = F.inverse();
    Eigen::Matrix<double, 9, 1> Fvec;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) Fvec[ij(i, j)] = F(i, j);
    const Eigen::Matrix<double, 9, 1> aF = A * Fvec;  // a_ij = A_ijmn F_mn
    for (int i = 0; i < 2; ++i) {
      for (int k = 0; k < 2; ++k) {
        Eigen::Matrix2d B;  // B_jl = (A : dF~/dF)_ijkl for fixed i, k
        for (int j = 0; j < 2; ++j)
          for (int l = 0; l < 2; ++l) B(j, l) = c * (A(ij(i, j), ij(k, l)) - aF[ij(i, j)] * Finv(l, k) / 3.0);
        const Eigen::Matrix3d block = dV0 * G * B * G.transpose();
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) (*K)(3 * a + i, 3 * b + k) += block(a, b);
      }
      const Eigen::Vector2d Q(c * aF[ij(i, 0)] / (3.0 * phi_q), c * aF[ij(i, 1)] / (3.0 * phi_q));
      const Eigen::Vector3d GQ = G * Q;  // GQ(A) = G^A_j Q_ij
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) (*K)(3 * a + i, 3 * b + 2) += dV0 * GQ[a] * N[b];
    }
    const NodalVectors<3> GFinv = G * Finv.topLeftCorner<2, 2>();  // (A, k): G^A_l F^-1_lk
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int k = 0; k < 2; ++k) (*K)(3 * a + 2, 3 * b + k) -= dV0 * N[a] * J * GFinv(b, k);
  }
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const double kab = M(a, b) + alpha_over_G * (M(a, b) - m[b] / 3.0);
      r[3 * a + 2] += kab * cell.phi[b];
      if (K) (*K)(3 * a + 2, 3 * b + 2) += kab;
    }
  return true;
}

}  // namespace loom
