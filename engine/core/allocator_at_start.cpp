// Compiled into every program, the loom command, each test and each benchmark (LOOM_PROGRAM_SOURCES,
// cmake/LoomHelpers.cmake): each runs under loom's allocator policy (engine/core/allocator.hpp) from before main, so
// that a timed factorisation costs what it costs in a run, and a test that runs a recipe in-process takes the time the
// run would (perf/README.md, "Freed memory stays in the heap").
#include "engine/core/allocator.hpp"

namespace {

[[maybe_unused]] const bool kPolicySet = (loom::keep_freed_memory_in_heap(), true);

}  // namespace
