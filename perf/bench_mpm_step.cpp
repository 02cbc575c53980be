// A whole MPM step (the mpm recipe's graph) on the dynamic Cook's membrane, ASGS, Newton to 1e-6: time per
// step and its split by system (counters in ms per step, from the run's own timers) against the number of
// particles, 1 and 2 threads. Each iteration builds the run (not timed) and runs 4 steps.
#include <benchmark/benchmark.h>

#include "engine/methods/recipes/mpm_method.hpp"
#include "perf/bench_support.hpp"

namespace loom {
namespace {

constexpr int kSteps = 4;

void run_steps(benchmark::State& state, const SceneSpec& scene) {
  bench::MpmRunTotals r = bench::time_mpm_runs(state, scene);
  auto& totals = r.timers;
  const long long particles = r.particles, iterations = r.runs, newton = r.newton;
  const double steps = double(iterations) * kSteps;
  state.SetItemsProcessed(int64_t(double(particles) * steps));
  state.counters["particles"] = double(particles);
  state.counters["newton_per_step"] = double(newton) / steps;
  for (const char* name : {"locate_particles", "activate_grid", "project_to_grid", "apply_grid_loads", "newton", "newton/assemble",
                           "newton/solve", "interpolate_to_particles", "probes"})
    state.counters[std::string(name) + "_ms"] = 1e3 * totals[name].total / steps;
}

void BM_MpmStep(benchmark::State& state) { run_steps(state, bench::cooks_dynamic(state.range(0), kSteps)); }
// The same on a quad4 grid of the same spacing (half the cells, bilinear, ghost penalty on the cut cells).
// Not at 1000 particles: that is 0.7 per grid cell, and quad4 cells with one particle have hourglass modes
// (the tangent is singular; triangles with one particle do not).
void BM_MpmStepQuad(benchmark::State& state) { run_steps(state, bench::cooks_dynamic(state.range(0), kSteps, "quad4")); }

BENCHMARK(BM_MpmStepQuad)->ArgsProduct({{10000, 100000}, {1, 2}})->UseRealTime()->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_MpmStep)->ArgsProduct({{1000, 10000, 100000}, {1, 2}})->UseRealTime()->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace loom

BENCHMARK_MAIN();
