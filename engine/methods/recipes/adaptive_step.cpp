#include "engine/methods/recipes/adaptive_step.hpp"

#include <string>

#include "engine/core/errors.hpp"
#include "engine/scene/expression.hpp"

namespace loom {

void use_adaptive_step(const SceneSpec& scene, const std::vector<double>& probe_values, RunHooks& hooks) {
  if (scene.time.adaptive_probe == kNoIndex) return;
  const std::size_t probe = std::size_t(scene.time.adaptive_probe);
  const std::string name = scene.probes[probe].name;
  hooks.step_size = [&scene, &probe_values, probe, name](const StepContext& c) {
    if (probe_values.empty()) return scene.time.dt;
    const double v = probe_values[probe];
    std::string err;
    const double dt = evaluate_formula(scene.time.adaptive_expression, {{name, v}, {"t", c.t}}, &err);
    LOOM_CHECK(err.empty() && dt > 0.0, RunError,
               "time.adaptive_dt.expression gives the step " << dt << " at " << name << " = " << v << ", t = " << c.t
                                                             << (err.empty() ? "" : ": " + err) << "; a step must be > 0");
    return dt;
  };
  hooks.end_time = scene.time.end;
}

}  // namespace loom
