// Compiled into every program (the loom command, the tests, the benchmarks: cmake/LoomHelpers.cmake), not into a
// library: the dynamic linker binds a shared library's call to the executable's definition of a symbol before its
// own library's, and only a definition in the executable is certain to be linked.
//
// Debian's CHOLMOD is built with OpenMP and opens a parallel region for each supernode it factorises. loom limits
// OpenMP to one thread (OMP_THREAD_LIMIT=1, engine/cli/main.cpp), and libgomp still starts a team of one for every
// region and ends it at a barrier whose last arrival wakes a futex: a system call per region, thousands per
// factorisation of a 2D system of small supernodes. On the MPM cantilever of perf/compare (10 240 particles, CHOLMOD)
// that was a third of the run's CPU time (perf/README.md, "OpenMP regions of one thread").
//
// GOMP_parallel is the entry point GCC compiles `#pragma omp parallel` to, and the only one of libgomp's region
// entries CHOLMOD calls (with omp_get_num_threads and omp_get_thread_num, for its statically scheduled loops). Here,
// when OpenMP's thread limit is one, it runs the region's body on the calling thread: what a team of one does, as
// those two functions answer 1 and 0 outside a region. Any other limit, or LOOM_OPENMP=libgomp in the environment,
// forwards every region to libgomp.
#include <dlfcn.h>

#include <atomic>
#include <cstdlib>
#include <cstring>

#include "engine/linalg/openmp_regions_of_one.hpp"

namespace {

using Region = void (*)(void*);
using GompParallel = void (*)(Region, void*, unsigned, unsigned);

std::atomic<long> regions_run_here{0};

struct Dispatch {
  bool here = false;            // run every region on the calling thread
  GompParallel libgomp = nullptr;
};

const Dispatch& dispatch() {
  static const Dispatch d = [] {
    Dispatch r;
    r.libgomp = reinterpret_cast<GompParallel>(dlvsym(RTLD_NEXT, "GOMP_parallel", "GOMP_4.0"));
    if (!r.libgomp) r.libgomp = reinterpret_cast<GompParallel>(dlsym(RTLD_NEXT, "GOMP_parallel"));
    using ThreadLimit = int (*)();
    const auto thread_limit = reinterpret_cast<ThreadLimit>(dlsym(RTLD_DEFAULT, "omp_get_thread_limit"));
    const char* choice = std::getenv("LOOM_OPENMP");
    const bool forced_libgomp = choice && std::strcmp(choice, "libgomp") == 0;
    r.here = !r.libgomp || (!forced_libgomp && thread_limit && thread_limit() == 1);
    return r;
  }();
  return d;
}

}  // namespace

extern "C" __attribute__((visibility("default"))) void GOMP_parallel(Region fn, void* data, unsigned num_threads, unsigned flags) {
  const Dispatch& d = dispatch();
  if (d.here) {
    regions_run_here.fetch_add(1, std::memory_order_relaxed);
    fn(data);
    return;
  }
  d.libgomp(fn, data, num_threads, flags);
}

namespace loom {

long openmp_regions_run_here() { return regions_run_here.load(std::memory_order_relaxed); }

}  // namespace loom
