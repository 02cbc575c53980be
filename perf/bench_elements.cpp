// Cost of the three element formulations (seed 000 §5.3) on Cook's membrane, Neo-Hooke, nu = 0.4999, the
// 'right' pattern (the set-up of scenes/cooks_membrane_nearly_incompressible.toml), built with FemModel:
//  - newton_iteration/<element>/<n>: one Newton iteration at the loaded undeformed state: assemble the
//    residual and tangent, factorize, back-substitute (the symbolic analysis is done once before timing, as
//    in a run, where the pattern never changes). The back-end is the one a run picks: CHOLMOD for p1 and
//    tri6 (their tangent is SPD here), UMFPACK for p1p1_uphi (non-symmetric tangent);
//    tri6_umfpack forces UMFPACK on tri6 to separate the element from the back-end.
//    Counters: assemble / factorize / solve in ms per iteration, dofs.
//  - load_step/<element>/<n>: the whole static load step (Newton from u = 0 to convergence, 3-4
//    iterations), the unit the seed's "calculation time per time step" compares.
//  - assemble/<element>/<n>/<threads>: the element kernels alone (assemble_system with tangent); items =
//    cells, so the figure reads as cells per second.
// Arguments <n>/<threads>: n = 16 and 32 (the seed's 16x16 and 32x32 meshes), n = 64 for the kernels; oneTBB
// threads 1 (serial) and all cores. Usage (figures in docs/constrained_block/README.md):
//   OPENBLAS_NUM_THREADS=1 build/perf/bench_elements --benchmark_filter='/1/' --benchmark_repetitions=10
#include <benchmark/benchmark.h>

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>

#include <chrono>
#include <initializer_list>
#include <memory>
#include <string>

#include "engine/drivers/newton.hpp"
#include "engine/methods/model/fem_model.hpp"
#include "engine/methods/recipes/fem_newton_problem.hpp"
#include "engine/scene/scene_loader.hpp"
#include "engine/timing/timers.hpp"
#include "systems/assemble/assemble_system.hpp"
#include "systems/loads/apply_boundary_conditions.hpp"
#include "systems/solve/solve_linear_step.hpp"
#include "systems/update/update_iterate.hpp"

namespace loom {
namespace {

SceneSpec cooks_scene(const std::string& element, int n, const std::string& linear = "auto") {
  const std::string text =
      "[scene]\nname = \"bench-elements\"\n[time]\ndt = 1.0\nsteps = 1\n"
      "[solver]\nlinear = \"" + linear + "\"\n"
      "[[material]]\nname = \"rubber\"\nmodel = \"neo_hooke\"\nE = 70.0\nnu = 0.4999\n"
      "[[body]]\nname = \"membrane\"\nmaterial = \"rubber\"\nelement = \"" + element + "\"\n"
      "mesh = { generator = \"cooks_membrane\", divisions = [" + std::to_string(n) + ", " + std::to_string(n) + "], pattern = \"right\" }\n"
      "[[boundary]]\nname = \"clamped\"\nregion = { box = [[0.0, 0.0], [0.0, 44.0]] }\ndisplacement = { x = 0.0, y = 0.0 }\n"
      "[[boundary]]\nname = \"loaded\"\nregion = { box = [[48.0, 44.0], [48.0, 60.0]] }\ntraction = { y = 0.0625 }\n"
      "[output]\nevery = 0\n";
  return load_scene_text(text, "bench_elements.toml", {});
}

// The model at the start of step 1: loads applied, u = u_n = 0.
struct LoadedModel {
  FemModel m;
  StepContext ctx;
  LinearSolve solver;
  Timers timers;

