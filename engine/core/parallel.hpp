// One helper runs a per-index body either in parallel (oneTBB) or serially (STYLE §4).
// The body must only write to entries owned by its index (or be made race-free by colouring).
#pragma once

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>

#include "engine/core/types.hpp"

namespace loom {

enum class Execution { serial, parallel };

// Below this many items the overhead of spawning tasks dominates.
inline constexpr Index kParallelGrain = 256;

template <class Body>
void for_each_index(Index n, Body&& body, Execution exec = Execution::parallel) {
  if (exec == Execution::serial || n < kParallelGrain) {
    for (Index i = 0; i < n; ++i) body(i);
    return;
  }
  oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<Index>(0, n, kParallelGrain / 4),
                            [&](const oneapi::tbb::blocked_range<Index>& r) {
                              for (Index i = r.begin(); i != r.end(); ++i) body(i);
                            });
}

// Same, over an explicit list of indices (e.g. the cells of one colour).
template <class Body>
void for_each_in(const Index* items, Index n, Body&& body, Execution exec = Execution::parallel) {
  for_each_index(n, [&](Index k) { body(items[k]); }, exec);
}

}  // namespace loom
