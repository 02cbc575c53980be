// Small-strain Hooke: eps = sym(F - I), sigma = lambda tr(eps) I + 2 mu eps. Used through the same
// interface as the finite-strain models with P := sigma, so that the residual is linear in u and Newton
// converges in one iteration: A_ijkl = lambda d_ij d_kl + mu (d_ik d_jl + d_il d_jk).
#pragma once

#include "systems/assemble/materials/tensor9.hpp"

namespace loom {

struct LinearElastic {
  double lambda = 0.0, mu = 0.0;

  bool stress(const Mat3& F, Mat3& P) const {
    const Mat3 eps = 0.5 * (F + F.transpose()) - Mat3::Identity();
    P = lambda * eps.trace() * Mat3::Identity() + 2.0 * mu * eps;
    return true;
  }

  bool stress_tangent(const Mat3& F, Mat3& P, Mat9& A) const {
    stress(F, P);
    A.setZero();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        A(ij(i, i), ij(j, j)) += lambda;
        A(ij(i, j), ij(i, j)) += mu;
        A(ij(i, j), ij(j, i)) += mu;
      }
    return true;
  }
};

}  // namespace loom