  LoadedModel(const std::string& element, int n, const std::string& linear)
      : m(cooks_scene(element, n, linear)), solver(m.linear_solver) {
    ctx.scene = &m.scene;
    ctx.step = 1, ctx.t = 1.0, ctx.dt = 1.0;
    apply_boundary_conditions(ctx, m.nodes, m.cells, m.materials, m.bc);
    reset_iterate(m.nodes);
  }
  Index cells() const {
    Index c = 0;
    for (const auto& b : m.cells) c += b.size();
    return c;
  }
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Caps oneTBB at the benchmark's second argument (1: serial; the factorizations also use BLAS threads, set
// by OPENBLAS_NUM_THREADS).
oneapi::tbb::global_control thread_limit(const benchmark::State& state) {
  return oneapi::tbb::global_control(oneapi::tbb::global_control::max_allowed_parallelism, std::size_t(state.range(1)));
}

void newton_iteration(benchmark::State& state, std::string element, std::string linear) {
  const auto limit = thread_limit(state);
  LoadedModel model(element, int(state.range(0)), linear);
  auto& m = model.m;
  auto iterate = [&] {
    assemble_system(model.ctx, AssemblyMode::residual_and_tangent, m.materials, m.nodes, m.cells, m.bc, m.quad, m.system);
    return solve_linear_step(m.nodes, m.bc, model.solver, m.system, model.timers) == LinearSolveStatus::ok;
  };
  if (!iterate()) return state.SkipWithError("singular tangent");  // also the symbolic analysis
  double assemble = 0.0, factorize = 0.0, solve = 0.0;
  for (auto _ : state) {
    auto t0 = std::chrono::steady_clock::now();
    assemble_system(model.ctx, AssemblyMode::residual_and_tangent, m.materials, m.nodes, m.cells, m.bc, m.quad, m.system);
    assemble += seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    const bool ok = model.solver.factorize(m.system.pattern);
    factorize += seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    Eigen::VectorXd rhs = -m.system.residual;
    const bool solved = ok && model.solver.solve(rhs, m.system.increment);
    solve += seconds_since(t0);
    if (!solved) return state.SkipWithError("solve failed");
    benchmark::DoNotOptimize(m.system.increment.data());
  }
  const double per = 1e3 / double(state.iterations());
  state.counters["assemble_ms"] = assemble * per;
  state.counters["factorize_ms"] = factorize * per;
  state.counters["solve_ms"] = solve * per;
  state.counters["dofs"] = double(m.system.dofs.n_free);
  state.SetLabel(model.solver.backend());
}

void load_step(benchmark::State& state, std::string element) {
  const auto limit = thread_limit(state);
  LoadedModel model(element, int(state.range(0)), "auto");
  auto& m = model.m;
  int iterations = 0;
  for (auto _ : state) {
    reset_iterate(m.nodes);  // u = u_n = 0 (nothing is committed)
    FemNewtonProblem problem(model.ctx, m.materials, m.cells, m.bc, m.nodes, m.quad, m.system, model.solver, model.timers);
    const NewtonReport report = solve_newton(problem, newton_settings_of(m.scene.solver), model.timers);
    if (!report.converged) return state.SkipWithError(report.failure.c_str());
    iterations = report.iterations;
  }
  state.counters["newton_iterations"] = iterations;
  state.counters["dofs"] = double(m.system.dofs.n_free);
  state.SetLabel(model.solver.backend());
}

void assemble(benchmark::State& state, std::string element) {
  const auto limit = thread_limit(state);
  LoadedModel model(element, int(state.range(0)), "auto");
  auto& m = model.m;
  for (auto _ : state) {
    const AssemblyResult r =
        assemble_system(model.ctx, AssemblyMode::residual_and_tangent, m.materials, m.nodes, m.cells, m.bc, m.quad, m.system);
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(state.iterations() * model.cells());
  state.counters["cells"] = double(model.cells());
}

const int kAllThreads = int(oneapi::tbb::info::default_concurrency());

// Arguments {n, threads}: n = 16, 32 (64 for the kernels), threads 1 and all cores.
void sizes(benchmark::internal::Benchmark* b, std::initializer_list<int> ns) {
  for (int n : ns) {
    b->Args({n, 1});
    if (kAllThreads > 1) b->Args({n, kAllThreads});
  }
  b->UseRealTime();
}

const bool registered = [] {
  for (const char* e : {"p1", "tri6", "p1p1_uphi"})
    sizes(benchmark::RegisterBenchmark((std::string("newton_iteration/") + e).c_str(), newton_iteration, std::string(e), std::string("auto"))
              ->Unit(benchmark::kMillisecond),
          {16, 32});
  sizes(benchmark::RegisterBenchmark("newton_iteration/tri6_umfpack", newton_iteration, std::string("tri6"), std::string("umfpack"))
            ->Unit(benchmark::kMillisecond),
        {16, 32});
  for (const char* e : {"tri6", "p1p1_uphi"})
    sizes(benchmark::RegisterBenchmark((std::string("load_step/") + e).c_str(), load_step, std::string(e))->Unit(benchmark::kMillisecond),
          {16, 32});
  for (const char* e : {"p1", "tri6", "p1p1_uphi"})
    sizes(benchmark::RegisterBenchmark((std::string("assemble/") + e).c_str(), assemble, std::string(e))->Unit(benchmark::kMicrosecond),
          {16, 64});
  return true;
}();

}  // namespace
}  // namespace loom

BENCHMARK_MAIN();
