// The linear solvers on 3D elasticity systems (issue: "direct solvers fill in quickly in 3D"): the stiffness
// of a unit cube of linear elastic tetrahedra (Kuhn box, E = 1, nu = 0.3 or 0.49; tet4 or tet10 from the kernels of
// systems/assemble/elements), clamped at z = 0 and loaded by its weight, from 10^4 to 10^6 dofs. The cube is
// the worst case of fill for a given dof count (a column or a plate fills less). Arguments:
// /<nodes per side - 1>/<element: 4 or 10>/<solver threads>/<1000 nu>; the tet4 mesh of n and the tet10 mesh of
// n/2 have the same nodes. The direct solvers' work does not depend on nu (they run at 0.3); the iterations do.
//
//   cholmod          the engine's back-end (engine/linalg/linear_solver.cpp: supernodal LL^T)
//   umfpack          the engine's general LU
//   cg_ic            Eigen's ConjugateGradient with its IncompleteCholesky preconditioner (AMD ordering,
//                    fill by its default dual threshold), relative residual 1e-8
//   cg_jacobi        the same with the diagonal preconditioner
//   petsc_gamg       solver.linear = "petsc" as a run uses it (engine/linalg/petsc_solver.cpp): CG + GAMG with the
//                    rigid-body modes, relative residual 1e-8 (unpreconditioned); built with PETSc only. Also
//                    resetup_s / resolve_s / reiterations: a second set-up of the same values (GAMG keeps its
//                    interpolation, as between Newton iterations) and its solve
//
// Counters: analyze_s, factorize_s (the preconditioner's set-up for cg_*), solve_s, iterations (cg_*),
// factor_entries and gflop (what the back-end reports; CHOLMOD predicts both at analysis), rss_mb (resident
// set growth across analyze + factorize: the factor's memory), relative_residual = |K x - b| / |b|.
// `analysis_only` runs CHOLMOD's analysis alone: the factor size and flops of sizes too large to factorize.
//
//   build/perf/bench_linear_solver_3d --benchmark_filter='^cholmod/(14|30|46)/4/'   (docs/solvers_3d.md: all)
#include <benchmark/benchmark.h>

#include <Eigen/IterativeLinearSolvers>
#include <chrono>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "engine/linalg/dof_map.hpp"
#include "engine/linalg/linear_solver.hpp"
#include "engine/linalg/sparse_pattern.hpp"
#include "engine/mesh/tet_generators.hpp"
#include "perf/solver_threads.hpp"
#include "systems/assemble/elements/displacement_point.hpp"
#include "systems/assemble/elements/tet10.hpp"
#include "systems/assemble/elements/tet4.hpp"
#include "systems/assemble/materials/linear_elastic.hpp"

namespace {

using loom::Index;
using loom::SparseMatrix;
using loom::perf::Clock;
using loom::perf::seconds;

struct Problem {
  SparseMatrix K;  // free dofs only
  Eigen::VectorXd b;
  loom::SolveStructure structure;  // dofs and node coordinates (petsc_gamg's near-null space)
};

// Resident set size in MB (Linux /proc/self/statm, pages of 4 KiB).
double rss_mb() {
  std::ifstream statm("/proc/self/statm");
  double size = 0, resident = 0;
  statm >> size >> resident;
  return resident * 4096.0 / 1048576.0;
}

template <int NEN>
void assemble(const std::vector<loom::Vec3>& X, const std::vector<Index>& cells, const loom::DofMap& dofs,
              const loom::CellScatter& scatter, double nu, SparseMatrix& K, Eigen::VectorXd& b) {
  const double E = 1.0;
  const loom::LinearElastic material{E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))};
  const loom::NodalVectors<NEN, 3> du = loom::NodalVectors<NEN, 3>::Zero();
  double* values = K.valuePtr();
  for (std::size_t c = 0; c < cells.size() / NEN; ++c) {
    Eigen::Matrix<double, NEN, 3> x;
    for (int a = 0; a < NEN; ++a) x.row(a) = X[std::size_t(cells[NEN * c + std::size_t(a)])].transpose();
    loom::ElementVector<NEN, 3> r = loom::ElementVector<NEN, 3>::Zero();
    loom::ElementMatrix<NEN, 3> Ke = loom::ElementMatrix<NEN, 3>::Zero();
    Eigen::Matrix<double, NEN, 1> weight;  // int N^A dV: the weight of a unit body force
    loom::Mat3 F;
    if constexpr (NEN == 4) {
      loom::Tet4Gradients dN;
      const double V = loom::tet4_gradients(x, dN);
      loom::add_displacement_point<4, 3>(material, du, dN, V, loom::Mat3::Identity(), F, r, &Ke);
      weight.setConstant(V / 4);
    } else {
      weight.setZero();
      for (const auto& l : loom::kTet4Rule4) {
        loom::Tet10Gradients dN;
        const double dV = loom::tet10_gradients(x, l, dN) / 24.0;
        loom::add_displacement_point<10, 3>(material, du, dN, dV, loom::Mat3::Identity(), F, r, &Ke);
        weight += dV * loom::tet10_values(l);
      }
    }
    for (int i = 0; i < 3 * NEN; ++i) {
      const Index gi = scatter.cell_dof(Index(c), i);
      if (dofs.kind[std::size_t(gi)] != loom::DofKind::free) continue;
      if (i % 3 == 2) b[dofs.equation[std::size_t(gi)]] -= weight[i / 3];
      for (int j = 0; j < 3 * NEN; ++j) {
        const Index slot = scatter.matrix_slot(Index(c), i, j);
        if (slot != loom::kNoIndex) values[slot] += Ke(i, j);
      }
    }
  }
}

