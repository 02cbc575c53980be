// body[].initial_velocity: each body's velocity at t = 0, a field of expressions in the reference position
// (x, y; t = 0), for the dynamic integrators of every method: the nodes of fem / pfem / es_pfem bodies,
// the particles of mpm bodies and the nodes of mpm_fem's FEM bodies. Points of a body without one keep
// zero; the scene loader refuses the key with a static integrator.
#pragma once

#include <algorithm>
#include <array>
#include <optional>
#include <sstream>
#include <vector>

#include "engine/core/errors.hpp"
#include "engine/core/types.hpp"
#include "engine/scene/expression.hpp"
#include "engine/scene/scene_spec.hpp"

namespace loom {

// Calls set(k, v) for every point k in [0, n) whose body (body_of(k), kNoIndex: none) has an initial
// velocity, with v evaluated at position_of(k). Expressions are evaluated serially (muparser).
template <int D = 2, class BodyOf, class PositionOf, class Set>
void for_each_initial_velocity(const SceneSpec& scene, Index n, BodyOf&& body_of, PositionOf&& position_of, Set&& set) {
  std::vector<std::array<std::optional<Expression>, D>> field(scene.bodies.size());
  bool any = false;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const VectorExpression& v = scene.bodies[b].initial_velocity;
    for (int d = 0; d < D; ++d) {
      const std::optional<ExpressionSpec>& e = v[d];
      if (!e) continue;
      std::ostringstream where;
      where << e->where << ": error: " << e->key;
      field[b][std::size_t(d)].emplace(e->text, where.str(), D);
      any = true;
    }
  }
  if (!any) return;
  for (Index k = 0; k < n; ++k) {
    const Index b = body_of(k);
    if (b == kNoIndex) continue;
    const auto& f = field[std::size_t(b)];
    if (std::none_of(f.begin(), f.end(), [](const auto& e) { return e.has_value(); })) continue;
    const Vec<D> X = position_of(k);
    Vec<D> v = Vec<D>::Zero();
    for (int d = 0; d < D; ++d) {
      if (!f[std::size_t(d)]) continue;
      try {
        v[d] = (*f[std::size_t(d)])(0.0, X.x(), X.y(), D == 3 ? X[D - 1] : 0.0);
      } catch (const RunError& e) {  // not finite here: the scene's field, so bad input (exit 2)
        throw InputError(e.what());
      }
    }
    set(k, v);
  }
}

}  // namespace loom
