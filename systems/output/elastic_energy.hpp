// The stored energy density psi(F) per unit reference volume of the hyperelastic materials, for energy probes:
// Neo-Hooke psi = lambda/2 (ln J)^2 + mu/2 (F:F - 3) - mu ln J; small-strain Hooke psi = lambda/2 tr(eps)^2 +
// mu eps:eps with eps = sym(F) - I; the split Neo-Hooke's own energy, or with a pressure unknown (mixed u-p)
// its deviatoric part plus p^2 / (2 kappa); elastic Hencky's of b^e = F F^T (a yielding one's is that of its b^e, which
// the callers that carry it read instead).
#pragma once

#include <cmath>
#include <variant>

#include "systems/assemble/materials/material.hpp"

namespace loom {

inline double elastic_energy(const BodyMaterial& material, const Mat3& F, bool mixed = false, double pressure = 0.0) {
  if (const auto* split = std::get_if<NeoHookeSplit>(&material.model)) {
    if (!mixed) return split->energy(F);
    NeoHookeSplit dev{split->mu, 0.0};
    return dev.energy(F) + 0.5 * pressure * pressure * split->inv_kappa;
  }
  if (const auto* hp = std::get_if<HenckyPerzyna>(&material.model)) return hp->energy(F * F.transpose());  // elastic: b^e = F F^T
  if (const auto* nh = std::get_if<NeoHooke>(&material.model)) {
    const double lnJ = std::log(F.determinant());
    return 0.5 * nh->lambda * lnJ * lnJ + 0.5 * nh->mu * (F.squaredNorm() - 3.0) - nh->mu * lnJ;
  }
  const auto& le = std::get<LinearElastic>(material.model);
  const Mat3 eps = 0.5 * (F + F.transpose()) - Mat3::Identity();
  return 0.5 * le.lambda * eps.trace() * eps.trace() + le.mu * eps.squaredNorm();
}

}  // namespace loom
