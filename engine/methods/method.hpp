// A method is a recipe (DESIGN §4): it reads the scene, builds the stores and columns it needs, wires
// its systems into a step graph and runs the time loop. The program (engine/cli) only sees this
// interface.
#pragma once

#include <cmath>
#include <deque>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "engine/drivers/run_summary.hpp"
#include "engine/scene/scene_spec.hpp"
#include "engine/timing/timers.hpp"

namespace loom {

struct RunOptions {
  std::string output_directory;  // resolved: --out or [output] directory
  int threads = 0;               // oneTBB concurrency in effect (reported)
  bool write_files = true;       // false for `loom info` / `loom check`
  bool progress = true;
  bool verbose = false;          // Newton residuals of every iteration to `log`
  bool profile = false;          // per-step profile in timings.json (engine/timing/profile.hpp)
  std::ostream* log = nullptr;   // run messages (cut-backs, failure); nullptr: silent
  bool quiet = false;            // --quiet: no line per cut-back (the summary counts them)
  std::string output_origin;     // what named the output directory, for messages: "--out" or file:line: output.directory
  std::string restart_file;      // continue from this checkpoint (engine/io/checkpoint.hpp); empty: start at t = 0
  int stop_after = 0;            // stop after this step and write its checkpoint (0: run to the end)
};

class MethodRun {
 public:
  virtual ~MethodRun() = default;
  // Stores with their allocated columns, and the step graph (`loom info`).
  virtual void describe(std::ostream& os) const = 0;
  // Runs every step; never throws for a failed solve (the summary says so), throws RunError for
  // anomalies and InputError for scene errors found while building.
  virtual RunSummary run() = 0;
  // Per-system timings of the last run (the table at exit and timings.json).
  virtual const Timers& timers() const = 0;
  // The probes' values at the last step written to probes.csv, in the order of the scene's probes.
  virtual const std::vector<double>& probe_values() const = 0;
};

// time.stop_when: whether the step that just completed (its probes in `probe_values`) ends the run, as completed.
// Keeps the watched probe's recent values for a rate over a window.
class StopCondition {
 public:
  using History = std::vector<Vec2>;  // (t, value), oldest first: what a checkpoint keeps
  History history() const {
    History h;
    for (const auto& [t, v] : history_) h.emplace_back(t, v);
    return h;
  }
  void restore(const History& h) {
    history_.clear();
    for (const Vec2& e : h) history_.emplace_back(e.x(), e.y());
  }

  bool met(const TimeSpec& time, double t, const std::vector<double>& probe_values) {
    if (time.stop_probe == kNoIndex) return false;
    const double v = probe_values[std::size_t(time.stop_probe)];
    if (!(v == v)) return false;  // a NaN reading never settles
    const bool late = t >= time.stop_after * (1.0 - 1e-12);
    if (!time.stop_rate) return late && std::abs(v) < time.stop_below;
    history_.emplace_back(t, v);
    while (history_.size() > 2 && history_[1].first <= t - time.stop_over * (1.0 - 1e-12)) history_.pop_front();
    const double t0 = history_.front().first, v0 = history_.front().second;
    return late && t - t0 >= time.stop_over * (1.0 - 1e-12) && std::abs(v - v0) < time.stop_below * (t - t0);
  }

 private:
  std::deque<std::pair<double, double>> history_;
};

// Builds the stores of the scene's method; scene errors that need the mesh are InputErrors.
std::unique_ptr<MethodRun> make_method_run(const SceneSpec& scene, const RunOptions& options);

}  // namespace loom
