// Mixed u-p kernel of one material point on a background cell with NC corners in D dimensions (seed 003
// eqs 8-26; tri3 linear, NC = 3, or quad4 bilinear, NC = 4, in 2D; tet4 linear, NC = 4, in 3D), written in the
// "positive" form of the pressure equation, (p/kappa - (J - 1), q) (the seed's form times -1, so that the
// stabilisation adds positive terms). Local dofs node-major [u_x, u_y, (u_z,) p]: (D + 1) a + i, (D + 1) a + D.
// D defaults to 2 and is never deduced: 3D callers write <4, 3>.
//
// Kinematics (updated Lagrangian on the grid, which starts the step undeformed at the configuration x_n):
//   dF = I + sum_a du_a (x) dN_a,  F = dF F_n,  G_a = F_n^T dN_a (gradient in the reference), dN = grad N at x_n.
// Galerkin terms (eqs 10, 16-17), weights V_0 (reference volume) so that they derive from
// Pi = int psi_dev(F) + p (J - 1) - p^2 / (2 kappa) dV_0 and the coupling blocks are each other's negative
// transpose (B = B* in eq 18):
//   r_u(a,i) += V_0 [P_dev + p_h J F^-T]_ij G_a,j          r_p(a) += V_0 N_a (p_h / kappa - (J - 1))
// VMS stabilisation (eqs 19-26), ASGS (P~ = I) or OSGS (P~ = I - P_h, the projections given as data,
// seed 003 §5: lagged, not linearised). For linear cells the second derivatives vanish and the adjoint is
// L*(w, q) = (grad q, div w + q / kappa); the residuals are
//   R_u = rho (b - a_h) + grad p_h,   R_p = (J - 1) - p_h / kappa,
// (quad4: the bilinear functions' second derivatives d2N/dxdy are left out of L*, as usual for
// stabilised Q1 elements: they vanish on the cell's mean and the residual stays that of the linear terms),
// and the terms sum_K (tau P~[R], L*(V))_K are evaluated on the grid's configuration x_n (weights
// V_n, gradients dN): the seed's extra terms with grad p^ (B^G, K^GG, ...) come from differentiating the
// current-configuration gradients and are of the order of the step's displacement; leaving them out keeps
// the Newton tangent exact for this residual.
//   r_u(a,i) += V_n tau2 P~[R_p] dN_a,i      r_p(a) += V_n (tau1 P~[R_u] . dN_a + tau2 P~[R_p] N_a / kappa)
// with tau1 = c1 h^2 / (2 mu), tau2 = 2 c2 mu (eq 21). The grid acceleration a_h = sum N_a a_a follows
// Newmark, d a_a / d du_a = c_a = 1 / (beta dt^2) (0 for static runs).
#pragma once

#include <Eigen/Core>

#include "engine/core/types.hpp"
#include "systems/assemble/materials/neo_hooke_split.hpp"

