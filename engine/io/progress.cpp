#include "engine/io/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "engine/io/console_format.hpp"

namespace loom {

Progress::Progress(int total_steps, bool enabled, int first_step)
    : total_(total_steps), first_(first_step), enabled_(enabled), tty_(isatty(fileno(stderr)) != 0),
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
  const double eta = done > 0 ? elapsed * (total_ - step) / done : 0.0;
  std::ostringstream os;
  os.precision(4);
  os << "step " << step << "/" << total_ << "  t = " << time << "  newton " << newton_iterations << "  elapsed "
     << format_seconds(elapsed) << "  remaining ~" << format_seconds(eta);
  if (tty_) std::cerr << "\r" << os.str() << "\033[K" << std::flush;
  else std::cerr << os.str() << std::endl;
  shown_ = true;
}

void Progress::finish() {
  if (enabled_ && shown_ && tty_) std::cerr << "\n";
  shown_ = false;
}

}  // namespace loom
