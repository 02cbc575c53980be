// Helpers of the benchmarks that time the sparse solvers (bench_linear_solver, bench_newton_step): wall
// seconds between two clock readings, and the thread count of a threading library set through its C
// function looked up at run time (OpenBLAS, OpenMP), so that the benchmarks link against neither.
#pragma once

#include <dlfcn.h>

#include <chrono>

namespace loom::perf {

using Clock = std::chrono::steady_clock;

inline double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

// Sets a thread count through a C function found at run time; false if no loaded library has it.
inline bool set_threads(const char* function, int n) {
  using SetThreads = void (*)(int);
  auto* f = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, function));
  if (!f) return false;
  f(n);
  return true;
}

}  // namespace loom::perf