namespace loom {

template <int NC, int D = 2>
using UpVector = Eigen::Matrix<double, (D + 1) * NC, 1>;
template <int NC, int D = 2>
using UpMatrix = Eigen::Matrix<double, (D + 1) * NC, (D + 1) * NC>;
template <int NC>
using CornerScalars = Eigen::Matrix<double, NC, 1>;
template <int NC, int D = 2>
using CornerVectors = Eigen::Matrix<double, NC, D>;  // rows: corners

// The cell's nodal values (rows: corners) at the Newton iterate.
template <int NC, int D = 2>
struct UpCellValues {
  CornerVectors<NC, D> du = CornerVectors<NC, D>::Zero();      // step displacement
  CornerScalars<NC> p = CornerScalars<NC>::Zero();             // pressure
  CornerVectors<NC, D> a = CornerVectors<NC, D>::Zero();       // Newmark acceleration
  CornerVectors<NC, D> proj_u = CornerVectors<NC, D>::Zero();  // OSGS projections
  CornerScalars<NC> proj_p = CornerScalars<NC>::Zero();
};

template <int NC, int D = 2>
struct UpPoint {
  CornerScalars<NC> N;      // shape functions at x_n
  CornerVectors<NC, D> dN;  // their gradients at x_n
  double V0 = 0;   // reference volume
  Mat3 F_n;        // deformation gradient at the start of the step
  double rho_n = 0;  // density at x_n: m / V_n
  Vec<D> b = Vec<D>::Zero();  // body force per unit mass
};

struct UpStabilisation {
  bool vms = false;        // ASGS or OSGS
  bool projected = false;  // OSGS: subtract the projections
  double tau1 = 0, tau2 = 0;
  double c_a = 0;          // d a_h / d du per unit N (1 / (beta dt^2)), 0 for static runs
};

// Adds the point's contribution; F receives the deformation gradient. False if J <= 0.
template <int NC, int D = 2>
bool add_up_point(const NeoHookeSplit& material, const UpStabilisation& stab, const UpPoint<NC, D>& pt, const UpCellValues<NC, D>& cell,
                  Mat3& F, UpVector<NC, D>& r, UpMatrix<NC, D>* K) {
  constexpr int PN = D + 1;  // dofs per node
  Mat3 dF = Mat3::Identity();
  dF.topLeftCorner<D, D>() += cell.du.transpose() * pt.dN;
  F = dF * pt.F_n;
  const double J = F.determinant();
  if (!(J > 0.0)) return false;
  const Mat3 Finv = F.inverse();
  const Mat3 JFinvT = J * Finv.transpose();
  const CornerVectors<NC, D> G = pt.dN * pt.F_n.template topLeftCorner<D, D>();
  const double p_h = pt.N.dot(cell.p);
  const double ik = material.inv_kappa;

  // 1. Galerkin.
  Mat3 P;
  Mat9 A;
  if (K ? !material.deviatoric_stress_tangent(F, P, A) : !material.deviatoric_stress(F, P)) return false;
  P += p_h * JFinvT;
  const CornerVectors<NC, D> f = pt.V0 * G * P.template topLeftCorner<D, D>().transpose();  // f(a, i) = P_ij G_a,j
  const CornerVectors<NC, D> dJ = G * JFinvT.template topLeftCorner<D, D>().transpose();    // dJ(b, k) = J F^-T_kl G_b,l = dJ/d du_b,k
  for (int a = 0; a < NC; ++a) {
    for (int i = 0; i < D; ++i) r[PN * a + i] += f(a, i);
    r[PN * a + D] += pt.V0 * pt.N[a] * (p_h * ik - (J - 1.0));
  }
  if (K) {
    Mat9 B;
    NeoHookeSplit::volume_tangent(F, B);
    A += p_h * B;
    for (int i = 0; i < D; ++i)
      for (int k = 0; k < D; ++k) {
        Eigen::Matrix<double, D, D> C;  // C_jl = A_ijkl
        for (int j = 0; j < D; ++j)
          for (int l = 0; l < D; ++l) C(j, l) = A(ij(i, j), ij(k, l));
        const Eigen::Matrix<double, NC, NC> block = pt.V0 * G * C * G.transpose();
        for (int a = 0; a < NC; ++a)
          for (int b = 0; b < NC; ++b) (*K)(PN * a + i, PN * b + k) += block(a, b);
      }
    for (int a = 0; a < NC; ++a)
      for (int b = 0; b < NC; ++b) {
        for (int i = 0; i < D; ++i) {
          (*K)(PN * a + i, PN * b + D) += pt.V0 * dJ(a, i) * pt.N[b];  // d f(a,i) / d p_b = V_0 (J F^-T G_a)_i N_b
          (*K)(PN * a + D, PN * b + i) -= pt.V0 * pt.N[a] * dJ(b, i);
        }
        (*K)(PN * a + D, PN * b + D) += pt.V0 * pt.N[a] * pt.N[b] * ik;
      }
  }
  if (!stab.vms) return true;

  // 2. Variational subgrid scales on the grid configuration.
  const double Vn = pt.V0 * pt.F_n.determinant();
  const Vec<D> grad_p = pt.dN.transpose() * cell.p;
  Vec<D> Ru = pt.rho_n * (pt.b - cell.a.transpose() * pt.N) + grad_p;
  double Rp = (J - 1.0) - p_h * ik;
  if (stab.projected) Ru -= cell.proj_u.transpose() * pt.N, Rp -= pt.N.dot(cell.proj_p);
  const double t1 = stab.tau1 * Vn, t2 = stab.tau2 * Vn;
  for (int a = 0; a < NC; ++a) {
    for (int i = 0; i < D; ++i) r[PN * a + i] += t2 * Rp * pt.dN(a, i);
    r[PN * a + D] += t1 * Ru.dot(pt.dN.row(a)) + t2 * Rp * pt.N[a] * ik;
  }
  if (!K) return true;
  // OSGS: P_h nearly reproduces the continuous linear field p_h / kappa of R_p (up to the lumping), so its
  // part of P~[R_p] = R_p - P_h[R_p] nearly vanishes, and so does its derivative. Keeping it in the tangent
  // (the ASGS tangent) overshoots the smooth pressure modes by 1 / (1 - tau2 / kappa): Newton diverged on
  // the static Cook's membrane at nu = 0.33 (tau2 / kappa = 0.77). The acceleration term of R_u is kept:
  // dropping it too (P_h[rho a_h] ~ rho a_h) made the dynamic Cook's membrane take 35 iterations, not 26.
  const double keep = stab.projected ? 0.0 : 1.0;
  for (int a = 0; a < NC; ++a)
    for (int b = 0; b < NC; ++b) {
      for (int i = 0; i < D; ++i) {
        for (int k = 0; k < D; ++k) (*K)(PN * a + i, PN * b + k) += t2 * pt.dN(a, i) * dJ(b, k);
        (*K)(PN * a + i, PN * b + D) -= keep * t2 * pt.dN(a, i) * pt.N[b] * ik;
        (*K)(PN * a + D, PN * b + i) += -t1 * pt.rho_n * stab.c_a * pt.N[b] * pt.dN(a, i) + t2 * ik * pt.N[a] * dJ(b, i);
      }
      (*K)(PN * a + D, PN * b + D) += t1 * pt.dN.row(a).dot(pt.dN.row(b)) - keep * t2 * ik * ik * pt.N[a] * pt.N[b];
    }
  return true;
}

// Polynomial pressure projection (Dohrmann-Bochev; seed 003 ref [47]) of one cell, with its points as the
// quadrature: (1/mu) int (p - Pi_0 p)(q - Pi_0 q) = (1/mu) (M - m m^T / V) with M_ab = sum V_n N_a N_b,
// m_a = sum V_n N_a, V = sum V_n. Added to the pressure rows (positive form).
template <int NC, int D = 2>
struct PppAccumulator {
  Eigen::Matrix<double, NC, NC> M = Eigen::Matrix<double, NC, NC>::Zero();
  CornerScalars<NC> m = CornerScalars<NC>::Zero();
  double V = 0.0;
  void add(const CornerScalars<NC>& N, double Vn) { M += Vn * N * N.transpose(), m += Vn * N, V += Vn; }
  void apply(double inv_mu, const CornerScalars<NC>& p, UpVector<NC, D>& r, UpMatrix<NC, D>* K) const {
    if (!(V > 0.0)) return;
    const Eigen::Matrix<double, NC, NC> S = inv_mu * (M - m * m.transpose() / V);
    const CornerScalars<NC> Sp = S * p;
    for (int a = 0; a < NC; ++a) {
      r[(D + 1) * a + D] += Sp[a];
      if (K)
        for (int b = 0; b < NC; ++b) (*K)((D + 1) * a + D, (D + 1) * b + D) += S(a, b);
    }
  }
};

}  // namespace loom
