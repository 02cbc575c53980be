// Helpers of the stress suite (label stress): run the loom program on a scene, check that the run ended
// cleanly whatever happened, and record one row per case for docs/BENCHMARKS.md.
//
// A clean end (DESIGN §5, §6) is either
//   - exit code 0, run.json converged = true, every probe of every step finite; or
//   - exit code 1, stderr naming the failure and "last converged step N", run.json converged = false with
//     last_converged_step = N, probes.csv holding exactly the steps 0..N, all finite.
// Anything else (a crash, an internal error, exit 2 on a valid scene, a NaN written as a result) is a
// failure of the test.
//
// Rows go to the CSV file named by the environment variable LOOM_STRESS_CSV (tools/study --all sets it to
// docs/benchmarks/stress/stress.csv); without it nothing is written.
#pragma once

#include <string>
#include <vector>

#include "tests/scenes/scene_checks.hpp"
#include "tests/support/test_support.hpp"

namespace loom::stress {

struct Outcome {
  int exit_code = -1;
  bool clean = false;       // one of the two clean ends above
  bool converged = false;
  int last_converged_step = 0;
  int steps_requested = 0;
  long long newton_iterations = 0;
  int cutbacks = 0;
  double wall_seconds = 0.0;
  std::string failure;      // run.json failure (empty when converged)
  std::string why_unclean;  // what broke the contract, if it did
  testing::ProbeTable probes;
  std::string err;
};

// Runs `loom run scene --out out --quiet` with the extra arguments and checks the end (EXPECTs inside).
Outcome run_checked(const std::string& scene, const std::string& out, const std::vector<std::string>& extra);

// The last value of a probe (NaN if there is no row).
double last(const Outcome& o, const std::string& probe);

// Appends a row group,case,outcome,exit,steps,detail,check to LOOM_STRESS_CSV (if set). `check` says
// whether the case's own property held ("holds", or "FAILS: ...").
void record(const std::string& group, const std::string& case_name, const Outcome& o, const std::string& detail,
            const std::string& check);

// The same scene with 1 and 2 oneTBB threads (`--threads`): the probes of every step and the Newton
// iterations must agree (assembly is ordered by cell colour, reductions are fixed-order).
struct ThreadComparison {
  Outcome one, two;
  double worst = 0.0;       // largest relative difference of a probe value over all steps
  bool same_shape = false;  // the same number of probe rows
  bool same() const { return same_shape && worst <= 1e-12 && one.newton_iterations == two.newton_iterations; }
  std::string detail() const;
};
ThreadComparison run_with_one_and_two_threads(const std::string& scene, const std::vector<std::string>& sets);

std::string scene_path(const std::string& file);  // scenes/<file> in the source tree
std::string stress_scene(const std::string& file);  // tests/stress/scenes/<file>
std::string format(double v, int digits = 6);

}  // namespace loom::stress
