// The materials a scene can use, as one closed set: kernels are instantiated per model by visiting the
// variant once per cell, never through a virtual call per point.
#pragma once

#include <cmath>
#include <type_traits>
#include <variant>
#include <vector>

#include "engine/scene/scene_spec.hpp"
#include "engine/store/quad_points.hpp"
#include "systems/assemble/materials/hencky_perzyna.hpp"
#include "systems/assemble/materials/linear_elastic.hpp"
#include "systems/assemble/materials/neo_hooke.hpp"
#include "systems/assemble/materials/neo_hooke_split.hpp"

namespace loom {

using Material = std::variant<NeoHooke, LinearElastic, NeoHookeSplit, HenckyPerzyna>;

inline Material make_material(const MaterialSpec& m) {
  switch (m.model) {
    case MaterialModel::neo_hooke: return NeoHooke{m.lambda, m.mu};
    case MaterialModel::linear_elastic: return LinearElastic{m.lambda, m.mu};
    case MaterialModel::neo_hooke_split: return NeoHookeSplit{m.mu, std::isinf(m.K) ? 0.0 : 1.0 / m.K};
    case MaterialModel::hencky_perzyna: return HenckyPerzyna{m.K, m.G, m.tau0, m.viscosity};
    case MaterialModel::drucker_prager: {  // Hencky's elasticity with Drucker-Prager's return (drucker_prager.hpp)
      const DruckerPragerCone cone = m.cone == ConeMatch::compression ? DruckerPragerCone::compression
                                     : m.cone == ConeMatch::extension ? DruckerPragerCone::extension
                                                                      : DruckerPragerCone::plane_strain;
      const double degree = std::acos(-1.0) / 180.0;
      HenckyPerzyna h{m.K, m.G};
      h.friction = DruckerPrager::from_mohr_coulomb(m.friction_angle * degree, m.dilatancy_angle * degree, m.cohesion, cone);
      return h;
    }
  }
  return NeoHooke{m.lambda, m.mu};
}

// What the kernels need to know of a body's material: the constitutive model and the reference density.
struct BodyMaterial {
  Material model;
  double density = 0.0;       // rho_0
  // PPP stabilisation: alpha_s / G of mixed u-phi elements (seed 000 eq 30, dimensionless), alpha_stab / G of
  // es_up and fem_up (seed 001 eq 48, 1 / stress: it multiplies the pressure).
  double alpha_over_G = 0.0;
  double inverse_bulk = 0.0;  // 1 / K: the pressure's own term of the u-p constraint (seed 001 eq 42)
};

// Indexed like SceneSpec::bodies.
inline std::vector<BodyMaterial> body_materials(const SceneSpec& scene) {
  std::vector<BodyMaterial> r;
  for (const auto& b : scene.bodies) {
    const auto& m = scene.materials[std::size_t(b.material)];
    const double alpha = has_pressure(b.element) ? b.alpha_stab : b.alpha_s;
    r.push_back({make_material(m), m.density, alpha / m.G, std::isinf(m.K) ? 0.0 : 1.0 / m.K});
  }
  return r;
}

// Cauchy stress: sigma = P F^T / J for finite-strain models (false where J <= 0); the small-strain model's
// stress is sigma itself.
inline bool cauchy_stress(const Material& material, const Mat3& F, Mat3& sigma) {
  return std::visit(
      [&](const auto& m) {
        Mat3 P;
        if (!m.stress(F, P)) return false;
        if constexpr (std::is_same_v<std::decay_t<decltype(m)>, LinearElastic>) sigma = P;
        else sigma = P * F.transpose() / F.determinant();
        return true;
      },
      material);
}

// Cauchy stress of quadrature point q: stored at commit by formulations whose materials carry history
// (stress_n), that of b^e_n where the point carries it (tau(b^e) / J), recomputed from F_n otherwise.
template <int D>
inline bool point_stress(const BodyMaterial& material, const QuadPoints<D>& quad, Index q, Mat3& sigma) {
  if (quad.stress_n.used()) {
    sigma = quad.stress_n[q];
    return true;
  }
  if (const auto* hp = std::get_if<HenckyPerzyna>(&material.model); hp && quad.be_n.used()) {
    const double J = quad.F_n[q].determinant();
    if (!(J > 0.0)) return false;
    sigma = hp->kirchhoff(quad.be_n[q]) / J;
    return true;
  }
  return cauchy_stress(material.model, quad.F_n[q], sigma);
}

}  // namespace loom
