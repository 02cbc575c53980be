// The closed form of a strain-driven Drucker-Prager element test (systems/assemble/materials/drucker_prager.hpp):
// principal logarithmic strains growing at a constant rate, eps(t) = rate t, from a stress-free state. Elastic until
// Phi = 0 at t_y = xi c / (q_e' + eta p_e'), q_e' = sqrt2 G |dev rate|, p_e' = K tr rate; then, the deviatoric
// direction fixed, dgamma' = (q_e' + eta p_e') / H (H = G + K eta eta_bar), q' = q_e' - G dgamma',
// p' = p_e' - K eta_bar dgamma': the stress is linear in t on either side of t_y, which backward Euler reproduces exactly.
#pragma once

#include <cmath>

#include "systems/assemble/materials/hencky_perzyna.hpp"

namespace loom::testing {

struct RadialStrainPath {
  const HenckyPerzyna& material;  // with friction
  Vec3 rate;                      // d eps_A / dt (principal, fixed axes)

  Vec3 dev() const { return rate - Vec3::Constant(rate.sum() / 3.0); }
  double q_rate() const { return std::sqrt(2.0) * material.G * dev().norm(); }
  double p_rate() const { return material.K * rate.sum(); }
  double yield_time() const { return material.friction->xi_c / (q_rate() + material.friction->eta * p_rate()); }

  // Principal Kirchhoff stresses at time t.
  Vec3 stress(double t) const {
    const DruckerPrager& dp = *material.friction;
    const double t_y = yield_time(), H = material.G + material.K * dp.eta * dp.eta_bar;
    const double dgamma = (q_rate() + dp.eta * p_rate()) / H;
    const double q = t < t_y ? q_rate() * t : q_rate() * t_y + (q_rate() - material.G * dgamma) * (t - t_y);
    const double p = t < t_y ? p_rate() * t : p_rate() * t_y + (p_rate() - material.K * dp.eta_bar * dgamma) * (t - t_y);
    return q * std::sqrt(2.0) * dev() / dev().norm() + Vec3::Constant(p);
  }
};

}  // namespace loom::testing
