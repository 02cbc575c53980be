// Hencky elasticity with Perzyna viscoplasticity of von Mises type (seed 001 §2, eqs 1-21; the Bingham-like
// material of ES-PFEM), a material with history: the elastic left Cauchy-Green tensor b^e.
//
// Energy (eq 19): psi = G sum_A (eps^e_A)^2 + 1/2 (K - 2G/3) (ln J)^2, eps^e_A = ln lambda^e_A, so the
// principal Kirchhoff stresses are tau_A = 2G dev eps^e_A + K ln J. Yield (eq 7): Phi = tau_eq - tau0 with
// tau_eq = sqrt(1/2 dev tau : dev tau): tau0 is the yield stress in simple shear. Flow (eqs 11-17):
// d^vp = gammadot dev tau / (2 tau_eq), gammadot = <tau_eq - tau0> / mu, so mu is the Bingham plastic
// viscosity (steady simple shear: tau = tau0 + mu gammadot).
//
// Return map (eqs 49-55, backward Euler; closed form because the overstress is linear):
//   b^e_tr = f b^e_n f^T = sum lambda_A^2 n_A (x) n_A,  eps_A = 1/2 ln lambda_A^2,  theta = sum eps_A = ln J
//   s_A = 2G (eps_A - theta/3),  q = sqrt(1/2 sum s_A^2),  f_tr = q - tau0
//   f_tr > 0: dgamma = f_tr / (G + mu/dt),  tau'_A = s_A (1 - G dgamma / q),  eps^e_A = eps_A - dgamma s_A / (2q)
//   b^e = sum exp(2 eps^e_A) n_A (x) n_A (eq 54; the typo of eq 51 corrected: exp(-dt d^vp)).
// Algorithmic modulus a_AB = d tau_A / d eps_B (H = G + mu/dt, n^_A = s_A / (sqrt2 q)):
//   a_AB = 2G (1 - G dgamma/q)(d_AB - 1/3) - 2G (G tau0 / (H q)) n^_A n^_B   (elastic: 2G (d_AB - 1/3)),
// from d q / d eps_B = G s_B / q (sum s = 0). The full stress adds K theta to tau_A and K to every a_AB.
// Spatial tangent (eq 21), trial stretches, c^tau = J c:
//   c^tau = sum_AB a_AB n_AABB - sum_A 2 tau_A n_AAAA + sum_{A != B} g_AB (n_ABAB + n_ABBA),
//   g_AB = (tau_A lambda_B^2 - tau_B lambda_A^2) / (lambda_A^2 - lambda_B^2), equal stretches: 1/2 (a_AA - a_AB) - tau_A.
// It depends on f only through l = df f^-1 (b^e_tr is pushed forward by f), which is what first_piola.hpp needs.
//
// With `friction` set the yield surface is Drucker-Prager's instead (drucker_prager.hpp: rate-independent,
// non-associated flow, tau0 and viscosity unused): the same elasticity, history, spectral form and tangent, with the
// stress's full principal values and modulus from that return. Its plastic flow changes volume, so det b^e = J^2
// does not hold for it; and it needs the full stress (`deviatoric` false): the pressure is in its yield function.
#pragma once

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <optional>

#include "systems/assemble/materials/drucker_prager.hpp"
#include "systems/assemble/materials/first_piola.hpp"
#include "systems/assemble/materials/tensor9.hpp"

namespace loom {

// What a history material returns for one integration domain.
struct HistoryResponse {
  Mat3 tau = Mat3::Zero();  // Kirchhoff stress (deviatoric part only when asked for)
  Mat3 be = Mat3::Identity();  // updated history b^e
  double J = 1.0;           // det F = sqrt(det b^e) (isochoric flow)
  Mat9 c_tau;               // spatial tangent J c (when asked for)
  bool plastic = false;     // the return map was active
  double tau_eq = 0.0;      // equivalent stress after the return map
};

struct HenckyPerzyna {
  double K = 0.0, G = 0.0;
  double tau0 = std::numeric_limits<double>::infinity();  // shear yield stress; infinite: Hencky elastic
  double viscosity = 0.0;                                  // Bingham plastic viscosity mu
  std::optional<DruckerPrager> friction = std::nullopt;    // set: Drucker-Prager's yield surface instead of von Mises'

  // The stored energy per unit reference volume of an elastic state b^e (eq 19): G sum_A (dev eps_A)^2 + K/2 (ln J)^2,
  // eps_A = 1/2 ln of b^e's eigenvalues (G sum eps_A^2 + 1/2 (K - 2G/3) (ln J)^2 written with the deviator).
  double energy(const Mat3& be) const {
    const Eigen::SelfAdjointEigenSolver<Mat3> eig(be, Eigen::EigenvaluesOnly);
    const Vec3 eps = 0.5 * eig.eigenvalues().array().log().matrix();
    const double theta = eps.sum();
    return G * (eps - Vec3::Constant(theta / 3.0)).squaredNorm() + 0.5 * K * theta * theta;
  }

