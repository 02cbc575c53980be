// When a cut-back can help: a failed step is halved and retried, which changes the problem only if the step's
// size enters it -- inertia (a dynamic integrator), loads or prescribed values that change in time, a rate-
// dependent material (Perzyna's viscosity over dt), inflow, a remesh (PFEM retries from the failed attempt's mesh). Otherwise the halved step solves the very problem
// that failed, from the same state, and fails the same way (a static step under a constant load): the time loop
// then stops at once with the reason instead of halving it max_cutbacks times for nothing.
#pragma once

#include <vector>

#include "engine/scene/expression.hpp"
#include "engine/scene/scene_spec.hpp"

namespace loom {

// `expressions`: every expression of the run's boundary conditions (prescribed values, tractions, body forces).
bool shorter_step_changes_problem(const SceneSpec& scene, const std::vector<Expression>& expressions);

}  // namespace loom
