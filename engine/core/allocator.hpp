// The process's allocator policy for loom's programs: the loom command, the tests and the benchmarks
// (engine/core/allocator_at_start.cpp applies it before main).
//
// UMFPACK allocates its factor afresh at every numeric factorisation and frees it at the next. glibc serves
// blocks that large with mmap and returns them with munmap, so every factorisation faulted its memory in page by
// page, zeroed by the kernel: es_pfem and pfem runs took 2.0 to 2.6 times as long (perf/README.md, "Freed memory
// stays in the heap"). Kept in the heap, a freed factor is the next one's memory, already mapped.
#pragma once

namespace loom {

// Large blocks come from the heap, not from mmap, and the heap's top is returned to the system only beyond
// 2 GiB free. Results are unchanged (only where the memory comes from); the resident size stays near the run's
// peak instead of falling between factorisations. Idempotent; a no-op where the C library is not glibc, and with
// LOOM_MALLOC=system in the environment (glibc's own policy, to compare: perf/policy_ab.py).
void keep_freed_memory_in_heap();

}  // namespace loom
