// From a Kirchhoff stress and its spatial tangent to the first Piola stress and its tangent with respect to
// the deformation gradient F (or the incremental f of an updated-Lagrangian step, relative to B_n):
//   P = s tau F^-T,   A_iJkL = dP_iJ / dF_kL = s F^-1_Jj F^-1_Ll (c^tau_ijkl + d_ik tau_jl)
// where the Kirchhoff stress changes as d tau = c^tau : l + l tau + tau l^T, l = dF F^-1 (c^tau minor
// symmetric): dP = (d tau - tau l^T) F^-T = (c^tau : l + l tau) F^-T. s scales both (1 / J_n for the
// relative stress of seed 001's domains, whose volume is det f V_n and whose stress is tau / J).
// The pressure part of a mixed u-p stress, P = p det F F^-T, is the case tau = J p I,
// c^tau = J p (I (x) I - 2 I_sym) (seed 001 text after eq 63).
#pragma once

#include "systems/assemble/materials/tensor9.hpp"

namespace loom {

inline void first_piola(const Mat3& F, const Mat3& tau, const Mat9& c_tau, double scale, Mat3& P, Mat9& A) {
  const Mat3 Finv = F.inverse();
  P = scale * tau * Finv.transpose();
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      Mat3 M;  // M_jl = c_ijkl + d_ik tau_jl for fixed i, k
      for (int j = 0; j < 3; ++j)
        for (int l = 0; l < 3; ++l) M(j, l) = c_tau(ij(i, j), ij(k, l)) + (i == k ? tau(j, l) : 0.0);
      const Mat3 B = scale * Finv * M * Finv.transpose();  // B_JL = F^-1_Jj M_jl F^-1_Ll
      for (int J = 0; J < 3; ++J)
        for (int L = 0; L < 3; ++L) A(ij(i, J), ij(k, L)) = B(J, L);
    }
}

// The Kirchhoff stress J p I of a pressure p and its spatial tangent J p (I (x) I - 2 I_sym).
inline void pressure_kirchhoff(double J, double p, Mat3& tau, Mat9& c_tau) {
  tau = J * p * Mat3::Identity();
  c_tau.setZero();
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      c_tau(ij(i, i), ij(k, k)) += J * p;
      c_tau(ij(i, k), ij(i, k)) -= J * p;
      c_tau(ij(i, k), ij(k, i)) -= J * p;
    }
}

}  // namespace loom