const Problem& problem_of(int n, int nen, int nu_permille = 300) {
  static std::map<std::tuple<int, int, int>, std::unique_ptr<Problem>> problems;
  auto& p = problems[{n, nen, nu_permille}];
  if (p) return *p;
  loom::BoxSpec spec;
  spec.nx = spec.ny = spec.nz = nen == 4 ? n : n / 2;
  const loom::TetMeshData tets = loom::generate_box(spec);
  std::vector<loom::Vec3> X = tets.X;
  std::vector<Index> connectivity = tets.tets;
  if (nen == 10) {
    loom::Tet10MeshData q = loom::tet10_from_tet4(tets);
    X = std::move(q.X), connectivity = std::move(q.cells);
  }
  loom::Cells cells;
  cells.stride = nen;
  cells.nodes.values() = connectivity;
  cells.body.values().assign(connectivity.size() / std::size_t(nen), 0);
  std::vector<loom::DofKind> kinds(3 * X.size(), loom::DofKind::free);
  for (std::size_t i = 0; i < X.size(); ++i)
    if (X[i].z() == 0.0)
      for (int k = 0; k < 3; ++k) kinds[3 * i + std::size_t(k)] = loom::DofKind::prescribed;
  loom::DofMap dofs;
  dofs.build(3, kinds);
  loom::SparsePattern pattern;
  loom::build_pattern({&cells}, dofs, pattern);
  loom::CellScatter scatter;
  loom::build_scatter(cells, dofs, pattern, scatter);
  p = std::make_unique<Problem>();
  p->K = pattern.matrix;
  p->b = Eigen::VectorXd::Zero(dofs.n_free);
  const double nu = 1e-3 * nu_permille;
  if (nen == 4) assemble<4>(X, connectivity, dofs, scatter, nu, p->K, p->b);
  else assemble<10>(X, connectivity, dofs, scatter, nu, p->K, p->b);
  p->structure.dim = 3;
  p->structure.dofs = dofs;
  for (const loom::Vec3& x : X) p->structure.coordinates.insert(p->structure.coordinates.end(), {x.x(), x.y(), x.z()});
  return *p;
}

void set_threads(int n) {
  loom::perf::set_threads("openblas_set_num_threads", n);
  loom::perf::set_threads("omp_set_num_threads", n);
}

void report(benchmark::State& state, const Problem& p, const Eigen::VectorXd& x) {
  state.counters["dofs"] = double(p.K.rows());
  state.counters["nnz_A"] = double(p.K.nonZeros());
  state.counters["relative_residual"] = (p.K * x - p.b).norm() / p.b.norm();
}

void BM_Direct(benchmark::State& state, bool cholmod) {
  const Problem& p = problem_of(int(state.range(0)), int(state.range(1)));
  set_threads(int(state.range(2)));
  Eigen::VectorXd x;
  for (auto _ : state) {
    auto solver = cholmod ? loom::make_cholmod_solver() : loom::make_umfpack_solver();
    const double rss0 = rss_mb();
    const auto t0 = Clock::now();
    solver->analyze(p.K);
    const auto t1 = Clock::now();
    if (!solver->factorize(p.K)) state.SkipWithError("factorisation failed");
    const auto t2 = Clock::now();
    const loom::LinearSolver::FactorSize size = solver->factor_size();
    state.counters["rss_mb"] = rss_mb() - rss0;
    solver->solve(p.b, x);
    const auto t3 = Clock::now();
    state.SetIterationTime(seconds(t0, t3));
    state.counters["analyze_s"] = seconds(t0, t1), state.counters["factorize_s"] = seconds(t1, t2);
    state.counters["solve_s"] = seconds(t2, t3);
    state.counters["factor_entries"] = size.entries, state.counters["gflop"] = 1e-9 * size.flops;
  }
  report(state, p, x);
}

