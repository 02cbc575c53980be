// Time stepping with cut-backs: each scene step of size dt is solved by running the step graph; when
// Newton fails the (sub)step is halved and retried, up to max_cutbacks halvings within one scene step.
// Sub-steps complete the scene step at exactly t = step * dt (ctx.step_end marks the last one).
// A RunError thrown by a system (an anomaly, not a Newton failure) ends the loop with the partial result.
#pragma once

#include <functional>
#include <string>

#include "engine/drivers/step_status.hpp"
#include "engine/graph/step_context.hpp"
#include "engine/graph/step_graph.hpp"

namespace loom {

struct TimeLoopResult {
  bool completed = false;
  int last_converged_step = 0;
  double last_converged_time = 0.0;  // time of the last committed state (may be inside a failed step)
  int failed_step = 0;
  double failed_dt = 0.0;
  int cutbacks = 0;                  // over the whole run
  bool anomaly = false;              // a system threw (RunError): no cut-back is tried
  std::string failure;
};

struct TimeLoopCallbacks {
  std::function<void(const StepContext&, const StepStatus&)> step_done;  // after each scene step
  std::function<void(const StepContext&, const StepStatus&)> cut_back;   // after each failed attempt
};

TimeLoopResult run_time_loop(double dt, int steps, int max_cutbacks, StepContext& ctx, StepGraph& graph,
                             StepStatus& status, const TimeLoopCallbacks& callbacks);

}  // namespace loom
