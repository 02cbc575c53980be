// The linear solve of a Newton iteration alone, on the P1 Neo-Hooke tangent of Cook's membrane at a
// mid-Newton iterate (perf/fem_bench_setup.hpp), 10^3 to 10^5 cells: the two back-ends the engine uses
// (engine/linalg/linear_solver.cpp: Eigen's CholmodSupernodalLLT and UmfPackLU with default controls)
// against alternatives it could use, each through Eigen's wrapper, to tell whether the engine's choice
// is the fast one for 2D P1 systems. Arguments: /<cells>/<solver threads> (OpenMP and OpenBLAS threads,
// see bench_newton_step.cpp, also for CHOLMOD's OpenMP teams and OMP_THREAD_LIMIT; oneTBB is idle here).
//
//   cholmod_supernodal   CholmodSupernodalLLT (the engine's cholmod)
//   cholmod_simplicial   CholmodSimplicialLLT (up-looking, no BLAS)
//   cholmod_auto         CholmodDecomposition (CHOLMOD picks simplicial or supernodal from the fill)
//   cholmod_supernodal_metis   CholmodSupernodalLLT with the METIS ordering only (default: AMD, then
//                        METIS only if AMD's fill is high)
//   umfpack              UmfPackLU, default controls (the engine's umfpack; 2 steps of iterative refinement)
//   umfpack_no_refine    UmfPackLU with UMFPACK_IRSTEP = 0
//   eigen_ldlt           Eigen's own SimplicialLDLT (AMD ordering), for reference
//
// The symbolic analysis is done once; each iteration is factorize + solve (counters factorize_ms,
// solve_ms; relative_residual = |K du + r| / |r| checks that the answer is right). CHOLMOD variants
// also report the factor's non-zeros (lnz) and flop count (gflop) of the ordering CHOLMOD selected.
//
//   build-perf/perf/bench_linear_solver --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <Eigen/UmfPackSupport>
#include <chrono>
#include <map>
#include <memory>

#include "perf/fem_bench_setup.hpp"
#include "perf/solver_threads.hpp"
#include "systems/assemble/assemble_system.hpp"

namespace {

using loom::Index;
using loom::SparseMatrix;
using loom::perf::FemBenchRun;
using loom::perf::Clock;
using loom::perf::seconds;
using loom::perf::set_threads;

// The tangent and residual at the mid-Newton iterate, one per size.
struct Problem {
  SparseMatrix K;
  Eigen::VectorXd r;
  Eigen::VectorXd b;  // -r
};

const Problem& problem_of(Index n_cells) {
  static std::map<Index, std::unique_ptr<Problem>> problems;
  auto& p = problems[n_cells];
  if (!p) {
    FemBenchRun run(n_cells);
    loom::assemble_system(run.ctx, loom::AssemblyMode::residual_and_tangent, run.materials, run.nodes, run.cells,
                          run.bc, run.quad, run.system);
    p = std::make_unique<Problem>(Problem{run.system.pattern.matrix, run.system.residual, -run.system.residual});
  }
  return *p;
}

template <class Solver>
void BM_LinearSolve(benchmark::State& state, void (*configure)(Solver&)) {
  const Index n_cells = Index(state.range(0));
  const int solver_threads = int(state.range(1));
  set_threads("openblas_set_num_threads", solver_threads);
  set_threads("omp_set_num_threads", solver_threads);
  const Problem& p = problem_of(n_cells);
  Solver solver;
  if (configure) configure(solver);
  solver.analyzePattern(p.K);
  if constexpr (requires { solver.cholmod(); }) {
    state.counters["lnz"] = solver.cholmod().lnz;
    state.counters["gflop"] = 1e-9 * solver.cholmod().fl;
  }
  Eigen::VectorXd x;
  double t_factorize = 0, t_solve = 0;
  bool failed = false;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    solver.factorize(p.K);
    failed |= solver.info() != Eigen::Success;
    const auto t1 = Clock::now();
    x = solver.solve(p.b);
    const auto t2 = Clock::now();
    t_factorize += seconds(t0, t1), t_solve += seconds(t1, t2);
    state.SetIterationTime(seconds(t0, t2));
  }
  if (failed) {
    state.SkipWithError("factorization failed");
    return;
  }
  using benchmark::Counter;
  state.counters["factorize_ms"] = Counter(1e3 * t_factorize, Counter::kAvgIterations);
  state.counters["solve_ms"] = Counter(1e3 * t_solve, Counter::kAvgIterations);
  state.counters["relative_residual"] = (p.K * x + p.r).norm() / p.r.norm();
  state.counters["dofs"] = double(p.K.rows());
}

void no_refinement(Eigen::UmfPackLU<SparseMatrix>& s) { s.umfpackControl()(UMFPACK_IRSTEP) = 0; }
template <class Solver>
void metis_only(Solver& s) {
  s.cholmod().nmethods = 1;
  s.cholmod().method[0].ordering = CHOLMOD_METIS;
}

// Cells 10^3, 10^4, 10^5 (the ctest smoke run filters /1000/), solver threads 1 and 2.
void sizes(benchmark::internal::Benchmark* b) {
  b->RangeMultiplier(10)->Ranges({{1000, 100000}, {1, 2}})->UseManualTime()->Unit(benchmark::kMillisecond);
}

using Supernodal = Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>;
using Simplicial = Eigen::CholmodSimplicialLLT<SparseMatrix, Eigen::Lower>;
using Automatic = Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower>;
using Umfpack = Eigen::UmfPackLU<SparseMatrix>;
using EigenLdlt = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower>;

template <class Solver>
void add(const char* name, void (*configure)(Solver&) = nullptr) {
  sizes(benchmark::RegisterBenchmark(
      name, [configure](benchmark::State& state) { BM_LinearSolve<Solver>(state, configure); }));
}

}  // namespace

int main(int argc, char** argv) {
  add<Supernodal>("BM_LinearSolve/cholmod_supernodal");
  add<Simplicial>("BM_LinearSolve/cholmod_simplicial");
  add<Automatic>("BM_LinearSolve/cholmod_auto");
  add<Supernodal>("BM_LinearSolve/cholmod_supernodal_metis", &metis_only<Supernodal>);
  add<Umfpack>("BM_LinearSolve/umfpack");
  add<Umfpack>("BM_LinearSolve/umfpack_no_refine", &no_refinement);
  add<EigenLdlt>("BM_LinearSolve/eigen_ldlt");
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
