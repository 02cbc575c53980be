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

#include <limits>
#include <optional>

#include "systems/assemble/materials/drucker_prager.hpp"
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

// The functions are defined in hencky_perzyna.cpp: their spectral decomposition (Eigen's 3x3 eigensolver) is the
// costliest code to compile of all the headers the engine's and tests' units include through material.hpp, and a
// call per integration point costs nothing beside the decomposition it makes.
struct HenckyPerzyna {
  double K = 0.0, G = 0.0;
  double tau0 = std::numeric_limits<double>::infinity();  // shear yield stress; infinite: Hencky elastic
  double viscosity = 0.0;                                  // Bingham plastic viscosity mu
  std::optional<DruckerPrager> friction = std::nullopt;    // set: Drucker-Prager's yield surface instead of von Mises'

  // The stored energy per unit reference volume of an elastic state b^e (eq 19): G sum_A (dev eps_A)^2 + K/2 (ln J)^2,
  // eps_A = 1/2 ln of b^e's eigenvalues (G sum eps_A^2 + 1/2 (K - 2G/3) (ln J)^2 written with the deviator).
  double energy(const Mat3& be) const;

  // The Kirchhoff stress of an elastic state b^e (eq 19's derivative): tau = sum_A (2G dev eps_A + K theta) n_A (x) n_A.
  Mat3 kirchhoff(const Mat3& be) const;

  // The return map from the incremental deformation f = F F_n^-1 and the converged b^e_n over dt. false if
  // det f <= 0 (the state does not exist).
  bool update(const Mat3& f, const Mat3& be_n, double dt, bool deviatoric, bool tangent, HistoryResponse& out) const;

  // The hyperelastic interface (elements without history): elastic Hencky from F, b^e = F F^T. Plasticity is
  // not seen here; the scene checks refuse tau0 on such elements.
  bool stress(const Mat3& F, Mat3& P) const;
  bool stress_tangent(const Mat3& F, Mat3& P, Mat9& A) const;

 private:
  bool elastic(const Mat3& F, bool tangent, HistoryResponse& r) const { return elastic_update(F, Mat3::Identity(), tangent, r); }
  bool elastic_update(const Mat3& f, const Mat3& be_n, bool tangent, HistoryResponse& r) const;
  static Mat9 spatial_tangent(const Mat3& n, const Vec3& w, const Vec3& t, const Mat3& a);
};

}  // namespace loom
