// One helper runs a per-index body either in parallel (oneTBB) or serially (STYLE §4).
// The body must only write to entries owned by its index (or be made race-free by colouring).
#pragma once

#include <algorithm>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>

#include "engine/core/types.hpp"

namespace loom {

enum class Execution { serial, parallel };

// Below this many items the overhead of spawning tasks dominates.
inline constexpr Index kParallelGrain = 256;

// `grain`: items worth one task (fewer for heavy items, e.g. grid cells holding many particles).
template <class Body>
void for_each_index(Index n, Body&& body, Execution exec = Execution::parallel, Index grain = kParallelGrain) {
  if (exec == Execution::serial || n < grain) {
    for (Index i = 0; i < n; ++i) body(i);
    return;
  }
  oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<Index>(0, n, std::max<Index>(1, grain / 4)),
                            [&](const oneapi::tbb::blocked_range<Index>& r) {
                              for (Index i = r.begin(); i != r.end(); ++i) body(i);
                            });
}

// Sets values[0 .. n) to zero in parallel chunks: the tangent's value array, zeroed before every assembly, is 1.3 MB
// at 10^4 MPM particles and 14 MB at 10^5, and zeroed by one thread it is the assembly's largest serial part.
inline void zero_in_parallel(double* values, Index n) {
  constexpr Index chunk = 1 << 14;
  for_each_index((n + chunk - 1) / chunk, [&](Index k) { std::fill(values + k * chunk, values + std::min(n, (k + 1) * chunk), 0.0); },
                 Execution::parallel, 8);
}

// Same, over an explicit list of indices (e.g. the cells of one colour).
template <class Body>
void for_each_in(const Index* items, Index n, Body&& body, Execution exec = Execution::parallel, Index grain = kParallelGrain) {
  for_each_index(n, [&](Index k) { body(items[k]); }, exec, grain);
}

// for_each_in, calling ahead(items[k + 1]) before body(items[k]): `ahead` prefetches what body will read for
// the next item. The next item may belong to another task's range; that only warms a line it would read too.
template <class Ahead, class Body>
void for_each_in_looking_ahead(const Index* items, Index n, Ahead&& ahead, Body&& body, Execution exec = Execution::parallel,
                               Index grain = kParallelGrain) {
  for_each_index(
      n,
      [&](Index k) {
        if (k + 1 < n) ahead(items[k + 1]);
        body(items[k]);
      },
      exec, grain);
}

}  // namespace loom