  // The Kirchhoff stress of an elastic state b^e (eq 19's derivative): tau = sum_A (2G dev eps_A + K theta) n_A (x) n_A.
  Mat3 kirchhoff(const Mat3& be) const {
    HistoryResponse r;
    if (!elastic_update(Mat3::Identity(), be, false, r)) return Mat3::Constant(std::numeric_limits<double>::quiet_NaN());
    return r.tau;
  }

  // The return map from the incremental deformation f = F F_n^-1 and the converged b^e_n over dt. false if
  // det f <= 0 (the state does not exist).
  bool update(const Mat3& f, const Mat3& be_n, double dt, bool deviatoric, bool tangent, HistoryResponse& out) const {
    const Mat3 be_tr = f * be_n * f.transpose();
    const Eigen::SelfAdjointEigenSolver<Mat3> eig(be_tr);
    const Vec3 w = eig.eigenvalues();
    if (!(w.minCoeff() > 0.0) || !(f.determinant() > 0.0)) return false;
    const Mat3& n = eig.eigenvectors();
    Vec3 eps = 0.5 * w.array().log().matrix();
    const double theta = eps.sum();
    const Vec3 s = 2.0 * G * (eps - Vec3::Constant(theta / 3.0));
    const double q = std::sqrt(0.5 * s.squaredNorm());
    const Mat3 dev = Mat3::Identity() - Mat3::Constant(1.0 / 3.0);
    Vec3 t = s;
    Mat3 a = 2.0 * G * dev;
    if (friction) {
      if (deviatoric) return false;  // its yield function needs the pressure: the scene checks refuse mixed elements
      out.plastic = friction->return_map(K, G, eps, t, a, out.tau_eq);
    } else {
      out.plastic = q > tau0;
      out.tau_eq = q;
    }
    if (out.plastic && !friction) {
      const double H = G + viscosity / dt;
      const double dgamma = (q - tau0) / H;
      const double factor = 1.0 - G * dgamma / q;
      const Vec3 nh = s / (std::sqrt(2.0) * q);
      t = factor * s;
      a = 2.0 * G * factor * dev - 2.0 * G * (G * tau0 / (H * q)) * nh * nh.transpose();
      eps -= dgamma / (2.0 * q) * s;
      out.tau_eq = factor * q;
    }
    if (!deviatoric && !friction) t.array() += K * theta, a.array() += K;
    // Elastic: b^e is the trial state itself (rebuilding it from the spectral form would only add round-off,
    // and a body at rest would drift by it step after step).
    out.be = out.plastic ? Mat3(n * eps.array().exp().square().matrix().asDiagonal() * n.transpose()) : be_tr;
    out.tau = n * t.asDiagonal() * n.transpose();
    out.J = std::exp(theta);
    if (tangent) out.c_tau = spatial_tangent(n, w, t, a);
    return true;
  }

  // The hyperelastic interface (elements without history): elastic Hencky from F, b^e = F F^T. Plasticity is
  // not seen here; the scene checks refuse tau0 on such elements.
  bool stress(const Mat3& F, Mat3& P) const {
    HistoryResponse r;
    if (!elastic(F, false, r)) return false;
    P = r.tau * F.inverse().transpose();
    return true;
  }
  bool stress_tangent(const Mat3& F, Mat3& P, Mat9& A) const {
    HistoryResponse r;
    if (!elastic(F, true, r)) return false;
    first_piola(F, r.tau, r.c_tau, 1.0, P, A);
    return true;
  }

 private:
  bool elastic(const Mat3& F, bool tangent, HistoryResponse& r) const { return elastic_update(F, Mat3::Identity(), tangent, r); }
  bool elastic_update(const Mat3& f, const Mat3& be_n, bool tangent, HistoryResponse& r) const {
    HenckyPerzyna e = *this;
    e.tau0 = std::numeric_limits<double>::infinity();
    e.friction.reset();
    return e.update(f, be_n, 1.0, false, tangent, r);
  }

  static Mat9 spatial_tangent(const Mat3& n, const Vec3& w, const Vec3& t, const Mat3& a) {
    // m[A][B] = vec(n_A (x) n_B), row-major, so that n_ABCD = m[A][B] m[C][D]^T.
    Eigen::Matrix<double, 9, 1> m[3][3];
    for (int A = 0; A < 3; ++A)
      for (int B = 0; B < 3; ++B) {
        const Mat3 nn = n.col(A) * n.col(B).transpose();
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) m[A][B][ij(i, j)] = nn(i, j);
      }
    Mat9 c = Mat9::Zero();
    for (int A = 0; A < 3; ++A) {
      for (int B = 0; B < 3; ++B) c += a(A, B) * m[A][A] * m[B][B].transpose();
      c -= 2.0 * t[A] * m[A][A] * m[A][A].transpose();
      for (int B = 0; B < 3; ++B) {
        if (A == B) continue;
        // Below sqrt(eps) relative separation the quotient loses more digits than the limit's O(d) error.
        const double g = std::abs(w[A] - w[B]) > 1.5e-8 * w.maxCoeff() ? (t[A] * w[B] - t[B] * w[A]) / (w[A] - w[B])
                                                                        : 0.5 * (a(A, A) - a(A, B)) - t[A];
        c += g * (m[A][B] * m[A][B].transpose() + m[A][B] * m[B][A].transpose());
      }
    }
    return c;
  }
};

}  // namespace loom
