// The process's allocator policy for loom's programs: the loom command, the tests and the benchmarks
// (engine/core/allocator_at_start.cpp applies it before main).
//
// UMFPACK allocates its factor afresh at every numeric factorisation and frees it at the next. glibc serves
// blocks that large with mmap and returns them with munmap, so every factorisation faulted its memory in page by
// page, zeroed by the kernel: es_pfem and pfem runs took 2.0 to 2.6 times as long (perf/README.md, "Freed memory
// stays in the heap"). Kept in the heap, a freed factor is the next one's memory, already mapped.
#pragma once

namespace loom {

// Large blocks of the main thread come from the heap, not from mmap, and the heap's top is returned to the system
// only beyond 2 GiB free. Only where the memory comes from changes (the probes of perf/policy_ab.py's cases were
// identical byte for byte); the resident size stays near the run's peak instead of falling between factorisations,
// and a block that grows (realloc) is copied instead of remapped, so it briefly needs its old and new size. Idempotent;
// a no-op where the C library is not glibc, and with LOOM_MALLOC=system in the environment (glibc's own policy, to
// compare: perf/policy_ab.py); another value of LOOM_MALLOC means loom's policy.
void keep_freed_memory_in_heap();

}  // namespace loom
