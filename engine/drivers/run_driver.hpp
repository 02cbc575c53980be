// What every recipe's run does around its step graph (fem, pfem, mpm): the time loop with the progress
// display and the cut-back log, the last converged state written when the run fails (so that the output
// ends where the run did), the frame writer drained, and the convergence fields of the run summary. A
// RunError outside the time loop (frame 0, the writer) ends the run as an anomaly, reported like a step
// that stopped. Checkpoints are written every `checkpoint_every` steps and when the run stops early (a
// signal, or `stop_after`); a restarted run starts after the checkpoint's step without writing step 0.
// Every end leaves the state it reached as the last frame (completed, settled, stopped, interrupted, failed).
#pragma once

#include <functional>
#include <ostream>

#include "engine/drivers/run_summary.hpp"
#include "engine/drivers/time_loop.hpp"
#include "engine/linalg/linear_solver.hpp"

namespace loom {

struct RunSchedule {
  double dt = 0.0;
  int steps = 0;
  int max_cutbacks = 0;
  bool progress = true;          // one-line progress display on stderr
  std::ostream* log = nullptr;   // cut-back messages; nullptr: silent
  int checkpoint_every = 0;      // steps between checkpoints; 0: none (but at a stop_after or an interrupt)
  bool restarted = false;        // continued from the checkpoint of step first_step - 1 (step 0 is not written again)
  int first_step = 1;
  int stop_after = 0;            // stop after this step as if interrupted (0: run to the end)
};

struct RunHooks {
  std::function<void()> write_initial_state;
  // At the end of every run: write the last converged state, reached at `last_converged_time` within or
  // before step `step` (the failed step, or the last completed one), if the recipe writes frames and has not
  // written that one.
  std::function<void(int step, double last_converged_time)> write_last_converged_state;
  std::function<void()> wait_for_writer;
  // Writes the checkpoint of the completed step (the writer has finished the step's frame).
  std::function<void(int step)> write_checkpoint;
  // After each completed step: true ends the run there as completed (time.stop_when).
  std::function<bool(const StepContext&)> settled;
  // Adaptive time steps (time.adaptive_dt): the next step's size, and the time the run ends at.
  std::function<double(const StepContext&)> step_size;
  double end_time = 0.0;
};

TimeLoopResult drive_run(const RunSchedule& schedule, StepContext& ctx, StepGraph& graph, StepStatus& status, const RunHooks& hooks);

// Fills converged, steps_done, last_converged_step/time, newton_iterations, cutbacks and failure.
void summarise_run(const TimeLoopResult& result, const StepStatus& status, const RunSchedule& schedule, RunSummary& summary);
// Fills linear_solver (the back-end the run came to), factorizations, reused_solves and gmres_iterations.
void summarise_linear_solver(const LinearSolve& solver, RunSummary& summary);

}  // namespace loom
