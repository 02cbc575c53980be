#include "engine/core/allocator.hpp"

#include <climits>
#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace loom {

void keep_freed_memory_in_heap() {
#if defined(__GLIBC__)
  if (const char* policy = std::getenv("LOOM_MALLOC"); policy && std::strcmp(policy, "system") == 0) return;
  // M_MMAP_MAX = 0: the main thread's blocks come from its heap (which glibc extends with a mapping of its own if
  // it cannot grow). Other threads' heaps are at most 64 MiB: a larger block there is still mapped, and unmapped at
  // free. The trim threshold keeps up to 2 GiB free at the heap's top. Setting these also ends glibc's dynamic
  // thresholds (mmap above 128 KiB, raised towards 32 MiB as mapped blocks are freed, a trim threshold twice that),
  // under which the channel's n = 22 run made 23 000 page faults and six mmap / mremap / munmap triples a second.
  // They override the user's MALLOC_MMAP_MAX_ / MALLOC_TRIM_THRESHOLD_ (GLIBC_TUNABLES); LOOM_MALLOC=system does not.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, INT_MAX);
#endif
}

}  // namespace loom
