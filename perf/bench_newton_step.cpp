// One full Newton iteration of the fem recipe on Cook's membrane (Neo-Hooke, P1), 10^3 to 10^5 cells:
//   assemble (residual + tangent) -> factorize -> back-substitute -> update
// exactly the calls FemNewtonProblem makes (assemble_system, solve_linear_step, update_iterate), with
// CHOLMOD and UMFPACK. Arguments: /<cells>/<tbb threads>/<solver threads>.
//
// Threads. oneTBB runs the assembly and the nodal loops (global_control). The sparse solvers run in two
// other thread pools that `loom --threads` does not control: Debian's CHOLMOD is built with OpenMP
// (libgomp) and the dense kernels of CHOLMOD and UMFPACK run in OpenBLAS (pthreads). <solver threads>
// sets OpenBLAS's count and OpenMP's default (openblas_set_num_threads, omp_set_num_threads, looked up
// at run time; counters blas_threads and omp_threads say -1 when a library is absent). CHOLMOD's
// OpenMP regions, however, ask for num_threads(CHOLMOD_OMP_NUM_THREADS), compiled in as 4
// (suitesparse/cholmod_core.h), which only the environment variable OMP_THREAD_LIMIT caps (libgomp
// reads it at load time): run the benchmark once as is and once with OMP_THREAD_LIMIT=1 (README).
// The combinations measured:
//   /1/1: one thread everywhere except CHOLMOD's OpenMP teams (the serial reference);
//   /2/2: two threads everywhere, which is what a loom run gets today (library defaults = 2 cores);
//   /2/1: oneTBB on two threads, OpenBLAS on one.
//
// Every iteration starts from the same mid-Newton iterate (restored outside the timed region; manual
// time is the sum of the four phases). The symbolic analysis is done once before the loop, as in a run
// where the pattern does not change; its cost with the first factorization is the counter
// first_factorize_ms. Counters (ms per Newton iteration): assemble, factorize, back_substitute
// (including the right-hand side copy), scatter (increment to all dofs, inside solve_linear_step),
// update, total; outside_solver = share of the iteration spent outside factorize + back_substitute.
//
//   build-perf/perf/bench_newton_step --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <oneapi/tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "engine/linalg/linear_solver.hpp"
#include "engine/timing/timers.hpp"
#include "perf/fem_bench_setup.hpp"
#include "perf/newton_iteration_timing.hpp"
#include "perf/solver_threads.hpp"
#include "systems/assemble/assemble_system.hpp"
#include "systems/solve/solve_linear_step.hpp"
#include "systems/update/update_iterate.hpp"

namespace {

using loom::Index;
using loom::perf::FemBenchRun;
using loom::perf::Clock;
using loom::perf::seconds;
using loom::perf::set_threads;

// One run per size for every benchmark of that size (set-up at 10^5 cells takes seconds).
FemBenchRun& run_of(Index n_cells) {
  static std::map<Index, std::unique_ptr<FemBenchRun>> runs;
  auto& r = runs[n_cells];
  if (!r) r = std::make_unique<FemBenchRun>(n_cells);
  return *r;
}

void BM_NewtonStep(benchmark::State& state, const char* linear) {  // linear: "cholmod" | "umfpack"
  const Index n_cells = Index(state.range(0));
  const int threads = int(state.range(1)), solver_threads = int(state.range(2));
  oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const bool blas_set = set_threads("openblas_set_num_threads", solver_threads);
  const bool omp_set = set_threads("omp_set_num_threads", solver_threads);

  FemBenchRun& run = run_of(n_cells);
  const auto kind =
      std::string(linear) == "umfpack" ? loom::LinearSolverKind::umfpack : loom::LinearSolverKind::cholmod;
  loom::LinearSolve solver(kind);
  const std::vector<loom::Vec2> start(run.nodes.u.begin(), run.nodes.u.end());
  auto restore = [&] { std::copy(start.begin(), start.end(), run.nodes.u.begin()); };
  struct Restore {  // leaves the shared run at its mid-Newton iterate for the next benchmark
    std::function<void()> f;
    ~Restore() { f(); }
  } restore_at_exit{restore};

  auto assemble = [&] {
    return loom::assemble_system(run.ctx, loom::AssemblyMode::residual_and_tangent, run.materials, run.nodes, run.cells, run.bc,
                                 run.quad, run.system)
        .inverted_cells;
  };
  if (!loom::perf::time_newton_iterations(state, restore, assemble, run.nodes, run.bc, solver, run.system)) return;
  state.counters["blas_threads"] = blas_set ? double(solver_threads) : -1.0;
  state.counters["omp_threads"] = omp_set ? double(solver_threads) : -1.0;
  state.SetItemsProcessed(state.iterations() * n_cells);
}

// Cells 10^3, 10^4, 10^5 (the ctest smoke run filters /1000/); threads as in the header.
void sizes(benchmark::internal::Benchmark* b) {
  for (int n : {1000, 10000, 100000})
    for (auto [threads, solver_threads] : {std::pair{1, 1}, std::pair{2, 2}, std::pair{2, 1}})
      b->Args({n, threads, solver_threads});
  b->UseManualTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK_CAPTURE(BM_NewtonStep, cholmod, "cholmod")->Apply(sizes);
BENCHMARK_CAPTURE(BM_NewtonStep, umfpack, "umfpack")->Apply(sizes);

}  // namespace

BENCHMARK_MAIN();
