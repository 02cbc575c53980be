// A one-line progress display on stderr for runs longer than a few seconds: rewritten in place on a
// terminal, a plain line every 10 s otherwise (logs, CI).
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
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace loom
