#include "engine/drivers/run_driver.hpp"

#include <algorithm>
#include <sstream>

#include "engine/core/errors.hpp"
#include "engine/io/progress.hpp"

namespace loom {

TimeLoopResult drive_run(const RunSchedule& schedule, StepContext& ctx, StepGraph& graph, StepStatus& status, const RunHooks& hooks) {
  // The step the run ends at: with --stop-after that one (a phase of a long run on a scene of 10^6 steps showed
  // a remaining time of hundreds of hours).
  const int last_step = schedule.stop_after > 0 ? std::min(schedule.steps, schedule.stop_after) : schedule.steps;
  // Adaptive steps end at a time, not a step: the estimate follows the time left.
  Progress progress(last_step, schedule.progress, schedule.first_step, hooks.step_size && schedule.stop_after <= 0 ? hooks.end_time : 0.0,
                    ctx.t);
  TimeLoopCallbacks callbacks;
  int checkpointed = -1;
  int completed = schedule.first_step - 1;  // the last scene step that completed (survives a throw from a hook)
  double completed_time = ctx.t;
  auto checkpoint = [&](int step) {
    if (!hooks.write_checkpoint || step == checkpointed) return;
    hooks.write_checkpoint(step);
    checkpointed = step;
  };
  callbacks.step_done = [&](const StepContext& c, const StepStatus& st) {
    completed = c.step, completed_time = c.t;
    progress.update(c.step, c.t, st.step_iterations);
  };
  callbacks.cut_back = [&](const StepContext& c, const StepStatus& st) {
    if (schedule.log) {
      progress.finish();
      *schedule.log << "step " << c.step << " (t = " << c.t << ", dt = " << c.dt << "): " << st.failure << "; cutting the step back\n";
    }
  };
  // The periodic checkpoint is written after time.stop_when has looked at the step, so that it holds the window
  // that the step's reading entered.
  // A run that settles on a checkpoint step still writes that step's checkpoint.
  callbacks.settled = [&](const StepContext& c) {
    const bool settled = hooks.settled && hooks.settled(c);
    if (schedule.checkpoint_every > 0 && c.step % schedule.checkpoint_every == 0) checkpoint(c.step);
    return settled;
  };
  callbacks.step_size = hooks.step_size;
  callbacks.end_time = hooks.end_time;
  TimeLoopResult result;
  // A RunError outside a step's graph (the initial state, a checkpoint, the writer): the run stops there, as
  // failed, with the steps that completed before it.
  auto stop = [&](const RunError& e) {
    result.completed = false;
    result.anomaly = true;
    result.interrupted_by = 0;
    result.stopped = false;
    result.failed_step = completed + 1;
    result.failed_dt = ctx.dt;
    result.last_converged_step = std::max(result.last_converged_step, completed);
    result.last_converged_time = std::max(result.last_converged_time, completed_time);
    result.last_step_time = std::max(result.last_step_time, completed_time);
    result.failure = e.what();
  };
  try {
    if (!schedule.restarted) hooks.write_initial_state();
    result = run_time_loop(schedule.dt, schedule.steps, schedule.max_cutbacks, ctx, graph, status, callbacks,
                           TimeLoopRange{schedule.first_step, schedule.stop_after});
    progress.finish();
    const bool early = result.interrupted_by != 0 || result.stopped;
    // A run stopped by a signal can be continued whatever checkpoint_every says: it is checkpointed before its
    // last frame, so that the continued run's collection is that of a run that never stopped.
    if (early) checkpoint(result.last_converged_step);
    // Every end writes the state it reached as a frame, unless the last frame is that state: a failed run its
    // last converged state (inside the failed step after converged sub-steps), a run that settles, ends at
    // time.end between frames, stops or is interrupted its last step.
    if (!result.completed && !early) hooks.write_last_converged_state(result.failed_step, result.last_converged_time);
    else hooks.write_last_converged_state(result.last_converged_step, result.last_step_time);
  } catch (const RunError& e) {
    stop(e);
  }
  try {
    hooks.wait_for_writer();
  } catch (const RunError& e) {
    if (result.completed) stop(e);
  }
  progress.finish();
  return result;
}

void summarise_run(const TimeLoopResult& result, const StepStatus& status, const RunSchedule& schedule, RunSummary& summary) {
  summary.converged = result.completed || result.interrupted_by != 0 || result.stopped;
  summary.completed = result.completed;
  summary.interrupted_by = result.interrupted_by;
  summary.stopped = result.stopped;
  summary.settled = result.settled;
  summary.steps_done = result.last_converged_step;
  summary.last_converged_step = result.last_converged_step;
  // The loop's own times: a restart with another dt has steps off the grid n dt.
  summary.last_converged_time = result.last_converged_time;
  summary.last_step_time = result.last_step_time;
  summary.newton_iterations = status.total_iterations;
  summary.cutbacks = status.total_cutbacks;
  if (summary.converged) return;
  std::ostringstream os;
  if (result.anomaly)
    os << "step " << result.failed_step << " stopped: " << result.failure;
  else if (result.no_cut_back)
    os << "step " << result.failed_step << " did not converge: " << result.failure;
  else
    os << "step " << result.failed_step << " did not converge after " << schedule.max_cutbacks << " cut-backs (last dt "
       << result.failed_dt << "): " << result.failure;
  summary.failure = os.str();
}

void summarise_linear_solver(const LinearSolve& solver, RunSummary& summary) {
  summary.linear_solver = solver.backend();
  summary.factorizations = solver.factorizations();
  summary.reused_solves = solver.reused_solves();
  summary.gmres_iterations = solver.gmres_iterations();
  summary.linear_iterations = solver.linear_iterations();
  summary.preconditioner_set_ups = solver.preconditioner_set_ups();
}

}  // namespace loom
