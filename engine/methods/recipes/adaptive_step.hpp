// time.adaptive_dt for every recipe: each step's size is the scene's formula in the latest value of a probe and t.
#pragma once

#include <vector>

#include "engine/drivers/run_driver.hpp"
#include "engine/scene/scene_spec.hpp"

namespace loom {

// Sets hooks.step_size and hooks.end_time when the scene asks for adaptive steps (otherwise leaves them unset:
// the fixed dt). `probe_values` are the run's latest probe values, read at each step's start (the step before's;
// the initial state's at the start; a restarted run takes time.dt until its first step has written them).
void use_adaptive_step(const SceneSpec& scene, const std::vector<double>& probe_values, RunHooks& hooks);

}  // namespace loom
