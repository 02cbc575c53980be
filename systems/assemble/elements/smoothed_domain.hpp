// The kernel of one integration domain of seed 001 (eqs 36-63): an edge's smoothing domain (stencil of 3 or
// 4 nodes, smoothed gradients b~) or, for the element-integrated variants, a triangle (b~ = grad N); in 3D a
// face's domain (4 or 5 nodes) or a tetrahedron. Local dofs node-major: [u_x, u_y, (u_z,) p] per node (mixed)
// or [u_x, u_y (, u_z)]. The reading is the same in 2D and 3D; in 2D the out-of-plane row of f is that of I.
//
// Kinematics (eq 49, the recommended reading of the spec: the domain's gradients are pushed forward from
// B_n, which makes the tangent exact): f = I + sum_I du_I (x) b~_I, b^_I = f^-T b~_I, V = det f V_n, and the
// Cauchy stress of the domain is sigma = tau' / J + p I (mixed; p = N_p . p, the pressure at the edge's
// midpoint) or tau / J (displacement only), J = det f J_n, J_n = sqrt(det b^e_n). With these,
//   f_int_I = sigma b^_I V = P b~_I V_n,  P = det f sigma f^-T = tau' f^-T / J_n + p det f f^-T   (eq 38)
//   R_p,a  = N_p,a (ln J / J) V_0,  V_0 = V_n / J_n = V / J        (eq 41: int N ln J / J dOmega_0)
//   K_uu   = b~ (dP/df) b~ V_n  (first_piola.hpp; = K_mat + K_geo of eqs 62-63)
//   K_up   = V_n det f b^_I N_p = B~^T m N_p V                      (eq 60)
//   K_pu   = N_p,a (1 - ln J) / J b^_I V_0                         (eq 61, dJ/du_I = J b^_I)
// The element terms of R_p (-K_pp,K p - K_stab p, eqs 42 and 48) are simplex_pressure_terms below.
//
// With material linear_elastic all geometric terms are dropped (seed 001 §4.1, Cook's membrane):
// eps = eps_n + sym(f - I), P = 2 mu dev eps + p I (mixed) or lambda tr eps I + 2 mu eps, R_p = N_p tr(eps) V_n;
// the domain's history b^e holds I + 2 eps.
#pragma once

#include <cmath>
#include <type_traits>

#include "systems/assemble/elements/displacement_point.hpp"
#include "systems/assemble/elements/smoothed_hyperelastic.hpp"
#include "systems/assemble/elements/smoothed_layout.hpp"
#include "systems/assemble/materials/first_piola.hpp"
#include "systems/assemble/materials/hencky_perzyna.hpp"
#include "systems/assemble/materials/linear_elastic.hpp"

