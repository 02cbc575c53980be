// Updated-Lagrangian displacement kernel at one quadrature point (seed 000 §2, eqs 2-3, 6, 14), for an
// element with NEN nodes in 2D plane strain:
//   dF = I + sum_A (u^A - u_n^A) (x) dN^A/dX_n,   F = dF F_n                     (eq 2-3)
//   G^A = F_n^T dN^A/dX_n = dN^A/dX (reference gradient, eq 10)
//   f_int^A_i += P_ij G^A_j dV_0                                                 (eq 6)
//   K^AB_ik  += G^A_j (dP_ij/dF_kl) G^B_l dV_0                                    (eq 14-15)
// with dV_0 = dV_n / J_n (eq 9). Local dofs are node-major: 2A + i.
#pragma once

#include <Eigen/Core>

#include "engine/core/types.hpp"
#include "systems/assemble/materials/tensor9.hpp"

namespace loom {

template <int NEN>
using NodalVectors = Eigen::Matrix<double, NEN, 2>;  // one 2D vector per node (rows)
template <int NEN>
using ElementVector = Eigen::Matrix<double, 2 * NEN, 1>;
template <int NEN>
using ElementMatrix = Eigen::Matrix<double, 2 * NEN, 2 * NEN>;

// Deformation gradient at the point: F = (I + du^T dN) F_n with plane-strain embedding.
template <int NEN>
Mat3 deformation_gradient(const NodalVectors<NEN>& du, const NodalVectors<NEN>& dN, const Mat3& F_n) {
  Mat3 dF = Mat3::Identity();
  dF.template topLeftCorner<2, 2>() += du.transpose() * dN;
  return dF * F_n;
}

// The point's internal force with trial gradients dN_trial that may differ from the test gradients dN: F is built from dN_trial
// (seed 004's receding contact replaces the displacements of a cell's wall nodes by a linear map of the
// others, u* = T u, so that dF depends on u through dN_trial = T^T dN), the virtual work from dN; the
// tangent G^A A G*^B is then unsymmetric.
template <int NEN, class MaterialT>
bool add_displacement_point(const MaterialT& material, const NodalVectors<NEN>& du, const NodalVectors<NEN>& dN,
                            const NodalVectors<NEN>& dN_trial, double dV_n, const Mat3& F_n, Mat3& F, ElementVector<NEN>& r,
                            ElementMatrix<NEN>* K) {
  F = deformation_gradient<NEN>(du, dN_trial, F_n);
  const double dV0 = dV_n / F_n.determinant();
  const NodalVectors<NEN> G = dN * F_n.template topLeftCorner<2, 2>();
  Mat3 P;
  if (!K) {
    if (!material.stress(F, P)) return false;
  } else {
    Mat9 A;
    if (!material.stress_tangent(F, P, A)) return false;
    const NodalVectors<NEN> G_trial = dN_trial * F_n.template topLeftCorner<2, 2>();
    for (int i = 0; i < 2; ++i)
      for (int k = 0; k < 2; ++k) {
        Eigen::Matrix2d C;  // C_jl = A_ijkl for fixed i, k
        C << A(ij(i, 0), ij(k, 0)), A(ij(i, 0), ij(k, 1)), A(ij(i, 1), ij(k, 0)), A(ij(i, 1), ij(k, 1));
        const NodalVectors<NEN> GC = G * C;
        const Eigen::Matrix<double, NEN, NEN> block = dV0 * GC * G_trial.transpose();
        for (int a = 0; a < NEN; ++a)
          for (int b = 0; b < NEN; ++b) (*K)(2 * a + i, 2 * b + k) += block(a, b);
      }
  }
  const NodalVectors<NEN> f = dV0 * G * P.template topLeftCorner<2, 2>().transpose();  // f(A, i) = P_ij G^A_j
  for (int a = 0; a < NEN; ++a) r.template segment<2>(2 * a) += f.row(a).transpose();
  return true;
}

// Adds the point's internal force (and tangent if K != nullptr) to r and K; returns false if the
// material state does not exist (J <= 0). F receives the deformation gradient. Test and trial gradients equal.
template <int NEN, class MaterialT>
bool add_displacement_point(const MaterialT& material, const NodalVectors<NEN>& du, const NodalVectors<NEN>& dN,
                            double dV_n, const Mat3& F_n, Mat3& F, ElementVector<NEN>& r, ElementMatrix<NEN>* K) {
  return add_displacement_point<NEN>(material, du, dN, dN, dV_n, F_n, F, r, K);
}

}  // namespace loom
