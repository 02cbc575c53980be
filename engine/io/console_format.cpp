#include "engine/io/console_format.hpp"

#include <cmath>
#include <cstdio>

namespace loom {

std::string format_seconds(double s) {
  char buf[64];
  if (!(s >= 0.0)) return "? s";
  if (s < 1e-3) std::snprintf(buf, sizeof buf, "%.2f ms", 1e3 * s);
  else if (s < 0.9995) std::snprintf(buf, sizeof buf, "%.0f ms", 1e3 * s);
  else if (s < 59.95) std::snprintf(buf, sizeof buf, "%.1f s", s);
  else if (s < 3599.5) {
    const long total = std::lround(s);
    std::snprintf(buf, sizeof buf, "%ld min %02ld s", total / 60, total % 60);
  } else {
    const long minutes = std::lround(s / 60.0);
    std::snprintf(buf, sizeof buf, "%ld h %02ld min", minutes / 60, minutes % 60);
  }
  return buf;
}

std::string count_of(long long n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many.empty() ? one + "s" : many);
}

}  // namespace loom
