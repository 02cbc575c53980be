// Time stepping with cut-backs: each scene step of size dt is solved by running the step graph; when
// Newton fails the (sub)step is halved and retried, up to max_cutbacks halvings within one scene step, unless the
// step's status says that a shorter step solves the same problem (then the loop stops at once).
// Sub-steps complete the scene step at exactly t = step * dt (ctx.step_end marks the last one), or at t + the
// size the step_size callback gives (adaptive time steps).
// A RunError thrown by a system (an anomaly, not a Newton failure) ends the loop with the partial result.
// Between scene steps the loop stops early when a signal asked it to (engine/core/interrupt.hpp) or when
// the requested last step is reached (`stop_after`); the state is then that of a completed step. A run also
// completes before its last step when the `settled` callback says so.
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
  double last_step_time = 0.0;       // time at the end of step last_converged_step
  int failed_step = 0;
  double failed_dt = 0.0;
  bool anomaly = false;              // a system threw (RunError): no cut-back is tried
  bool no_cut_back = false;          // failed where a shorter step solves the same problem: no cut-back was tried
  int interrupted_by = 0;            // the signal that stopped the loop between steps, 0 if none
  bool stopped = false;              // stopped after step `stop_after` as asked
  bool settled = false;              // completed early: `settled` said the run had reached its end state
  std::string failure;
};

struct TimeLoopCallbacks {
  std::function<void(const StepContext&, const StepStatus&)> step_done;  // after each scene step
  std::function<void(const StepContext&, const StepStatus&)> cut_back;   // after each failed attempt
  // After step_done: true ends the run as completed (a flow that has come to rest, time.stop_when).
  std::function<bool(const StepContext&)> settled;
  // Adaptive time stepping (time.adaptive_dt): when set, the size of the next scene step, asked at its start with
  // ctx.t the time reached; the run then completes once t reaches end_time.
  std::function<double(const StepContext&)> step_size;
  double end_time = 0.0;
};

struct TimeLoopRange {
  int first_step = 1;   // a restarted run begins after the checkpoint's step (ctx.t holds its time)
  int stop_after = 0;   // stop (as if interrupted) after this step; 0: run to the end
};

TimeLoopResult run_time_loop(double dt, int steps, int max_cutbacks, StepContext& ctx, StepGraph& graph,
                             StepStatus& status, const TimeLoopCallbacks& callbacks, const TimeLoopRange& range = {});

}  // namespace loom
