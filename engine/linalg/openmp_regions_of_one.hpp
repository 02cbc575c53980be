// OpenMP regions run on the calling thread when OpenMP is limited to one thread:
// engine/linalg/openmp_regions_of_one.cpp (compiled into every program, not into a library) says why and how.
#pragma once

namespace loom {

// How many OpenMP parallel regions (CHOLMOD's, and any other library's) this program has run on the calling thread
// instead of through libgomp: 0 with LOOM_OPENMP=libgomp or a thread limit above one.
long openmp_regions_run_here();

}  // namespace loom
