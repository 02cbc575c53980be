// Compressible Neo-Hooke, seed 000 eq (48)-(51):
//   psi_0 = lambda/2 ln^2 J + mu/2 (F:F - 3) - mu ln J
//   P = mu F + (lambda ln J - mu) F^-T                                  (eq 51)
//   A_ijkl = dP_ij/dF_kl = mu d_ik d_jl + lambda F^-T_ij F^-T_kl - (lambda ln J - mu) F^-1_jk F^-1_li
// using d(ln J)/dF = F^-T and d(F^-T)_ij/dF_kl = -F^-1_jk F^-1_li. Units: stresses in the units of mu.
#pragma once

#include <cmath>

#include "systems/assemble/materials/tensor9.hpp"

namespace loom {

struct NeoHooke {
  double lambda = 0.0, mu = 0.0;

  // Returns false where J <= 0 (the stress does not exist).
  bool stress(const Mat3& F, Mat3& P) const {
    const double J = F.determinant();
    if (!(J > 0.0)) return false;
    const Mat3 Finv = F.inverse();
    P = mu * F + (lambda * std::log(J) - mu) * Finv.transpose();
    return true;
  }

  bool stress_tangent(const Mat3& F, Mat3& P, Mat9& A) const {
    const double J = F.determinant();
    if (!(J > 0.0)) return false;
    const Mat3 Finv = F.inverse();
    const Mat3 FinvT = Finv.transpose();
    const double c = lambda * std::log(J) - mu;
    P = mu * F + c * FinvT;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l)
            A(ij(i, j), ij(k, l)) = lambda * FinvT(i, j) * FinvT(k, l) - c * Finv(j, k) * Finv(l, i) +
                                    (i == k && j == l ? mu : 0.0);
    return true;
  }
};

}  // namespace loom