void BM_AnalysisOnly(benchmark::State& state) {
  const Problem& p = problem_of(int(state.range(0)), int(state.range(1)));
  for (auto _ : state) {
    auto solver = loom::make_cholmod_solver();
    const auto t0 = Clock::now();
    solver->analyze(p.K);
    state.SetIterationTime(seconds(t0, Clock::now()));
    const loom::LinearSolver::FactorSize size = solver->factor_size();
    state.counters["factor_entries"] = size.entries, state.counters["gflop"] = 1e-9 * size.flops;
    state.counters["factor_gb"] = 8e-9 * size.entries;
  }
  state.counters["dofs"] = double(p.K.rows());
}

template <class Preconditioner>
void BM_ConjugateGradient(benchmark::State& state) {
  const Problem& p = problem_of(int(state.range(0)), int(state.range(1)), int(state.range(3)));
  set_threads(int(state.range(2)));
  Eigen::VectorXd x;
  for (auto _ : state) {
    Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper, Preconditioner> cg;
    cg.setTolerance(1e-8);
    cg.setMaxIterations(20000);
    const double rss0 = rss_mb();
    const auto t0 = Clock::now();
    cg.compute(p.K);
    const auto t1 = Clock::now();
    state.counters["rss_mb"] = rss_mb() - rss0;
    x = cg.solve(p.b);
    const auto t2 = Clock::now();
    if (cg.info() != Eigen::Success) state.SkipWithError("no convergence");
    state.SetIterationTime(seconds(t0, t2));
    state.counters["factorize_s"] = seconds(t0, t1), state.counters["solve_s"] = seconds(t1, t2);
    state.counters["iterations"] = double(cg.iterations());
  }
  report(state, p, x);
}

void BM_Petsc(benchmark::State& state) {
  const Problem& p = problem_of(int(state.range(0)), int(state.range(1)), int(state.range(3)));
  Eigen::VectorXd x;
  for (auto _ : state) {
    auto solver = loom::make_petsc_solver(1e-8, "");
    solver->set_structure(p.structure);
    const double rss0 = rss_mb();
    const auto t0 = Clock::now();
    solver->analyze(p.K);
    const auto t1 = Clock::now();
    const bool set_up = solver->factorize(p.K);
    const auto t2 = Clock::now();
    if (!set_up || !solver->solve(p.b, x)) {  // no second solve on a failed one
      state.SkipWithError(solver->failure_reason().c_str());
      break;
    }
    const auto t3 = Clock::now();
    state.counters["rss_mb"] = rss_mb() - rss0;
    const long long first = solver->iterations();
    solver->factorize(p.K);
    const auto t4 = Clock::now();
    solver->solve(p.b, x);
    const auto t5 = Clock::now();
    state.SetIterationTime(seconds(t0, t3));
    state.counters["analyze_s"] = seconds(t0, t1), state.counters["factorize_s"] = seconds(t1, t2);
    state.counters["solve_s"] = seconds(t2, t3), state.counters["iterations"] = double(first);
    state.counters["resetup_s"] = seconds(t3, t4), state.counters["resolve_s"] = seconds(t4, t5);
    state.counters["reiterations"] = double(solver->iterations() - first);
  }
  report(state, p, x);
}

// n = 14, 30, 46, 68: 9.5e3, 9.0e4, 3.1e5, 9.7e5 free dofs (tet4 of n, tet10 of n / 2).
void sizes(benchmark::internal::Benchmark* b, std::initializer_list<int> ns, std::initializer_list<int> nus = {300}) {
  for (int n : ns)
    for (int nen : {4, 10})
      for (int threads : {1, 2})
        for (int nu : nus) b->Args({n, nen, threads, nu});
  b->UseManualTime()->Unit(benchmark::kSecond)->Iterations(1);
}

}  // namespace

int main(int argc, char** argv) {
  sizes(benchmark::RegisterBenchmark("cholmod", [](benchmark::State& s) { BM_Direct(s, true); }), {14, 30, 46});
  sizes(benchmark::RegisterBenchmark("umfpack", [](benchmark::State& s) { BM_Direct(s, false); }), {14, 30});
  sizes(benchmark::RegisterBenchmark("cg_ic", BM_ConjugateGradient<Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::AMDOrdering<int>>>),
        {14, 30, 46, 68}, {300, 490});
  sizes(benchmark::RegisterBenchmark("cg_jacobi", BM_ConjugateGradient<Eigen::DiagonalPreconditioner<double>>), {14, 30, 46, 68},
        {300, 490});
  if (loom::petsc_solver_problem().empty())  // one thread: PETSc runs on one core per process
    for (int n : {14, 30, 46, 68})
      for (int nen : {4, 10})
        for (int nu : {300, 490})
          benchmark::RegisterBenchmark("petsc_gamg", BM_Petsc)->Args({n, nen, 1, nu})->UseManualTime()->Unit(benchmark::kSecond)->Iterations(1);
  benchmark::RegisterBenchmark("analysis_only", BM_AnalysisOnly)
      ->Args({46, 4, 1})->Args({46, 10, 1})->Args({68, 4, 1})->Args({68, 10, 1})
      ->UseManualTime()->Unit(benchmark::kSecond)->Iterations(1);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
