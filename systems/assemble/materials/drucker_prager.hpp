// Drucker-Prager plasticity with non-associated flow, rate-independent and perfectly plastic, in the principal
// Kirchhoff stresses and elastic logarithmic principal strains of Hencky elasticity (hencky_perzyna.hpp hosts it:
// the same b^e history, spectral form and spatial tangent). The small-strain algorithm of de Souza Neto, Peric &
// Owen, Computational Methods for Plasticity (2008) §8.3.3, holds unchanged in logarithmic strains because Hencky's
// law is linear in them and b^e's eigenvectors are those of the trial state (isotropy).
//
//   tau_A = s_A + p,  p = K theta^e,  s_A = 2G (eps^e_A - theta^e / 3),  q = sqrt(1/2 sum s_A^2)  (p > 0 in tension)
//   yield      Phi = q + eta p - xi c
//   potential  g   = q + eta_bar p       (eta_bar from the dilatancy angle; eta_bar = eta: associated flow)
//   flow       eps^e_A = eps^tr_A - dgamma (s_A / (2q) + eta_bar / 3)   (backward Euler)
//
// Return to the cone (closed form: the overstress is linear in dgamma, and the flow direction is the trial one):
//   dgamma = Phi_tr / H, H = G + K eta eta_bar;  s = (1 - G dgamma / q_tr) s_tr;  p = p_tr - K eta_bar dgamma,
// valid while G dgamma < q_tr; past it the state returns to the apex, s = 0, p = xi c / eta (a cohesionless material
// in tension carries nothing). Algorithmic modulus a_AB = d tau_A / d eps_B (n^_A = s_tr,A / (sqrt2 q_tr), 1 = (1,1,1)):
//   cone:  a = 2G (1 - G dgamma / q_tr) I_dev + 2G (G dgamma / q_tr - G / H) n^ n^T
//              - sqrt2 G K / H (eta n^ 1^T + eta_bar 1 n^T) + K (1 - K eta eta_bar / H) 1 1^T
//   apex:  a = 0 (the stress is fixed);  elastic: 2G I_dev + K 1 1^T.
// Derivation: d q_tr / d eps_B = sqrt2 G n^_B, d n^_A / d eps_B = sqrt2 G / q_tr (I_dev - n^ n^T)_AB,
// d dgamma / d eps_B = (sqrt2 G n^_B + eta K) / H; unsymmetric unless eta_bar = eta.
//
// Cones matched to Mohr-Coulomb (friction angle phi, dilatancy psi, cohesion c; de Souza Neto §6.4.2):
//   compression   eta = 6 sin phi / (sqrt3 (3 - sin phi)),        xi = 6 cos phi / (sqrt3 (3 - sin phi))  (outer cone)
//   extension     eta = 6 sin phi / (sqrt3 (3 + sin phi)),        xi = 6 cos phi / (sqrt3 (3 + sin phi))  (inner cone)
// with eta_bar the same function of psi as eta is of phi; and in plane strain, where the flow has no out-of-plane
// part (s_3 = -2 q eta_bar / 3), matched in the plane for any psi:
//   eta_bar = 3 sin psi / sqrt(9 + 3 sin^2 psi)   (in-plane dilatancy: -d eps_v / (d eps_1 - d eps_2) = sin psi)
//   k = sqrt(1 - eta_bar^2 / 3) + eta_bar sin phi / 3,  eta = sin phi / k,  xi = cos phi / k
// (the in-plane circle has radius q sqrt(1 - eta_bar^2 / 3) and centre p + q eta_bar / 3; Mohr-Coulomb's
// R = c cos phi - centre sin phi then reads q k = c cos phi - p sin phi). With psi = phi this is de Souza Neto's
// 3 tan phi / sqrt(9 + 12 tan^2 phi) and 3 / sqrt(...); with psi = 0 it is sin phi and cos phi (that formula would
// give the material an in-plane friction angle of asin(eta), 28.7 degrees for 30).
#pragma once

#include <cmath>

#include "engine/core/types.hpp"

namespace loom {

enum class DruckerPragerCone { plane_strain, compression, extension };

struct DruckerPrager {
  double eta = 0.0;      // friction: d(-q) / dp on the yield surface
  double eta_bar = 0.0;  // dilatancy: the potential's slope
  double xi_c = 0.0;     // xi c: q on the yield surface at p = 0

  // Angles in radians.
  static DruckerPrager from_mohr_coulomb(double friction, double dilatancy, double cohesion, DruckerPragerCone cone) {
    const double s = std::sin(friction), c = std::cos(friction), sd = std::sin(dilatancy);
    if (cone == DruckerPragerCone::plane_strain) {
      const double eta_bar = 3.0 * sd / std::sqrt(9.0 + 3.0 * sd * sd);
      const double k = std::sqrt(1.0 - eta_bar * eta_bar / 3.0) + eta_bar * s / 3.0;
      return {s / k, eta_bar, c / k * cohesion};
    }
    const double lode = cone == DruckerPragerCone::compression ? -1.0 : 1.0;  // 3 - sin or 3 + sin
    return {6.0 * s / (std::sqrt(3.0) * (3.0 + lode * s)), 6.0 * sd / (std::sqrt(3.0) * (3.0 + lode * sd)),
            6.0 * c / (std::sqrt(3.0) * (3.0 + lode * s)) * cohesion};
  }

  double yield(double q, double p) const { return q + eta * p - xi_c; }

  // The return from the trial principal logarithmic strains eps (replaced by the elastic ones): principal Kirchhoff
  // stresses t, modulus a = dt / d eps, the stress's q. Returns whether the material yielded.
  bool return_map(double K, double G, Vec3& eps, Vec3& t, Mat3& a, double& q) const {
    const double theta = eps.sum();
    const Vec3 s_tr = 2.0 * G * (eps - Vec3::Constant(theta / 3.0));
    const double p_tr = K * theta, q_tr = std::sqrt(0.5 * s_tr.squaredNorm());
    const Mat3 dev = Mat3::Identity() - Mat3::Constant(1.0 / 3.0), ones = Mat3::Ones();
    const double phi_tr = yield(q_tr, p_tr);
    if (!(phi_tr > 0.0)) {
      t = s_tr + Vec3::Constant(p_tr), a = 2.0 * G * dev + K * ones, q = q_tr;
      return false;
    }
    const double H = G + K * eta * eta_bar, dgamma = phi_tr / H;
    if (G * dgamma < q_tr) {  // the cone
      const double factor = 1.0 - G * dgamma / q_tr, p = p_tr - K * eta_bar * dgamma;
      const Vec3 n = s_tr / (std::sqrt(2.0) * q_tr), one = Vec3::Ones();
      t = factor * s_tr + Vec3::Constant(p);
      a = 2.0 * G * factor * dev + 2.0 * G * (G * dgamma / q_tr - G / H) * n * n.transpose() -
          std::sqrt(2.0) * G * K / H * (eta * n * one.transpose() + eta_bar * one * n.transpose()) + K * (1.0 - K * eta * eta_bar / H) * ones;
      eps = factor * (eps - Vec3::Constant(theta / 3.0)) + Vec3::Constant(p / (3.0 * K));
      q = factor * q_tr;
      return true;
    }
    const double p = xi_c / eta;  // the apex (G dgamma >= q_tr > 0 needs eta > 0 when xi c > 0)
    t = Vec3::Constant(p), a = Mat3::Zero(), eps = Vec3::Constant(p / (3.0 * K)), q = 0.0;
    return true;
  }
};

}  // namespace loom
