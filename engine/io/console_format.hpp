// Numbers for people on the console: durations in the unit that reads best, counts with their noun.
#pragma once

#include <string>

namespace loom {

// 0.35 -> "350 ms", 14.61 -> "14.6 s", 125 -> "2 min 05 s", 7384 -> "2 h 03 min".
std::string format_seconds(double seconds);
// (1, "step") -> "1 step", (3, "step") -> "3 steps"; `many` replaces the plural when given.
std::string count_of(long long n, const std::string& one, const std::string& many = "");

}  // namespace loom
