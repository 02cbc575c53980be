// The materials a scene can use, as one closed set: kernels are instantiated per model by visiting the
// variant once per cell, never through a virtual call per point.
#pragma once

#include <cmath>
#include <type_traits>
#include <variant>
#include <vector>

#include "engine/scene/scene_spec.hpp"
#include "systems/assemble/materials/linear_elastic.hpp"
#include "systems/assemble/materials/neo_hooke.hpp"
#include "systems/assemble/materials/neo_hooke_split.hpp"

namespace loom {

using Material = std::variant<NeoHooke, LinearElastic, NeoHookeSplit>;

inline Material make_material(const MaterialSpec& m) {
  switch (m.model) {
    case MaterialModel::neo_hooke: return NeoHooke{m.lambda, m.mu};
    case MaterialModel::linear_elastic: return LinearElastic{m.lambda, m.mu};
    case MaterialModel::neo_hooke_split: return NeoHookeSplit{m.mu, std::isinf(m.K) ? 0.0 : 1.0 / m.K};
  }
  return NeoHooke{m.lambda, m.mu};
}

// What the kernels need to know of a body's material: the constitutive model and the reference density.
struct BodyMaterial {
  Material model;
  double density = 0.0;       // rho_0
  double alpha_over_G = 0.0;  // PPP stabilisation alpha_s / G of mixed u-phi elements (seed 000 eq 30)
};

// Indexed like SceneSpec::bodies.
inline std::vector<BodyMaterial> body_materials(const SceneSpec& scene) {
  std::vector<BodyMaterial> r;
  for (const auto& b : scene.bodies) {
    const auto& m = scene.materials[std::size_t(b.material)];
    r.push_back({make_material(m), m.density, b.alpha_s / m.G});
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

}  // namespace loom
