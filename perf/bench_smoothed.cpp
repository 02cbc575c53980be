// The edge-based smoothed mixed element es_up (seed 001, Reinold & Meschke 2021) against the P1 u-phi
// element p1p1_uphi and the element-integrated fem_up, on Cook's membrane (finite strain, plane strain):
//
//  BM_SmoothedAssemble/<element>/<divisions>/<threads>: assemble_system (residual + tangent) with the run's
//    integration domains (`&model.edges`), 1 and 2 oneTBB threads. items_per_second: edges per second for
//    es_up (interior and boundary edges together), cells per second for p1p1_uphi; counters edges, cells,
//    edge_colours (summed over the interior and boundary stores), cell_colours.
//  BM_SmoothedResidual/es_up/<divisions>/<threads>: the same with the residual alone (a line search's trial
//    point needs no tangent).
//  BM_Pattern/<element>/<divisions>: not timed; the sparsity of the Newton system the element couples,
//    counters nnz_per_row = pattern.matrix.nonZeros() / rows, nnz, rows (es_up, fem_up, p1p1_uphi).
//  BM_SmoothedNewton/<element>/<divisions>/<tbb threads>/<solver threads>: one full Newton iteration
//    (assemble with tangent, factorize, back-substitute, update: FemNewtonProblem's calls) with UMFPACK (both
//    tangents are non-symmetric), at equal dofs: both elements carry 3 dofs per node (u_x, u_y and p or phi)
//    on the same mesh. Counters as in bench_newton_step (ms per iteration).
//
// Mesh: the cooks_membrane generator, n x n divisions, pattern "right" (scenes/cooks_membrane_es.toml):
// 2 n^2 triangles, (n + 1)^2 nodes, about 3 n^2 edges. Materials, E = 250, nu = 0.4999: hencky_perzyna without
// tau0 (Hencky elastic, finite strain) for es_up and fem_up (alpha_stab = 0.5), neo_hooke for p1p1_uphi
// (alpha_s = K/10, the default), which does not take hencky_perzyna. Step 1 of a static run, left edge
// clamped, shear traction 6.25 on the right edge. The state is a mid-Newton iterate, as in
// fem_bench_setup.hpp: two full Newton updates from u = u_n = 0 (counter residual_ratio: |r| there over |r|
// at the start of the step), so the material is not at the identity.
//
//   build/perf/bench_smoothed --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <oneapi/tbb/global_control.h>

#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_solver.hpp"
#include "engine/methods/model/fem_model.hpp"
#include "engine/scene/scene_loader.hpp"
#include "engine/timing/timers.hpp"
#include "perf/newton_iteration_timing.hpp"
#include "perf/newton_iteration_timing.hpp"
#include "perf/solver_threads.hpp"
#include "systems/assemble/assemble_system.hpp"
#include "systems/loads/apply_boundary_conditions.hpp"
#include "systems/solve/solve_linear_step.hpp"
#include "systems/update/update_iterate.hpp"

namespace {

using loom::AssemblyMode;
using loom::Index;
using loom::perf::Clock;
using loom::perf::seconds;
using loom::perf::set_threads;

std::string scene_text(const std::string& element, int divisions) {
  const bool smoothed = element != "p1p1_uphi";
  std::ostringstream s;
  s << "[scene]\nname = \"perf-cooks-membrane-smoothed\"\nmethod = \"fem\"\n"
    << "[time]\nintegrator = \"static\"\ndt = 1.0\nsteps = 1\n"
    << "[[material]]\nname = \"m\"\nmodel = \"" << (smoothed ? "hencky_perzyna" : "neo_hooke") << "\"\nE = 250.0\nnu = 0.4999\n"
    << "[[body]]\nname = \"membrane\"\nmaterial = \"m\"\nelement = \"" << element << "\"\n"
    << (element == "es_up" || element == "fem_up" ? "alpha_stab = 0.5\n" : "")
    << "mesh = { generator = \"cooks_membrane\", divisions = [" << divisions << ", " << divisions << "], pattern = \"right\" }\n"
    << "[[boundary]]\nname = \"clamped\"\nregion = { box = [[0.0, 0.0], [0.0, 44.0]] }\ndisplacement = { x = 0.0, y = 0.0 }\n"
    << "[[boundary]]\nname = \"loaded\"\nregion = { box = [[48.0, 44.0], [48.0, 60.0]] }\ntraction = { y = 6.25 }\n"
    << "[output]\nevery = 0\n";
  return s.str();
}

// The stores of one run (FemModel) at step 1 of the static run. Not movable: ctx points at scene.
struct SmoothedBenchRun : loom::FemModel {
  loom::StepContext ctx;
  double residual_ratio = 0.0;  // |r| at the iterate / |r| at the start of the step

