// The profile of a run (`loom run --profile`): every timed scope as an event, grouped into a tree
// step > system > sub-phase for timings.json. Times in seconds; `start` relative to the moment the profile
// was enabled.
//
// Nesting follows the slash-separated timer names ("newton/solve/factorize" lies under "newton/solve",
// under "newton") within one run of the step graph. A sub-phase of the Newton driver (timer names under
// "newton/") recorded during iteration k gets the level "iteration k" between the system and itself:
// newton > iteration 2 > solve > factorize.
// Iteration 0 is the assembly before the first solve; iteration k holds the k-th solve, the update and
// the assemblies after it (line-search trials included); such a level, which no scope timed, spans its
// children (first start to last end, the untimed work between them included). Repeated scopes with the same
// path are merged (calls counts them), as a flame graph merges equal stacks. A scope that started inside a
// graph run but does not lie inside its parent's time (the VTK writer, which runs while the next step
// computes; a scope timed after the run, between two steps) is listed at the step level under its full name
// with "concurrent": true, so that every child lies within its parent's time. Systems of one step may
// overlap (probes and output run in parallel), so a step's children may add up to more than the step; below
// the systems, phases run one after the other.
#pragma once

#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace loom {

// The first name component of the Newton driver's scopes (solve_newton: "newton/assemble", ...).
inline constexpr const char* kNewtonScope = "newton";

// One run of the step graph: a scene step or a sub-step of a cut-back step.
struct ProfileRun {
  int step = 0;
  double t = 0.0, dt = 0.0;
  double start = 0.0, seconds = 0.0;
};

// One timed scope. run: index into the runs (-1: before the first graph run, the initial state);
// iteration: Newton iteration in progress when it started (-1: outside Newton).
struct ProfileEvent {
  std::string name;
  int run = -1;
  int iteration = -1;
  double start = 0.0, seconds = 0.0;
};

// {"steps": [{"name": "step 1", "step": 1, "t": .., "dt": .., "start": .., "seconds": .., "children": [
//    {"name": "newton", "calls": 1, "start": .., "seconds": .., "children": [
//      {"name": "iteration 0", ...}, ...]}, ...]}, ...]}
// written as the value of the "profile" key (no trailing newline); `indent` prefixes every line but the
// first.
void write_profile_json(std::ostream& os, const std::vector<ProfileRun>& runs, const std::vector<ProfileEvent>& events,
                        const std::string& indent);

// The `n` timers with the largest self time (total minus the totals of their named children, at least 0),
// largest first: the most expensive systems and sub-phases of the run.
struct TimerTotal {
  std::string name;
  double total = 0.0;
};
std::vector<std::pair<std::string, double>> most_expensive(const std::vector<TimerTotal>& timers, std::size_t n);

}  // namespace loom
