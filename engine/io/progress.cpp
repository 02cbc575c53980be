#include "engine/io/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "engine/io/console_format.hpp"

namespace loom {

Progress::Progress(int total_steps, bool enabled, int first_step, double end_time, double start_time)
    : total_(total_steps), first_(first_step), end_time_(end_time), start_time_(start_time), enabled_(enabled), tty_(isatty(fileno(stderr)) != 0),
      start_(std::chrono::steady_clock::now()), last_(start_) {
  if (const char* s = std::getenv("LOOM_PROGRESS_SECONDS")) interval_ = std::max(0.01, std::atof(s));
}

void Progress::update(int step, double time, int newton_iterations) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (tty_ ? (elapsed < 3.0 || since < 0.25) : since < interval_) return;
  last_ = now;
  const int done = step - first_ + 1;
  const bool by_time = end_time_ > 0.0 && time > start_time_;
  const double eta = by_time ? elapsed * (end_time_ - time) / (time - start_time_) : done > 0 ? elapsed * (total_ - step) / done : 0.0;
  std::ostringstream os;
  os.precision(4);
  os << "step " << step;
  if (end_time_ > 0.0) os << "  t = " << time << "/" << end_time_;
  else os << "/" << total_ << "  t = " << time;
  os << "  newton " << newton_iterations << "  elapsed " << format_seconds(elapsed) << "  remaining ~" << format_seconds(eta);
  if (tty_) std::cerr << "\r" << os.str() << "\033[K" << std::flush;
  else std::cerr << os.str() << std::endl;
  shown_ = true;
}

void Progress::finish() {
  if (enabled_ && shown_ && tty_) std::cerr << "\n";
  shown_ = false;
}

}  // namespace loom
