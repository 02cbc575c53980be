// Compiled into every program (LOOM_PROGRAM_SOURCES: the loom command, the tests, the benchmarks), not into a
// library, and exported from it (--export-dynamic-symbol, cmake/LoomHelpers.cmake): the dynamic linker binds a shared
// library's call to the executable's definition of a symbol before libgomp's.
//
// Debian's CHOLMOD is built with OpenMP and opens a parallel region for each supernode it factorises. loom limits
// OpenMP to one thread (OMP_THREAD_LIMIT=1, engine/cli/main.cpp), and libgomp still starts a team of one for every
// region and ends it at a barrier whose last arrival wakes a futex: a system call per region, thousands per
// factorisation of a 2D system of small supernodes. On the MPM cantilever of perf/compare (10 240 particles, CHOLMOD)
// that was a third of the run's CPU time (perf/README.md, "OpenMP regions of one thread").
//
// GOMP_parallel is the entry point GCC compiles `#pragma omp parallel` to. Every library's regions arrive here:
// CHOLMOD's (statically scheduled loops asking omp_get_num_threads and omp_get_thread_num), muparser's, and those of
// gmsh when it is loaded (dynamically scheduled loops, single, barrier, critical, atomic). When OpenMP's thread limit
// is one and no libgomp region is active, the region's body runs on the calling thread. That is what a team of one
// does: outside a team the two functions answer 1 and 0, and libgomp runs worksharing constructs orphaned, by the
// calling thread alone (a loop over its whole range, single taken, barrier passed, critical and atomic under its
// global lock).
// Any other limit, a call from inside a libgomp region, or LOOM_OPENMP=libgomp in the environment goes to libgomp.
// The one piece of process-wide state is the count of regions run here (for the test); the choice is made once.
#include <dlfcn.h>

#include <atomic>
#include <cstdlib>
#include <cstring>

#include "engine/linalg/openmp_regions_of_one.hpp"

namespace {

using Region = void (*)(void*);
using GompParallel = void (*)(Region, void*, unsigned, unsigned);
using OmpInt = int (*)();

std::atomic<long> regions_run_here{0};

struct Dispatch {
  bool here = false;  // the thread limit is one: run a region on the calling thread unless a libgomp region is active
  GompParallel libgomp = nullptr;
  OmpInt level = nullptr;  // omp_get_level: > 0 inside a libgomp region
};

const Dispatch& dispatch() {
  static const Dispatch d = [] {
    Dispatch r;
    r.libgomp = reinterpret_cast<GompParallel>(dlvsym(RTLD_NEXT, "GOMP_parallel", "GOMP_4.0"));
    if (!r.libgomp) r.libgomp = reinterpret_cast<GompParallel>(dlsym(RTLD_NEXT, "GOMP_parallel"));
    r.level = reinterpret_cast<OmpInt>(dlsym(RTLD_DEFAULT, "omp_get_level"));
    const auto thread_limit = reinterpret_cast<OmpInt>(dlsym(RTLD_DEFAULT, "omp_get_thread_limit"));
    const char* choice = std::getenv("LOOM_OPENMP");
    const bool forced_libgomp = choice && std::strcmp(choice, "libgomp") == 0;
    // Without libgomp in the global scope (only a library opened with RTLD_LOCAL brought it) there is nothing to
    // forward to: its regions run here, as a team of one, whatever the limit.
    r.here = !r.libgomp || (!forced_libgomp && thread_limit && thread_limit() == 1);
    return r;
  }();
  return d;
}

}  // namespace

extern "C" void GOMP_parallel(Region fn, void* data, unsigned num_threads, unsigned flags) {
  const Dispatch& d = dispatch();
  if (d.here && !(d.libgomp && d.level && d.level() > 0)) {
    regions_run_here.fetch_add(1, std::memory_order_relaxed);
    fn(data);
    return;
  }
  d.libgomp(fn, data, num_threads, flags);
}

namespace loom {

long openmp_regions_run_here() { return regions_run_here.load(std::memory_order_relaxed); }

}  // namespace loom