  SmoothedBenchRun(const std::string& element, int divisions, bool deformed)
      : loom::FemModel(loom::load_scene_text(scene_text(element, divisions), "perf/cooks_membrane_" + element)) {
    ctx.scene = &scene;
    ctx.step = 1, ctx.dt = scene.time.dt, ctx.t = ctx.dt, ctx.step_end = true;
    loom::apply_boundary_conditions(ctx, nodes, cells, materials, bc);
    if (deformed) deform();
  }
  SmoothedBenchRun(const SmoothedBenchRun&) = delete;
  SmoothedBenchRun& operator=(const SmoothedBenchRun&) = delete;

  std::vector<loom::Edges<2>>* domains() { return edges.empty() ? nullptr : &edges; }

  loom::AssemblyResult assemble(AssemblyMode mode) {
    return loom::assemble_system(ctx, mode, materials, nodes, cells, bc, quad, system, domains());
  }

  Index n_cells() const {
    Index n = 0;
    for (const auto& c : cells) n += c.size();
    return n;
  }
  Index n_edges() const {  // smoothing domains (es_*) or triangle domains (fem_*)
    Index n = 0;
    for (const auto& e : edges) n += e.size();
    return n;
  }

  // Two Newton iterations of step 1 from u = u_n = 0 (UMFPACK: the mixed tangents are non-symmetric).
  void deform() {
    loom::LinearSolve solver(loom::LinearSolverKind::umfpack);
    loom::Timers timers;
    double r0 = 0.0;
    for (int it = 0; it < 2; ++it) {
      if (assemble(AssemblyMode::residual_and_tangent).inverted_cells != 0 ||
          loom::solve_linear_step(nodes, bc, solver, system, timers) != loom::LinearSolveStatus::ok)
        throw std::runtime_error("set-up Newton iteration failed");
      if (it == 0) r0 = system.residual.norm();
      loom::update_iterate(1.0, system, nodes);
    }
    if (assemble(AssemblyMode::residual).inverted_cells != 0) throw std::runtime_error("inverted domains at the iterate");
    residual_ratio = system.residual.norm() / r0;
  }

