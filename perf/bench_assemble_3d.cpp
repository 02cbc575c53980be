// 3D assembly and Newton iteration of the fem on tetrahedra: a Neo-Hooke box [0,1]^3 of n x n x n cubes cut into
// 6 n^3 Kuhn tetrahedra (tet4, element p1; or tet10), clamped at z = 0 and pulled at z = 1 by a traction, at the
// iterate of one Newton update from u = 0 (a genuine mid-Newton state: the tangent stays positive definite).
//   BM_Assemble3d/<mode>/<n>/<nen>/<threads>: assemble_system<3> (items_per_second: cells per second);
//   BM_NewtonIteration3d/<n>/<nen>/<threads>: one Newton iteration as FemRun does it -- assemble with tangent,
//     factorise and solve (CHOLMOD, a new numeric factorisation; the symbolic one is reused), update -- with the
//     counters assemble_s, solve_s and non_solver_share = (assemble + update) / iteration.
// Sizes: n = 8, 16, 26 (3072, 24576, 105456 tet4 cells); tet10 n = 8, 16 (the 10^5-cell tet10 system needs
// 1.3e6 dofs: beyond CHOLMOD on this machine, docs/solvers_3d.md).
//
//   build/perf/bench_assemble_3d --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <oneapi/tbb/global_control.h>

#include <chrono>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_solver.hpp"
#include "engine/methods/model/fem_model.hpp"
#include "engine/scene/scene_loader.hpp"
#include "engine/timing/timers.hpp"
#include "systems/assemble/assemble_system.hpp"
#include "systems/loads/apply_boundary_conditions.hpp"
#include "systems/solve/solve_linear_step.hpp"
#include "systems/update/update_iterate.hpp"

namespace {

using loom::AssemblyMode;
using loom::Index;

std::string box_scene(int n, int nen) {
  std::ostringstream s;
  s << "[scene]\nname = \"perf-box-3d\"\nmethod = \"fem\"\ndimension = 3\n"
    << "[time]\nintegrator = \"static\"\ndt = 1.0\nsteps = 1\n"
    << "[[material]]\nname = \"rubber\"\nmodel = \"neo_hooke\"\nE = 250.0\nnu = 0.3\n"
    << "[[body]]\nname = \"box\"\nmaterial = \"rubber\"\nelement = \"" << (nen == 10 ? "tet10" : "p1") << "\"\n"
    << "mesh = { generator = \"box\", size = [1.0, 1.0, 1.0], divisions = [" << n << ", " << n << ", " << n << "] }\n"
    << "[[boundary]]\nname = \"base\"\nregion = { box = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0]] }\ndisplacement = { x = 0.0, y = 0.0, z = 0.0 }\n"
    << "[[boundary]]\nname = \"top\"\nregion = { box = [[0.0, 0.0, 1.0], [1.0, 1.0, 1.0]] }\ntraction = { x = 5.0, z = 10.0 }\n"
    << "[output]\nevery = 0\n";
  return s.str();
}

struct Run : loom::FemModelT<3> {
  loom::StepContext ctx;
  loom::LinearSolve solver{loom::LinearSolverKind::cholmod};
  loom::Timers timers;
  Run(int n, int nen) : loom::FemModelT<3>(loom::load_scene_text(box_scene(n, nen), "perf/box_3d")) {
    ctx.scene = &scene;
    ctx.step = 1, ctx.dt = 1.0, ctx.t = 1.0, ctx.step_end = true;
    loom::apply_boundary_conditions(ctx, nodes, cells, materials, bc);
    iterate();  // one Newton update from u = 0
  }
  // One Newton iteration; returns (assemble, solve, update) seconds.
  std::array<double, 3> iterate() {
    using clock = std::chrono::steady_clock;
    const auto t0 = clock::now();
    if (loom::assemble_system(ctx, AssemblyMode::residual_and_tangent, materials, nodes, cells, bc, quad, system).inverted_cells != 0)
      throw std::runtime_error("inverted cells");
    const auto t1 = clock::now();
    if (loom::solve_linear_step(nodes, bc, solver, system, timers) != loom::LinearSolveStatus::ok) throw std::runtime_error("singular");
    const auto t2 = clock::now();
    return {std::chrono::duration<double>(t1 - t0).count(), std::chrono::duration<double>(t2 - t1).count(), 0.0};
  }
  Index n_cells() const { return cells[0].size(); }
};

Run& run_of(int n, int nen) {
  static std::map<std::pair<int, int>, std::unique_ptr<Run>> runs;
  auto& r = runs[{n, nen}];
  if (!r) r = std::make_unique<Run>(n, nen);
  return *r;
}

void BM_Assemble3d(benchmark::State& state, AssemblyMode mode) {
  const int n = int(state.range(0)), nen = int(state.range(1)), threads = int(state.range(2));
  oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  Run& run = run_of(n, nen);
  for (auto _ : state) {
    benchmark::DoNotOptimize(loom::assemble_system(run.ctx, mode, run.materials, run.nodes, run.cells, run.bc, run.quad, run.system));
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * run.n_cells());
  state.counters["cells"] = double(run.n_cells());
  state.counters["dofs"] = double(run.system.dofs.n_free);
}

void BM_NewtonIteration3d(benchmark::State& state) {
  const int n = int(state.range(0)), nen = int(state.range(1)), threads = int(state.range(2));
  oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  Run& run = run_of(n, nen);
  double assemble = 0, solve = 0, update = 0;
  for (auto _ : state) {
    const auto saved = run.nodes.u.values();  // every iteration from the same iterate
    auto t = run.iterate();
    const auto u0 = std::chrono::steady_clock::now();
    loom::update_iterate(1.0, run.system, run.nodes);
    update += std::chrono::duration<double>(std::chrono::steady_clock::now() - u0).count();
    assemble += t[0], solve += t[1];
    state.PauseTiming();
    run.nodes.u.values() = saved;
    state.ResumeTiming();
  }
  const double it = double(state.iterations());
  state.counters["cells"] = double(run.n_cells());
  state.counters["dofs"] = double(run.system.dofs.n_free);
  state.counters["assemble_s"] = assemble / it;
  state.counters["solve_s"] = solve / it;
  state.counters["non_solver_share"] = (assemble + update) / (assemble + solve + update);
}

BENCHMARK_CAPTURE(BM_Assemble3d, residual, AssemblyMode::residual)
    ->ArgsProduct({{8, 16, 26}, {4}, {1, 2}})
    ->ArgsProduct({{8, 16}, {10}, {1, 2}})
    ->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Assemble3d, tangent, AssemblyMode::residual_and_tangent)
    ->ArgsProduct({{8, 16, 26}, {4}, {1, 2}})
    ->ArgsProduct({{8, 16}, {10}, {1, 2}})
    ->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NewtonIteration3d)->ArgsProduct({{16, 26}, {4}, {2}})->Args({8, 10, 2})->Args({16, 10, 2})->UseRealTime()->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
