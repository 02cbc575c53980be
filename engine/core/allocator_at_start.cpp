// Compiled into every test and benchmark program (cmake/LoomHelpers.cmake), not into the engine library: they
// run under the allocator policy of the loom program (engine/core/allocator.hpp), so that a timed factorisation
// costs what it costs in a run, and a test that runs a recipe in-process takes the time the run would. Before
// 2026-12-05 they ran under glibc's own, as loom did (perf/README.md, "Freed memory stays in the heap").
#include "engine/core/allocator.hpp"

namespace {

[[maybe_unused]] const bool kPolicySet = (loom::keep_freed_memory_in_heap(), true);

}  // namespace