  // The Newton unknowns (u and the third nodal dof, p or phi), to restore the iterate.
  struct Iterate {
    std::vector<loom::Vec2> u;
    std::vector<double> third;
  };
  Iterate save() const {
    Iterate s{{nodes.u.begin(), nodes.u.end()}, {}};
    if (nodes.p.used()) s.third.assign(nodes.p.begin(), nodes.p.end());
    if (nodes.phi.used()) s.third.assign(nodes.phi.begin(), nodes.phi.end());
    return s;
  }
  void restore(const Iterate& s) {
    std::copy(s.u.begin(), s.u.end(), nodes.u.begin());
    if (nodes.p.used()) std::copy(s.third.begin(), s.third.end(), nodes.p.begin());
    if (nodes.phi.used()) std::copy(s.third.begin(), s.third.end(), nodes.phi.begin());
  }
};

// One deformed run per element and size, shared by the benchmarks (set-up at 256 divisions takes seconds).
SmoothedBenchRun& run_of(const std::string& element, int divisions) {
  static std::map<std::pair<std::string, int>, std::unique_ptr<SmoothedBenchRun>> runs;
  auto& r = runs[{element, divisions}];
  if (!r) r = std::make_unique<SmoothedBenchRun>(element, divisions, true);
  return *r;
}

// ---- 1. Assembly rate ------------------------------------------------------------------------------------

void assembly_rate(benchmark::State& state, const char* element, AssemblyMode mode) {
  const int divisions = int(state.range(0)), threads = int(state.range(1));
  oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  SmoothedBenchRun& run = run_of(element, divisions);
  const bool smoothed = !run.edges.empty();
  Index inverted = 0;
  for (auto _ : state) {
    inverted += run.assemble(mode).inverted_cells;
    benchmark::DoNotOptimize(run.system.residual.data());
    benchmark::ClobberMemory();
  }
  if (inverted != 0) state.SkipWithError("inverted cells or domains: the kernel skipped work");
  state.SetItemsProcessed(state.iterations() * (smoothed ? run.n_edges() : run.n_cells()));
  state.counters["edges"] = double(run.n_edges());
  state.counters["cells"] = double(run.n_cells());
  state.counters["dofs"] = double(run.system.dofs.n_free);
  state.counters["residual_ratio"] = run.residual_ratio;
  Index edge_colours = 0;  // summed over the stores (interior, boundary), which are visited one after the other
  for (const auto& e : run.edges) edge_colours += e.stencil.n_colours();
  state.counters["edge_colours"] = double(edge_colours);
  state.counters["cell_colours"] = double(run.cells[0].n_colours());
}

void BM_SmoothedAssemble(benchmark::State& state, const char* element) { assembly_rate(state, element, AssemblyMode::residual_and_tangent); }
// The residual alone: what a line search's trial point costs if it is assembled without the tangent.
void BM_SmoothedResidual(benchmark::State& state, const char* element) { assembly_rate(state, element, AssemblyMode::residual); }

// Divisions 16 .. 256 (the ctest smoke run filters /16/), threads 1 and 2.
void assemble_sizes(benchmark::internal::Benchmark* b) {
  for (int n : {16, 32, 64, 128, 256})
    for (int threads : {1, 2}) b->Args({n, threads});
  b->UseRealTime()->Unit(benchmark::kMicrosecond);
}

BENCHMARK_CAPTURE(BM_SmoothedAssemble, es_up, "es_up")->Apply(assemble_sizes);
BENCHMARK_CAPTURE(BM_SmoothedAssemble, p1p1_uphi, "p1p1_uphi")->Apply(assemble_sizes);
BENCHMARK_CAPTURE(BM_SmoothedResidual, es_up, "es_up")->Apply(assemble_sizes);

// ---- 2. Non-zeros per row --------------------------------------------------------------------------------

void BM_Pattern(benchmark::State& state, const char* element) {
  const SmoothedBenchRun run(element, int(state.range(0)), false);  // the pattern does not depend on the state
  const auto& A = run.system.pattern.matrix;
  for (auto _ : state) benchmark::DoNotOptimize(A.nonZeros());
  state.counters["nnz_per_row"] = double(A.nonZeros()) / double(A.rows());
  state.counters["nnz"] = double(A.nonZeros());
  state.counters["rows"] = double(A.rows());
  state.counters["edges"] = double(run.n_edges());
  state.counters["cells"] = double(run.n_cells());
}

void pattern_sizes(benchmark::internal::Benchmark* b) {
  for (int n : {16, 64, 256}) b->Arg(n);
  b->Iterations(1);
}

BENCHMARK_CAPTURE(BM_Pattern, es_up, "es_up")->Apply(pattern_sizes);
BENCHMARK_CAPTURE(BM_Pattern, fem_up, "fem_up")->Apply(pattern_sizes);
BENCHMARK_CAPTURE(BM_Pattern, p1p1_uphi, "p1p1_uphi")->Apply(pattern_sizes);

// ---- 3. One Newton iteration at equal dofs ---------------------------------------------------------------

void BM_SmoothedNewton(benchmark::State& state, const char* element) {
  const int divisions = int(state.range(0));
  const int threads = int(state.range(1)), solver_threads = int(state.range(2));
  oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  set_threads("openblas_set_num_threads", solver_threads);
  set_threads("omp_set_num_threads", solver_threads);

  SmoothedBenchRun& run = run_of(element, divisions);
  loom::LinearSolve solver(loom::LinearSolverKind::umfpack);
  const auto start = run.save();
  struct Restore {  // leaves the shared run at its mid-Newton iterate for the next benchmark
    std::function<void()> f;
    ~Restore() { f(); }
  } restore_at_exit{[&] { run.restore(start); }};

  auto assemble = [&] { return run.assemble(AssemblyMode::residual_and_tangent).inverted_cells; };
  if (!loom::perf::time_newton_iterations(state, [&] { run.restore(start); }, assemble, run.nodes, run.bc, solver, run.system)) return;
  state.counters["residual_ratio"] = run.residual_ratio;
}

// Divisions 16, 57, 182: about 10^3, 10^4, 10^5 dofs (3 (n + 1)^2 less the clamped u); the smoke run filters
// /16/. Threads tbb/solver: 1/1 (serial reference) and 2/2 (what a loom run gets on this machine).
void newton_sizes(benchmark::internal::Benchmark* b) {
  for (int n : {16, 57, 182})
    for (auto [threads, solver_threads] : {std::pair{1, 1}, std::pair{2, 2}}) b->Args({n, threads, solver_threads});
  b->UseManualTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK_CAPTURE(BM_SmoothedNewton, es_up, "es_up")->Apply(newton_sizes);
BENCHMARK_CAPTURE(BM_SmoothedNewton, p1p1_uphi, "p1p1_uphi")->Apply(newton_sizes);

}  // namespace

BENCHMARK_MAIN();
