#include "engine/methods/recipes/cut_back_policy.hpp"

#include <cmath>

namespace loom {

bool shorter_step_changes_problem(const SceneSpec& scene, const std::vector<Expression>& expressions) {
  if (scene.time.integrator != Integrator::static_ || !scene.inlets.empty()) return true;
  // A retried PFEM step remeshes again, from the mesh and the particles the failed attempt left: another problem.
  if (scene.scene.method == Method::pfem || scene.scene.method == Method::es_pfem) return true;
  for (const MaterialSpec& m : scene.materials)
    if (m.model == MaterialModel::hencky_perzyna && m.viscosity > 0.0 && std::isfinite(m.tau0)) return true;
  for (const Expression& e : expressions)
    if (e.depends_on_time()) return true;
  return false;
}

}  // namespace loom
