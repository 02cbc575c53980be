// Wall-clock timers keyed by a slash-separated name ("newton/assemble"): every graph node is timed under
// its own name and systems time their sub-phases (STYLE §13). Thread-safe; cheap enough per call
// (one steady_clock read at each end, one short lock when a scope ends), never per entity.
// With the profile enabled (`loom run --profile`) every scope is also kept as an event with the graph run
// and the Newton iteration it started in (engine/timing/profile.hpp); without it a scope costs one more
// branch.
#pragma once

#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <ostream>
#include <string>
#include <vector>

#include "engine/timing/profile.hpp"

namespace loom {

struct TimerStats {
  long long calls = 0;
  double total = 0.0;  // seconds
  double max = 0.0;
};

// Where a scope started: the graph run (index into the profile's runs) and the Newton iteration.
struct ProfileMark {
  int run = -1;
  int iteration = -1;
};

class Timers {
 public:
  using Clock = std::chrono::steady_clock;

  void add(const std::string& name, double seconds);
  std::map<std::string, TimerStats> snapshot() const;
  void clear();

  // The profile: call enable_profile() before the run starts (not thread-safe against running scopes).
  void enable_profile();
  bool profiling() const { return profiling_; }
  ProfileMark mark() const { return {run_.load(std::memory_order_relaxed), iteration_.load(std::memory_order_relaxed)}; }
  // A scope's statistics and, when profiling, its event.
  void add_scope(const std::string& name, const ProfileMark& mark, Clock::time_point start, Clock::time_point end);
  // Called by the step graph around each run and by the Newton driver per iteration; no-ops unless
  // profiling. set_iteration(-1) marks the end of the Newton loop.
  void begin_graph_run(int step, double t, double dt);
  void end_graph_run();
  void set_iteration(int iteration) {
    if (profiling_) iteration_.store(iteration, std::memory_order_relaxed);
  }
  std::vector<ProfileRun> profile_runs() const;
  std::vector<ProfileEvent> profile_events() const;

  // The table printed at the end of a run: calls, total, mean, max and share of `wall` seconds, for the
  // top-level entries (no '/') and their children indented below them, recursively; a sub-timer whose
  // parent is not timed is listed under its full name.
  void print_table(std::ostream& os, double wall) const;
  // Below the table: the three timers of largest self time (most_expensive).
  //
  // {"wall": w, "timers": {"name": {"calls": .., "total": .., "mean": .., "max": .., "share": ..}, ...},
  //  "most_expensive": [{"name": .., "self": .., "share": ..}, ...]} and, when profiling, "profile": {..}
  // (write_profile_json).
  void write_json(std::ostream& os, double wall) const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, TimerStats> stats_;
  bool profiling_ = false;
  std::atomic<int> run_{-1}, iteration_{-1};
  Clock::time_point origin_;
  std::vector<ProfileRun> runs_;
  std::vector<ProfileEvent> events_;
};

class ScopedTimer {
 public:
  ScopedTimer(Timers& timers, std::string name)
      : timers_(&timers), name_(std::move(name)), start_(std::chrono::steady_clock::now()) {
    if (timers.profiling()) mark_ = timers.mark();
  }
  ~ScopedTimer() { stop(); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;
  // Ends the measurement early; returns the elapsed seconds.
  double stop() {
    if (!timers_) return 0.0;
    const auto end = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(end - start_).count();
    if (timers_->profiling()) timers_->add_scope(name_, mark_, start_, end);
    else timers_->add(name_, s);
    timers_ = nullptr;
    return s;
  }

 private:
  Timers* timers_;
  std::string name_;
  std::chrono::steady_clock::time_point start_;
  ProfileMark mark_;
};

}  // namespace loom
