// Software prefetch for loops that visit grid cells and, in each, the points it holds (for_each_in_looking_ahead
// in engine/core/parallel.hpp, PointLocations::prefetch_points_in). The points of a cell are scattered through
// the point columns (particles are numbered body cell by body cell; the grid is visited colour by colour, so each
// colour's pass walks the whole particle store), and every point's rows cost cache misses that out-of-order
// execution cannot overlap: the per-point work between two points' loads is hundreds of instructions. Asking
// for the next cell's rows while the current cell is computed hides that latency (perf/compare/README.md). A
// prefetch changes no result.
#pragma once

#include <cstddef>

namespace loom {

// One cache line. An asm statement, not __builtin_prefetch: g++ 12 takes a function that only reads memory and
// prefetches for pure, and drops a call to it whose result is unused (a look-ahead's).
inline void prefetch_line(const char* p) {
#if defined(__x86_64__)
  asm volatile("prefetcht0 %0" : : "m"(*p));
#else
  __builtin_prefetch(p);
#endif
}

// Every cache line of one object (an entry of a column: up to 128 bytes; a Mat3 is 72).
template <class T>
inline void prefetch_object(const T& object) {
  static_assert(sizeof(T) <= 128, "prefetch_object covers objects of up to 128 bytes");
  const char* p = reinterpret_cast<const char*>(&object);
  prefetch_line(p);
  if constexpr (sizeof(T) > 64) prefetch_line(p + 64);
  if constexpr (sizeof(T) > 1) prefetch_line(p + sizeof(T) - 1);  // the line the object's end straddles into
}

}  // namespace loom
