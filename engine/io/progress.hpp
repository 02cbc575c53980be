// A one-line progress display on stderr for runs longer than a few seconds: rewritten in place on a
// terminal, a plain line every 10 s otherwise (logs, CI; LOOM_PROGRESS_SECONDS sets the interval).
#pragma once

#include <chrono>
#include <string>

namespace loom {

class Progress {
 public:
  Progress(int total_steps, bool enabled);
  void update(int step, double time, int newton_iterations);
  void finish();

 private:
  int total_;
  bool enabled_, tty_, shown_ = false;
  double interval_ = 10.0;  // seconds between lines when stderr is not a terminal
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace loom
