// A whole 3D MPM step (the mpm recipe on a tet4 grid) on seed 003's twisting column: mixed u-p with ASGS, 24
// material points per cell, grid spacing equal to the body mesh's, Newton to the scene's 1e-8. Time per step and
// its split by system (counters in ms per step, from the run's own timers), the particle throughput of locate,
// projection and interpolation (M particles/s), and the linear solver's share, at about 1e5 and 1e6 particles,
// 1 and 2 threads. Each iteration builds the run (not timed) and runs 2 steps.
#include <benchmark/benchmark.h>

#include "engine/methods/recipes/mpm_method.hpp"
#include "perf/bench_support.hpp"

namespace loom {
namespace {

constexpr int kSteps = 2;

void BM_MpmStep3d(benchmark::State& state) {
  bench::MpmRunTotals r = bench::time_mpm_runs<3>(state, bench::column_twisting(state.range(0), kSteps));
  auto& totals = r.timers;
  const double steps = double(r.runs) * kSteps;
  if (steps == 0) return;
  state.SetItemsProcessed(int64_t(double(r.particles) * steps));
  state.counters["particles"] = double(r.particles);
  state.counters["newton_per_step"] = double(r.newton) / steps;
  for (const char* name : {"locate_particles", "activate_grid", "project_to_grid", "newton", "newton/assemble", "newton/solve",
                           "interpolate_to_particles", "probes"})
    state.counters[std::string(name) + "_ms"] = 1e3 * totals[name].total / steps;
  for (const char* name : {"locate_particles", "project_to_grid", "interpolate_to_particles"})
    state.counters[std::string(name) + "_Mpts_per_s"] = double(r.particles) * steps / std::max(1e-12, totals[name].total) / 1e6;
  double whole = 0.0;
  for (const auto& [name, t] : totals)
    if (name.find('/') == std::string::npos) whole += t.total;
  state.counters["solve_share"] = totals["newton/solve"].total / std::max(1e-12, whole);
}

BENCHMARK(BM_MpmStep3d)->ArgsProduct({{1000, 100000, 1000000}, {1, 2}})->UseRealTime()->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace loom

BENCHMARK_MAIN();
