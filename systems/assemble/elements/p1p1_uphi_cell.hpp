// Mixed P1P1 u-phi simplex (triangle, D = 2; tetrahedron, D = 3) with polynomial pressure projection
// (seed 000 §4.2, eqs 25-44). Unknowns per node: the D displacements and the volume dilatation phi; local dofs
// node-major [u_1 .. u_D, phi]. History: the modified deformation gradient F~_n (eq 28), so that at each of the
// D + 1 points of the simplex's degree-2 rule (tri: 3 points, tet: 4)
//   F = dF F~_n,  J = det F,  phi_q = N^A phi^A,  c = (phi_q / J)^(1/3),  F~ = c F,  P~ = P(F~).
// Residuals (eqs 38-39), with G^A = F~_n^T dN^A/dX_n and dV_0 = dV_n / det F~_n (the push-back of eq 9-10
// with the history the element carries):
//   f_u^A   = sum_q P~ G^A dV_0
//   f_phi^A = -sum_q N^A J dV_0 + K_phiphi^AB phi^B,
//   K_phiphi^AB = M^AB + (alpha_s / G)(M^AB - m^B / NEN),  M^AB = int N^A N^B,  m^B = int N^B  (eqs 39, 43;
//   the condensed projection onto constants, N-check^A = 1/NEN: 1/3 on the triangle, 1/4 on the tetrahedron).
// Tangent blocks (eqs 40-44), with A = dP~/dF~ and a = A : F (contraction over the last pair):
//   dF~_ij/dF_kl = c (d_ik d_jl - 1/3 F_ij F^-1_lk)  =>  (A : dF~/dF)_ijkl = c (A_ijkl - 1/3 a_ij F^-1_lk)
//   dF~/dphi_q = F~ / (3 phi_q)                       =>  A : dF~/dphi = c a / (3 phi_q)
//   K_uu^AB_ik   = sum_q G^A_j (A : dF~/dF)_ijkl G^B_l dV_0                      (eq 40)
//   K_uphi^AB_i  = sum_q G^A_j (A : dF~/dphi)_ij N^B dV_0                        (eq 41)
//   K_phiu^AB_k  = -sum_q N^A J F^-1_lk G^B_l dV_0    (dJ/dF = J F^-T)            (eq 42)
//   K_phiphi^AB  as above                                                        (eq 43)
// The 1/3 of dF~/dF and dF~/dphi is the volumetric exponent of (phi/J)^(1/3) in every dimension.
// F33 of F~_n is not 1 in plane strain (F~ scales all three directions): the 3x3 kinematics carry it.
#pragma once

#include <cmath>

#include "engine/core/types.hpp"
#include "systems/assemble/elements/displacement_point.hpp"
#include "systems/assemble/elements/tet4.hpp"
#include "systems/assemble/elements/tri3.hpp"
#include "systems/assemble/materials/tensor9.hpp"

