// A one-line progress display on stderr for runs longer than a few seconds: rewritten in place on a
// terminal, a plain line every 10 s otherwise (logs, CI; LOOM_PROGRESS_SECONDS sets the interval).
#pragma once

#include <chrono>
#include <string>

namespace loom {

class Progress {
 public:
  // first_step: the step a restarted run begins with (the rate is measured from there). end_time > 0: a run of
  // adaptive steps that ends at that time, whose remaining time is estimated from the time left, not the steps.
  Progress(int total_steps, bool enabled, int first_step = 1, double end_time = 0.0, double start_time = 0.0);
  void update(int step, double time, int newton_iterations);
  void finish();

 private:
  int total_, first_;
  double end_time_, start_time_;
  bool enabled_, tty_, shown_ = false;
  double interval_ = 10.0;  // seconds between lines when stderr is not a terminal
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace loom
