// Neo-Hooke with a deviatoric / volumetric split, seed 003 §2.2 (eq 7):
//   psi = psi_dev(C-bar) + U(J),  psi_dev = mu/2 (I1-bar - 3),  I1-bar = J^(-2/3) F:F,  U = kappa/2 (J - 1)^2
// with 3x3 kinematics (plane strain: F33 = 1 enters F:F). Stresses in the units of mu, first Piola P:
//   P_dev = mu J^(-2/3) (F - I1/3 F^-T)                                     (I1 = F:F)
//   P_vol = p J F^-T,  p = U'(J) = kappa (J - 1)                             (sigma = sigma_dev + p I)
// Tangents A_ijkl = dP_ij/dF_kl, using dJ/dF = J F^-T and d(F^-T)_ij/dF_kl = -F^-1_jk F^-1_li:
//   A_dev = mu J^(-2/3) [ d_ik d_jl - 2/3 F_ij F^-T_kl - 2/3 F^-T_ij F_kl + 2/9 I1 F^-T_ij F^-T_kl
//                         + 1/3 I1 F^-1_jk F^-1_li ]
//   d(p J F^-T)/dF at fixed p = p J (F^-T_ij F^-T_kl - F^-1_jk F^-1_li)        (volume_tangent)
//   A_vol = kappa J^2 F^-T_ij F^-T_kl + kappa (J - 1) J (F^-T_ij F^-T_kl - F^-1_jk F^-1_li)
// The mixed u-p formulation of seed 003 (eqs 16-18) takes p as an unknown and uses only the deviatoric part
// and inv_kappa = 1/kappa; inv_kappa = 0 is the incompressible limit nu = 1/2, where the displacement-only
// form (stress, stress_tangent) does not exist.
#pragma once

#include <cmath>

#include "systems/assemble/materials/tensor9.hpp"

namespace loom {

struct NeoHookeSplit {
  double mu = 0.0;
  double inv_kappa = 0.0;  // 1 / kappa; 0: incompressible

  // Deviatoric first Piola stress; false where J <= 0.
  bool deviatoric_stress(const Mat3& F, Mat3& P) const {
    const double J = F.determinant();
    if (!(J > 0.0)) return false;
    P = mu * std::pow(J, -2.0 / 3.0) * (F - F.squaredNorm() / 3.0 * F.inverse().transpose());
    return true;
  }

  bool deviatoric_stress_tangent(const Mat3& F, Mat3& P, Mat9& A) const {
    const double J = F.determinant();
    if (!(J > 0.0)) return false;
    const Mat3 Finv = F.inverse();
    const Mat3 FinvT = Finv.transpose();
    const double I1 = F.squaredNorm();
    const double c = mu * std::pow(J, -2.0 / 3.0);
    P = c * (F - I1 / 3.0 * FinvT);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l)
            A(ij(i, j), ij(k, l)) = c * ((i == k && j == l ? 1.0 : 0.0) - 2.0 / 3.0 * F(i, j) * FinvT(k, l) -
                                         2.0 / 3.0 * FinvT(i, j) * F(k, l) + 2.0 / 9.0 * I1 * FinvT(i, j) * FinvT(k, l) +
                                         I1 / 3.0 * Finv(j, k) * Finv(l, i));
    return true;
  }

  // d(J F^-T)/dF: the tangent of the pressure term p J F^-T per unit pressure.
  static void volume_tangent(const Mat3& F, Mat9& B) {
    const double J = F.determinant();
    const Mat3 Finv = F.inverse();
    const Mat3 FinvT = Finv.transpose();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) B(ij(i, j), ij(k, l)) = J * (FinvT(i, j) * FinvT(k, l) - Finv(j, k) * Finv(l, i));
  }

  // Full stress of the displacement formulation (needs kappa < infinity).
  bool stress(const Mat3& F, Mat3& P) const {
    if (!deviatoric_stress(F, P)) return false;
    const double J = F.determinant();
    P += (J - 1.0) / inv_kappa * J * F.inverse().transpose();
    return true;
  }

  bool stress_tangent(const Mat3& F, Mat3& P, Mat9& A) const {
    if (!deviatoric_stress_tangent(F, P, A)) return false;
    const double J = F.determinant();
    const double kappa = 1.0 / inv_kappa;
    const Mat3 FinvT = F.inverse().transpose();
    P += kappa * (J - 1.0) * J * FinvT;
    Mat9 B;
    volume_tangent(F, B);
    A += kappa * (J - 1.0) * B;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) A(ij(i, j), ij(k, l)) += kappa * J * J * FinvT(i, j) * FinvT(k, l);
    return true;
  }

  // Strain energy per unit reference volume; the volumetric part vanishes in the incompressible limit.
  double energy(const Mat3& F) const {
    const double J = F.determinant();
    const double dev = 0.5 * mu * (std::pow(J, -2.0 / 3.0) * F.squaredNorm() - 3.0);
    return inv_kappa > 0.0 ? dev + 0.5 * (J - 1.0) * (J - 1.0) / inv_kappa : dev;
  }
};

}  // namespace loom
