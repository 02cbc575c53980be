// Hyperelastic materials (neo_hooke, neo_hooke_split) on seed 001's smoothing domains (es_up, es_u, fem_up, fem_u).
//
// The domain carries the left Cauchy-Green tensor of the total deformation, b_n = F_n F_n^T, as its history (the
// slot that holds b^e for Hencky-Perzyna: for an elastic material b^e = b, and the es_pfem remesh transfers it the same
// way). An isotropic material's Kirchhoff stress is a function of b alone, so any F_n with F_n F_n^T = b_n gives the
// same stress: take the symmetric root. With F = f F_n (f the step's gradient relative to B_n):
//   tau = P(F) F^T,   P_f = tau f^-T / J_n = P(F) F_n^T / J_n              (the domain's force: V_n P_f b~)
//   A_f,iJkL = dP_f,iJ / df_kL = sum_MN A_iMkN F_n,JM F_n,LN / J_n           (A = dP/dF of the material)
// Displacement only (es_u, fem_u): that is all. Mixed (es_up, fem_up): sigma = dev sigma(F) + p I, with the pressure's
// constraint the material's own volumetric law,
//   neo_hooke_split (U = kappa / 2 (J - 1)^2):  R_p,a = N_p,a (J - 1) V_0,   K_pu = N_p,a J b^_c V_0   (p = kappa (J - 1))
//   neo_hooke:  R_p,a = N_p,a pi / K V_0, pi = tr tau / (3 J) its mean Cauchy stress (a function of J and tr b), K its bulk
//               modulus lambda + 2 mu / 3, so that p = pi: the displacement solution, and the Hencky branch's reading
//               (ln J / J = pi / K for Hencky)
// against the simplices' -K_pp p (inverse_bulk = 1 / K; 1 / kappa). neo_hooke_split's deviatoric part is its own
// (deviatoric_stress_tangent: it exists at kappa = infinity too); neo_hooke's is tau - tr tau / 3 I:
//   P_dev = P_f - tr tau / (3 J_n) f^-T,  d(tr tau)/dF_kN = sum_iM A_iMkN F_iM + P_kN (tr tau = P : F),
//   dP_dev = A_f - [f^-T_iJ g_kL - tr tau f^-1_Jk f^-1_Li] / (3 J_n),   g_kL = sum_N d(tr tau)/dF_kN F_n,LN.
// Tangents are checked against central differences in tests/unit/smoothed_domain_test.cpp.
#pragma once

#include <type_traits>

#include <Eigen/Eigenvalues>

#include "systems/assemble/elements/smoothed_layout.hpp"
#include "systems/assemble/materials/first_piola.hpp"
#include "systems/assemble/materials/neo_hooke.hpp"
#include "systems/assemble/materials/neo_hooke_split.hpp"

namespace loom {

namespace detail {

// The symmetric square root of a left Cauchy-Green tensor (exactly I for b = I, the undeformed start).
inline Mat3 symmetric_root(const Mat3& b) {
  if (b == Mat3::Identity()) return Mat3::Identity();
  return Eigen::SelfAdjointEigenSolver<Mat3>(b).operatorSqrt();
}

// A_f from the material's A = dP/dF: for each (i, k), the block F_n A_(i.)(k.) F_n^T / J_n.
inline Mat9 tangent_relative_to_step(const Mat9& A, const Mat3& F_n, double J_n) {
  Mat9 out;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      Mat3 block;
      for (int M = 0; M < 3; ++M)
        for (int N = 0; N < 3; ++N) block(M, N) = A(ij(i, M), ij(k, N));
      const Mat3 pulled = F_n * block * F_n.transpose() / J_n;
      for (int J = 0; J < 3; ++J)
        for (int L = 0; L < 3; ++L) out(ij(i, J), ij(k, L)) = pulled(J, L);
    }
  return out;
}

}  // namespace detail

