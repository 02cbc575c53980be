#include "engine/drivers/time_loop.hpp"

#include <algorithm>
#include <cmath>

#include "engine/core/errors.hpp"
#include "engine/core/interrupt.hpp"

namespace loom {
namespace {

// The end of an adaptive step: at most time.end, and time.end itself when the step falls short of it by less than
// a millionth of the step (summed steps of 4e-3 s reach 0.1 s as 0.09999999999999999: a last step of 1e-17 s would
// fail, Bossak's inertia term growing as 1 / dt^2).
double adaptive_step_end(double t, double step, double end) {
  const double next = t + step;
  return end - next <= 1e-6 * step ? end : next;
}

}  // namespace

TimeLoopResult run_time_loop(double dt, int steps, int max_cutbacks, StepContext& ctx, StepGraph& graph,
                             StepStatus& status, const TimeLoopCallbacks& callbacks, const TimeLoopRange& range) {
  TimeLoopResult result;
  double t = ctx.t;
  result.last_converged_step = range.first_step - 1;
  result.last_converged_time = result.last_step_time = t;
  // Fixed steps end at t = n dt, counted from t = 0 (no sum of dt's to drift). A run restarted with another dt
  // than its checkpoint's (its time is off that grid) counts them from the checkpoint's time instead: counted
  // from 0, its first step would run from the checkpoint's time to n dt at once.
  const bool on_grid = t == double(range.first_step - 1) * dt;
  const int step0 = on_grid ? 0 : range.first_step - 1;
  const double t0 = on_grid ? 0.0 : t;
  for (int step = range.first_step; step <= steps; ++step) {
    if (const int signal = agreed_interrupt_signal(); signal != 0) {
      result.interrupted_by = signal;
      return result;
    }
    ctx.t = t;
    const double t_end = callbacks.step_size ? adaptive_step_end(t, callbacks.step_size(ctx), callbacks.end_time) : t0 + double(step - step0) * dt;
    double h = callbacks.step_size ? t_end - t : dt;
    int halvings = 0;
    status.step_iterations = 0;
    while (t < t_end) {
      const double remaining = t_end - t;
      // Within a millionth of h the rest is the round-off of the summed sub-steps (64 sub-steps of 1.25e-4 s from
      // t = 80.888 s leave 2e-13 s): it joins this sub-step, since a step of its own would fail (Bossak's inertia
      // term grows as 1 / dt^2; tests/unit/time_loop_test.cpp).
      const bool last = remaining <= h * (1.0 + 1e-6);
      ctx.step = step;
      ctx.dt = last ? remaining : h;
      ctx.t = last ? t_end : t + h;
      ctx.step_end = last;
      try {
        graph.run();
      } catch (const RunError& e) {
        result.failed_step = step;
        result.failed_dt = ctx.dt;
        result.failure = e.what();
        result.anomaly = true;
        ctx.t = t;
        return result;
      }
      if (status.converged) {
        t = ctx.t;
        result.last_converged_time = t;
        continue;
      }
      if (!status.shorter_step_helps) {  // the halved step would fail the same way
        result.failed_step = step;
        result.failed_dt = ctx.dt;
        result.failure = status.failure + "; no cut-back was tried: a shorter step solves the same problem here (a static step whose "
                                          "loads and prescribed values do not change in time)";
        result.no_cut_back = true;
        ctx.t = t;
        return result;
      }
      if (callbacks.cut_back) callbacks.cut_back(ctx, status);
      if (halvings == max_cutbacks) {
        result.failed_step = step;
        result.failed_dt = ctx.dt;
        result.failure = status.failure;
        ctx.t = t;
        return result;
      }
      ++halvings;
      ++status.total_cutbacks;
      h = 0.5 * ctx.dt;
    }
    result.last_converged_step = step;
    result.last_step_time = t;
    if (callbacks.step_done) callbacks.step_done(ctx, status);
    if (callbacks.settled && callbacks.settled(ctx)) {
      result.completed = result.settled = true;
      return result;
    }
    if (callbacks.step_size && t >= callbacks.end_time) break;
    if (step == range.stop_after && step < steps) {
      result.stopped = true;
      return result;
    }
  }
  if (callbacks.step_size && t < callbacks.end_time) {  // time.steps ran out before time.end
    result.failed_step = steps + 1;
    result.failed_dt = 0.0;
    result.anomaly = true;
    result.failure = "time.steps = " + std::to_string(steps) + " ran out at t = " + std::to_string(t) + ", before time.end = " +
                     std::to_string(callbacks.end_time) + " (the adaptive steps were smaller than time.steps allows for): raise time.steps";
    return result;
  }
  result.completed = true;
  return result;
}

}  // namespace loom