namespace loom {

// Barycentric coordinates of point q of the simplex's degree-2 rule (equal weights 1 / (D + 1)).
template <int D>
inline const double* simplex_rule_point(int q) {
  if constexpr (D == 2) return kTri3Rule3[q];
  else return kTet4Rule4[q];
}

template <int D>
struct UPhiCellT {
  static constexpr int NEN = D + 1;
  NodalVectors<NEN, D> du;             // u - u_n at the corners
  Eigen::Matrix<double, NEN, 1> phi;   // nodal phi (iterate)
  NodalVectors<NEN, D> dN;             // dN/dX_n, constant over the cell
  double dV_n[NEN] = {};               // point weights in B_n
  Mat3 F_n[NEN];                       // history F~_n at the points
};
template <int D>
using UPhiVectorT = Eigen::Matrix<double, (D + 1) * (D + 1), 1>;
template <int D>
using UPhiMatrixT = Eigen::Matrix<double, (D + 1) * (D + 1), (D + 1) * (D + 1)>;

using UPhiCell = UPhiCellT<2>;
using UPhiVector = UPhiVectorT<2>;
using UPhiMatrix = UPhiMatrixT<2>;

// Adds the cell's residual (and tangent if K) to r, K; F~ of each point goes to Ft. False if J <= 0 or
// phi_q <= 0 at a point (the state does not exist).
template <int D, class MaterialT>
bool uphi_internal(const MaterialT& material, double alpha_over_G, const UPhiCellT<D>& cell, Mat3 Ft[D + 1], UPhiVectorT<D>& r,
                   UPhiMatrixT<D>* K) {
  constexpr int NEN = D + 1, S = D + 1;  // nodes; dofs per node
  Mat3 dF = Mat3::Identity();
  dF.topLeftCorner<D, D>() += cell.du.transpose() * cell.dN;
  Eigen::Matrix<double, NEN, NEN> M = Eigen::Matrix<double, NEN, NEN>::Zero();
  Eigen::Matrix<double, NEN, 1> m = Eigen::Matrix<double, NEN, 1>::Zero();
  for (int q = 0; q < NEN; ++q) {
    const double* N = simplex_rule_point<D>(q);  // barycentric coordinates = linear shape functions at the point
    const Mat3 F = dF * cell.F_n[q];
    const double J = F.determinant();
    double phi_q = N[0] * cell.phi[0];
    for (int a = 1; a < NEN; ++a) phi_q += N[a] * cell.phi[a];
    if (!(J > 0.0) || !(phi_q > 0.0)) return false;
    const double dV0 = cell.dV_n[q] / cell.F_n[q].determinant();
    const double c = std::cbrt(phi_q / J);
    Ft[q] = c * F;
    Mat3 P;
    Mat9 A;
    if (K ? !material.stress_tangent(Ft[q], P, A) : !material.stress(Ft[q], P)) return false;
    const NodalVectors<NEN, D> G = cell.dN * cell.F_n[q].template topLeftCorner<D, D>();
    const NodalVectors<NEN, D> f = dV0 * G * P.topLeftCorner<D, D>().transpose();  // f(A, i) = P~_ij G^A_j
    for (int a = 0; a < NEN; ++a) {
      for (int i = 0; i < D; ++i) r[S * a + i] += f(a, i);
      r[S * a + D] -= N[a] * J * dV0;
      for (int b = 0; b < NEN; ++b) M(a, b) += N[a] * N[b] * dV0;
      m[a] += N[a] * dV0;
    }
    if (!K) continue;
    const Mat3 Finv = F.inverse();
    Eigen::Matrix<double, 9, 1> Fvec;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) Fvec[ij(i, j)] = F(i, j);
    const Eigen::Matrix<double, 9, 1> aF = A * Fvec;  // a_ij = A_ijmn F_mn
    for (int i = 0; i < D; ++i) {
      for (int k = 0; k < D; ++k) {
        Eigen::Matrix<double, D, D> B;  // B_jl = (A : dF~/dF)_ijkl for fixed i, k
        for (int j = 0; j < D; ++j)
          for (int l = 0; l < D; ++l) B(j, l) = c * (A(ij(i, j), ij(k, l)) - aF[ij(i, j)] * Finv(l, k) / 3.0);
        const Eigen::Matrix<double, NEN, NEN> block = dV0 * G * B * G.transpose();
        for (int a = 0; a < NEN; ++a)
          for (int b = 0; b < NEN; ++b) (*K)(S * a + i, S * b + k) += block(a, b);
      }
      Eigen::Matrix<double, D, 1> Q;
      for (int j = 0; j < D; ++j) Q[j] = c * aF[ij(i, j)] / (3.0 * phi_q);
      const Eigen::Matrix<double, NEN, 1> GQ = G * Q;  // GQ(A) = G^A_j Q_ij
      for (int a = 0; a < NEN; ++a)
        for (int b = 0; b < NEN; ++b) (*K)(S * a + i, S * b + D) += dV0 * GQ[a] * N[b];
    }
    const NodalVectors<NEN, D> GFinv = G * Finv.topLeftCorner<D, D>();  // (A, k): G^A_l F^-1_lk
    for (int a = 0; a < NEN; ++a)
      for (int b = 0; b < NEN; ++b)
        for (int k = 0; k < D; ++k) (*K)(S * a + D, S * b + k) -= dV0 * N[a] * J * GFinv(b, k);
  }
  for (int a = 0; a < NEN; ++a)
    for (int b = 0; b < NEN; ++b) {
      const double kab = M(a, b) + alpha_over_G * (M(a, b) - m[b] / double(NEN));
      r[S * a + D] += kab * cell.phi[b];
      if (K) (*K)(S * a + D, S * b + D) += kab;
    }
  return true;
}

}  // namespace loom