namespace loom {

// Adds the domain's residual (and tangent if K) to r, K; false if the state does not exist (det f <= 0)
// or the material cannot be used on smoothed domains (the scene checks refuse that before a run).
template <int NEN, bool Mixed, class MaterialT, int D>
bool smoothed_domain(const MaterialT& material, const SmoothedDomain<NEN, D>& d, typename SmoothedLayout<NEN, Mixed, D>::Vector& r,
                     typename SmoothedLayout<NEN, Mixed, D>::Matrix* K, SmoothedDomainState& out) {
  using L = SmoothedLayout<NEN, Mixed, D>;
  Mat3 f = Mat3::Identity();
  f.topLeftCorner<D, D>() += d.du.transpose() * d.b;
  const double det_f = f.determinant();
  if (!(det_f > 0.0)) return false;
  const double p = Mixed ? d.Np.dot(d.p) : 0.0;
  if constexpr (std::is_same_v<MaterialT, HenckyPerzyna>) {
    HistoryResponse h;
    if (!material.update(f, d.be_n, d.dt, Mixed, K != nullptr, h)) return false;
    const double J_n = std::sqrt(d.be_n.determinant());
    Mat3 P;
    Mat9 A;
    if (K) first_piola(f, h.tau, h.c_tau, 1.0 / J_n, P, A);
    else P = h.tau * f.inverse().transpose() / J_n;
    out.be = h.be, out.sigma = h.tau / h.J, out.j = det_f;
    if constexpr (Mixed) {
      Mat3 tau_p, P_p;
      Mat9 c_p, A_p;
      if (K) {
        pressure_kirchhoff(det_f, p, tau_p, c_p);
        first_piola(f, tau_p, c_p, 1.0, P_p, A_p);
        P += P_p, A += A_p;
      } else {
        P += p * det_f * f.inverse().transpose();
      }
      out.sigma += p * Mat3::Identity();
      const double lnJ = std::log(h.J), V0 = d.V_n / J_n;
      const NodalVectors<NEN, D> bhat = d.b * f.inverse().template topLeftCorner<D, D>();  // row I: (f^-T b~_I)^T
      for (int a = 0; a < NEN; ++a) r[L::p(a)] += d.Np[a] * lnJ / h.J * V0;
      if (K)
        for (int a = 0; a < NEN; ++a)
          for (int c = 0; c < NEN; ++c)
            for (int i = 0; i < D; ++i) {
              (*K)(L::u(a, i), L::p(c)) += d.V_n * det_f * bhat(a, i) * d.Np[c];
              (*K)(L::p(a), L::u(c, i)) += d.Np[a] * (1.0 - lnJ) / h.J * bhat(c, i) * V0;
            }
    }
    detail::add_first_piola<NEN, Mixed, D>(d, P, K ? &A : nullptr, r, K);
    return true;
  } else if constexpr (std::is_same_v<MaterialT, LinearElastic>) {
    // The history holds I + 2 eps_n (the small-strain counterpart of b^e), so that the total strain is
    // eps_n + sym(f - I) over any number of steps; F_total = I + 2 eps_n / 2 + (f - I) feeds Hooke.
    const Mat3 F_total = f + 0.5 * (d.be_n - Mat3::Identity());
    Mat3 P;
    Mat9 A;
    if constexpr (Mixed) {
      // Deviatoric Hooke plus the pressure unknown; the constraint is tr(eps) - p / K = 0.
      const LinearElastic shear_only{-2.0 * material.mu / 3.0, material.mu};
      shear_only.stress_tangent(F_total, P, A);
      P += p * Mat3::Identity();
      for (int a = 0; a < NEN; ++a) {
        r[L::p(a)] += d.Np[a] * (F_total.topLeftCorner<D, D>().trace() - double(D)) * d.V_n;
        if (K)
          for (int c = 0; c < NEN; ++c)
            for (int i = 0; i < D; ++i) {
              (*K)(L::u(a, i), L::p(c)) += d.V_n * d.b(a, i) * d.Np[c];
              (*K)(L::p(a), L::u(c, i)) += d.Np[a] * d.b(c, i) * d.V_n;
            }
      }
    } else {
      material.stress_tangent(F_total, P, A);
    }
    out.be = Mat3::Identity() + (F_total + F_total.transpose() - 2.0 * Mat3::Identity()), out.sigma = P, out.j = det_f;
    detail::add_first_piola<NEN, Mixed, D>(d, P, K ? &A : nullptr, r, K);
    return true;
  } else if constexpr (std::is_same_v<MaterialT, NeoHooke> || std::is_same_v<MaterialT, NeoHookeSplit>) {
    return hyperelastic_domain<NEN, Mixed>(material, d, f, r, K, out);
  } else {
    return false;
  }
}

// The simplex's share of the pressure equation (eqs 42, 47-48): R_p,a -= (K_pp,K + K_stab)_ab p_b with
//   triangle:    K_pp,K,ab = A_0 (1 + d_ab) / (12 K),   K_stab,ab = (alpha_stab / G) (A_0 (1 + d_ab) / 12 - A_0 / 9)
//   tetrahedron: K_pp,K,ab = V_0 (1 + d_ab) / (20 K),   K_stab,ab = (alpha_stab / G) (V_0 (1 + d_ab) / 20 - V_0 / 16)
// (the mass matrix int N_a N_b of the linear pressure and its PPP against the element mean, Dohrmann-Bochev:
// int (N_a - 1/(D+1)) (N_b - 1/(D+1)) = M_ab - V_0 / (D+1)^2), V_0 the reference measure of the simplex (A_e / J_e
// of the spec). Rows of K_stab sum to zero.
template <int D>
void simplex_pressure_terms(double V0, double inverse_bulk, double alpha_over_G, const Eigen::Matrix<double, D + 1, 1>& p,
                            Eigen::Matrix<double, D + 1, 1>& r, Eigen::Matrix<double, D + 1, D + 1>* K) {
  using Matrix = Eigen::Matrix<double, D + 1, D + 1>;
  constexpr double mass_denominator = D == 2 ? 12.0 : 20.0, mean_denominator = D == 2 ? 9.0 : 16.0;
  Matrix M;
  for (int a = 0; a < D + 1; ++a)
    for (int b = 0; b < D + 1; ++b) M(a, b) = V0 * (a == b ? 2.0 : 1.0) / mass_denominator;
  const Matrix Kp = -(inverse_bulk * M + alpha_over_G * (M - Matrix::Constant(V0 / mean_denominator)));
  r += Kp * p;
  if (K) *K += Kp;
}
inline void triangle_pressure_terms(double A0, double inverse_bulk, double alpha_over_G, const Vec3& p, Vec3& r, Mat3* K) {
  simplex_pressure_terms<2>(A0, inverse_bulk, alpha_over_G, p, r, K);
}

}  // namespace loom
