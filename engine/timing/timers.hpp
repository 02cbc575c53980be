// Wall-clock timers keyed by a slash-separated name ("newton/assemble"): every graph node is timed under
// its own name and systems time their sub-phases (STYLE §13). Thread-safe; cheap enough per call
// (one steady_clock read at each end, one short lock when a scope ends), never per entity.
#pragma once

#include <chrono>
#include <map>
#include <mutex>
#include <ostream>
#include <string>

namespace loom {

struct TimerStats {
  long long calls = 0;
  double total = 0.0;  // seconds
  double max = 0.0;
};

class Timers {
 public:
  void add(const std::string& name, double seconds);
  std::map<std::string, TimerStats> snapshot() const;
  void clear();

  // The table printed at the end of a run: calls, total, mean, max and share of `wall` seconds, for the
  // top-level entries (no '/') and their children indented below them, recursively; a sub-timer whose
  // parent is not timed is listed under its full name.
  void print_table(std::ostream& os, double wall) const;
  // {"wall": w, "timers": {"name": {"calls": .., "total": .., "mean": .., "max": ..}, ...}}
  void write_json(std::ostream& os, double wall) const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, TimerStats> stats_;
};

class ScopedTimer {
 public:
  ScopedTimer(Timers& timers, std::string name)
      : timers_(&timers), name_(std::move(name)), start_(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() { stop(); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;
  // Ends the measurement early; returns the elapsed seconds.
  double stop() {
    if (!timers_) return 0.0;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    timers_->add(name_, s);
    timers_ = nullptr;
    return s;
  }

 private:
  Timers* timers_;
  std::string name_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace loom
