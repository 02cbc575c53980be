// What a finished (or failed) run reports: written to run.json and printed at exit.
#pragma once

#include <string>

namespace loom {

struct RunSummary {
  bool converged = false;           // every step that was run converged (also when the run stopped early)
  bool completed = false;           // it reached the last step of the scene
  int interrupted_by = 0;           // the signal that stopped it between steps (SIGINT, SIGTERM), 0 if none
  bool stopped = false;             // stopped after the step asked for (`loom run --stop-after N`)
  bool settled = false;             // completed before the last step: time.stop_when's probe fell below its bound
  bool restarted = false;           // continued from a checkpoint, of step restarted_from
  int restarted_from = 0;
  int steps_requested = 0;
  int steps_done = 0;               // scene steps completed
  int last_converged_step = 0;
  double last_converged_time = 0.0;  // may lie inside the failed step (its sub-steps that converged)
  double last_step_time = 0.0;       // the end of step last_converged_step
  long long newton_iterations = 0;  // linear solves over the run
  int cutbacks = 0;                 // over the whole run (a restarted run counts those before its checkpoint)
  double wall_seconds = 0.0;
  std::string failure;              // empty when converged
  std::string linear_solver;        // back-end in use at the end
  // Numeric factorisations of this process (not those before a restart) and, with solver.reuse_factor, the
  // linear solves done by GMRES on a kept factorisation and their GMRES iterations.
  long long factorizations = 0, reused_solves = 0, gmres_iterations = 0;
  // Krylov iterations and preconditioner set-ups of an iterative back-end (petsc), this process.
  long long linear_iterations = 0, preconditioner_set_ups = 0;
  long long dofs = 0, cells = 0;
  int threads = 0;
  int ranks = 1;  // MPI ranks of the run (mpirun -n N)
};

}  // namespace loom
