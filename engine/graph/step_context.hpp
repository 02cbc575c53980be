// What every system may read besides its stores: the time of the step being solved and the validated
// scene (materials, solver settings). It holds no store (STYLE §3).
#pragma once

#include "engine/scene/scene_spec.hpp"

namespace loom {

struct StepContext {
  int step = 0;         // step being solved, 1-based (0: initial state)
  double t = 0.0;       // time at the end of the (sub)step being solved
  double dt = 0.0;      // (sub)step size
  bool step_end = true;  // this (sub)step completes a scene step (cut-backs split a step)
  const SceneSpec* scene = nullptr;
};

}  // namespace loom