// The hyperelastic branch of smoothed_domain (see above); f = I + sum du (x) b~ with det f > 0.
template <int NEN, bool Mixed, class MaterialT, int D>
bool hyperelastic_domain(const MaterialT& material, const SmoothedDomain<NEN, D>& d, const Mat3& f,
                         typename SmoothedLayout<NEN, Mixed, D>::Vector& r, typename SmoothedLayout<NEN, Mixed, D>::Matrix* K,
                         SmoothedDomainState& out) {
  using L = SmoothedLayout<NEN, Mixed, D>;
  constexpr bool split = std::is_same_v<MaterialT, NeoHookeSplit>;
  const Mat3 F_n = detail::symmetric_root(d.be_n);
  const double J_n = F_n.determinant(), det_f = f.determinant(), J = det_f * J_n;
  const Mat3 F = f * F_n;
  // The material's P(F) (mixed neo_hooke_split: its deviatoric part) and, with K, A = dP/dF.
  Mat3 P_F;
  Mat9 A_F;
  bool ok = true;
  if constexpr (Mixed && split) ok = K ? material.deviatoric_stress_tangent(F, P_F, A_F) : material.deviatoric_stress(F, P_F);
  else ok = K ? material.stress_tangent(F, P_F, A_F) : material.stress(F, P_F);
  if (!ok) return false;
  const Mat3 tau = P_F * F.transpose();
  Mat3 P = P_F * F_n.transpose() / J_n;
  Mat9 A;
  if (K) A = detail::tangent_relative_to_step(A_F, F_n, J_n);
  out.be = F * F.transpose(), out.j = det_f, out.sigma = tau / J;
  if constexpr (!Mixed) {
    detail::add_first_piola<NEN, Mixed, D>(d, P, K ? &A : nullptr, r, K);
    return true;
  } else {
    const Mat3 finv = f.inverse(), finvT = finv.transpose();
    const double tr_tau = tau.trace();
    // d(tr tau)/df, needed by neo_hooke's deviatoric projection and its pressure constraint.
    Mat3 g = Mat3::Zero();
    if (!split && K) {
      Mat3 dtr_dF = P_F;
      for (int k = 0; k < 3; ++k)
        for (int N = 0; N < 3; ++N)
          for (int i = 0; i < 3; ++i)
            for (int M = 0; M < 3; ++M) dtr_dF(k, N) += A_F(ij(i, M), ij(k, N)) * F(i, M);
      g = dtr_dF * F_n.transpose();
    }
    if constexpr (!split) {  // tau' = tau - tr tau / 3 I (neo_hooke_split's deviatoric stress is deviatoric already)
      P -= tr_tau / (3.0 * J_n) * finvT;
      if (K)
        for (int i = 0; i < 3; ++i)
          for (int Jj = 0; Jj < 3; ++Jj)
            for (int k = 0; k < 3; ++k)
              for (int Ll = 0; Ll < 3; ++Ll) A(ij(i, Jj), ij(k, Ll)) -= (finvT(i, Jj) * g(k, Ll) - tr_tau * finv(Jj, k) * finv(Ll, i)) / (3.0 * J_n);
      out.sigma = (tau - tr_tau / 3.0 * Mat3::Identity()) / J;
    }
    const double p = d.Np.dot(d.p);
    if (K) {
      Mat3 tau_p, P_p;
      Mat9 c_p, A_p;
      pressure_kirchhoff(det_f, p, tau_p, c_p);
      first_piola(f, tau_p, c_p, 1.0, P_p, A_p);
      P += P_p, A += A_p;
    } else {
      P += p * det_f * finvT;
    }
    out.sigma += p * Mat3::Identity();
    // The constraint c(f) and dc/df: split J - 1; neo_hooke pi / K = tr tau / (3 J K).
    const double V0 = d.V_n / J_n;
    double c;
    Mat3 dc_df;
    if constexpr (split) {
      c = J - 1.0, dc_df = J * finvT;
    } else {
      const double bulk = material.lambda + 2.0 * material.mu / 3.0;
      c = tr_tau / (3.0 * J * bulk), dc_df = (g / (3.0 * J) - tr_tau / (3.0 * J) * finvT) / bulk;
    }
    const NodalVectors<NEN, D> bhat = d.b * finv.template topLeftCorner<D, D>();  // row I: (f^-T b~_I)^T
    const NodalVectors<NEN, D> dc_du = d.b * dc_df.template topLeftCorner<D, D>().transpose();  // row I: dc/du_I
    for (int a = 0; a < NEN; ++a) r[L::p(a)] += d.Np[a] * c * V0;
    if (K)
      for (int a = 0; a < NEN; ++a)
        for (int cc = 0; cc < NEN; ++cc)
          for (int i = 0; i < D; ++i) {
            (*K)(L::u(a, i), L::p(cc)) += d.V_n * det_f * bhat(a, i) * d.Np[cc];
            (*K)(L::p(a), L::u(cc, i)) += d.Np[a] * dc_du(cc, i) * V0;
          }
    detail::add_first_piola<NEN, Mixed, D>(d, P, K ? &A : nullptr, r, K);
    return true;
  }
}

}  // namespace loom
