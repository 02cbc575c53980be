// Particle-grid transfers (systems/map): particles per second of the projection to the grid (seed 003
// Algorithm 1 lines 5-10; cell-coloured scatter) and of the interpolation back (lines 44-49; per particle),
// against the number of particles, 1 and 2 threads, on the dynamic Cook's membrane (mixed, Newmark).
#include <benchmark/benchmark.h>

#include "engine/methods/model/mpm_model.hpp"
#include "perf/bench_support.hpp"
#include "systems/map/interpolate_to_particles.hpp"
#include "systems/map/project_to_grid.hpp"

namespace loom {
namespace {

void BM_ProjectToGrid(benchmark::State& state) {
  MpmModel m(bench::cooks_dynamic(state.range(0), 1));
  StepContext ctx;
  ctx.scene = &m.scene;
  bench::with_threads(int(state.range(1)), [&] {
    for (auto _ : state) project_to_grid(ctx, m.grid, m.particles, m.particle_loc, m.grid_nodes);
  });
  state.SetItemsProcessed(state.iterations() * m.particles.X.size());
  state.counters["particles"] = double(m.particles.X.size());
}

void BM_InterpolateToParticles(benchmark::State& state) {
  MpmModel m(bench::cooks_dynamic(state.range(0), 1));
  StepContext ctx;
  ctx.scene = &m.scene;
  ctx.dt = m.scene.time.dt;
  project_to_grid(ctx, m.grid, m.particles, m.particle_loc, m.grid_nodes);
  for (Index i = 0; i < m.grid_nodes.size(); ++i) m.grid_nodes.u[i] = Vec2(1e-9, -1e-9);  // tiny: F stays near I
  bench::with_threads(int(state.range(1)), [&] {
    for (auto _ : state) interpolate_to_particles(ctx, m.grid, m.grid_nodes, m.particle_loc, m.particles);
  });
  state.SetItemsProcessed(state.iterations() * m.particles.X.size());
  state.counters["particles"] = double(m.particles.X.size());
}

BENCHMARK(BM_ProjectToGrid)->ArgsProduct({{1000, 10000, 100000}, {1, 2}})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InterpolateToParticles)->ArgsProduct({{1000, 10000, 100000}, {1, 2}})->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace loom

BENCHMARK_MAIN();
