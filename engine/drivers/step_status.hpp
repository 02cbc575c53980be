// Outcome of the Newton solve of the current (sub)step: written by the solve node, read by the nodes
// that may only run on a converged state (commit, probes, output) and by the time loop.
#pragma once

#include <string>

namespace loom {

struct StepStatus {
  bool converged = false;
  int iterations = 0;       // linear solves of this (sub)step
  int step_iterations = 0;  // summed over the sub-steps of the current scene step
  long long total_iterations = 0;
  int total_cutbacks = 0;   // step halvings over the run (the time loop counts them)
  // false: a shorter (sub)step would solve the same problem as the one that failed (engine/methods/recipes/cut_back_policy.hpp),
  // and the time loop does not cut back.
  bool shorter_step_helps = true;
  std::string failure;
};

}  // namespace loom
