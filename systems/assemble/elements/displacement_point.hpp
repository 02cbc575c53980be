// Updated-Lagrangian displacement kernel at one quadrature point (seed 000 §2, eqs 2-3, 6, 14), for an
// element with NEN nodes in D dimensions (D = 2: plane strain, F33 = 1; D = 3: the whole 3x3 F):
//   dF = I + sum_A (u^A - u_n^A) (x) dN^A/dX_n,   F = dF F_n                     (eq 2-3)
//   G^A = F_n^T dN^A/dX_n = dN^A/dX (reference gradient, eq 10)
//   f_int^A_i += P_ij G^A_j dV_0                                                 (eq 6)
//   K^AB_ik  += G^A_j (dP_ij/dF_kl) G^B_l dV_0                                    (eq 14-15)
// with dV_0 = dV_n / J_n (eq 9) and i, j, k, l < D. Local dofs are node-major: D A + i.
// D defaults to 2 and is never deduced (the arrays may be Maps): 3D callers write <NEN, 3>.
#pragma once

#include <Eigen/Core>
#include <type_traits>

#include "engine/core/types.hpp"
#include "systems/assemble/materials/tensor9.hpp"

namespace loom {

template <int NEN, int D = 2>
using NodalVectors = Eigen::Matrix<double, NEN, D>;  // one D-vector per node (rows)
template <int NEN, int D = 2>
using ElementVector = Eigen::Matrix<double, D * NEN, 1>;
template <int NEN, int D = 2>
using ElementMatrix = Eigen::Matrix<double, D * NEN, D * NEN>;

// Deformation gradient at the point: F = (I + du^T dN) F_n (in 2D with the plane-strain embedding).
template <int NEN, int D = 2>
Mat3 deformation_gradient(const std::type_identity_t<NodalVectors<NEN, D>>& du, const std::type_identity_t<NodalVectors<NEN, D>>& dN,
                          const Mat3& F_n) {
  Mat3 dF = Mat3::Identity();
  dF.template topLeftCorner<D, D>() += du.transpose() * dN;
  return dF * F_n;
}

// The point's internal force with trial gradients dN_trial that may differ from the test gradients dN: F is built from dN_trial
// (seed 004's receding contact replaces the displacements of a cell's wall nodes by a linear map of the
// others, u* = T u, so that dF depends on u through dN_trial = T^T dN), the virtual work from dN; the
// tangent G^A A G*^B is then unsymmetric.
template <int NEN, int D = 2, class MaterialT>
bool add_displacement_point(const MaterialT& material, const std::type_identity_t<NodalVectors<NEN, D>>& du,
                            const std::type_identity_t<NodalVectors<NEN, D>>& dN,
                            const std::type_identity_t<NodalVectors<NEN, D>>& dN_trial, double dV_n, const Mat3& F_n, Mat3& F,
                            ElementVector<NEN, D>& r, ElementMatrix<NEN, D>* K) {
  F = deformation_gradient<NEN, D>(du, dN_trial, F_n);
  const double dV0 = dV_n / F_n.determinant();
  const NodalVectors<NEN, D> G = dN * F_n.template topLeftCorner<D, D>();
  Mat3 P;
  if (!K) {
    if (!material.stress(F, P)) return false;
  } else {
    Mat9 A;
    if (!material.stress_tangent(F, P, A)) return false;
    const NodalVectors<NEN, D> G_trial = dN_trial * F_n.template topLeftCorner<D, D>();
    for (int i = 0; i < D; ++i)
      for (int k = 0; k < D; ++k) {
        Eigen::Matrix<double, D, D> C;  // C_jl = A_ijkl for fixed i, k
        for (int j = 0; j < D; ++j)
          for (int l = 0; l < D; ++l) C(j, l) = A(ij(i, j), ij(k, l));
        const NodalVectors<NEN, D> GC = G * C;
        const Eigen::Matrix<double, NEN, NEN> block = dV0 * GC * G_trial.transpose();
        for (int a = 0; a < NEN; ++a)
          for (int b = 0; b < NEN; ++b) (*K)(D * a + i, D * b + k) += block(a, b);
      }
  }
  const NodalVectors<NEN, D> f = dV0 * G * P.template topLeftCorner<D, D>().transpose();  // f(A, i) = P_ij G^A_j
  for (int a = 0; a < NEN; ++a) r.template segment<D>(D * a) += f.row(a).transpose();
  return true;
}

// Adds the point's internal force (and tangent if K != nullptr) to r and K; returns false if the
// material state does not exist (J <= 0). F receives the deformation gradient. Test and trial gradients equal.
template <int NEN, int D = 2, class MaterialT>
bool add_displacement_point(const MaterialT& material, const std::type_identity_t<NodalVectors<NEN, D>>& du,
                            const std::type_identity_t<NodalVectors<NEN, D>>& dN, double dV_n, const Mat3& F_n, Mat3& F, ElementVector<NEN, D>& r, ElementMatrix<NEN, D>* K) {
  return add_displacement_point<NEN, D>(material, du, dN, dN, dV_n, F_n, F, r, K);
}

}  // namespace loom
