// The MPM grid assembly of the side-by-side cantilever (perf/compare/cantilever_mpm.toml: linear elastic, grid
// Newmark, quad4 cells with the ghost penalty, 4 particles per cell) alone, with and without the tangent, on 1 and 2
// threads: the 2-thread speed-up that a whole run's timers blur (there the worker thread sleeps through the serial
// factorisation and each parallel loop first wakes it). The model is set up as at the start of the first step
// (located, grid activated, projected, loaded, Newmark predictor) and assembled repeatedly.
#include <benchmark/benchmark.h>

#include "engine/methods/model/mpm_model.hpp"
#include "engine/scene/scene_loader.hpp"
#include "perf/bench_support.hpp"
#include "systems/assemble/assemble_grid_system.hpp"
#include "systems/loads/apply_grid_loads.hpp"
#include "systems/locate/activate_grid.hpp"
#include "systems/locate/locate_points.hpp"
#include "systems/map/project_to_grid.hpp"
#include "systems/update/update_grid.hpp"

namespace loom {
namespace {

// k = 8: 10 240 particles, k = 25: 100 000 (perf/compare/step_times.py).
SceneSpec cantilever(int k) {
  const std::string file = std::string(LOOM_SOURCE_DIR) + "/perf/compare/cantilever_mpm.toml";
  return load_scene(file, {"body[0].mesh.divisions=[" + std::to_string(5 * k) + "," + std::to_string(k) + "]",
                           "grid.divisions=[" + std::to_string(21 * k) + "," + std::to_string(5 * k) + "]"});
}

void assemble(benchmark::State& state, bool tangent) {
  MpmModel m(cantilever(int(state.range(0))));
  StepContext ctx;
  ctx.scene = &m.scene;
  ctx.dt = m.scene.time.dt;
  locate_points(ctx, m.layout, m.grid, m.grid_nodes, m.particles, m.particle_loc);
  locate_points(ctx, m.layout, m.grid, m.grid_nodes, m.traction_points, m.traction_loc);
  activate_grid(ctx, m.grid, m.particle_loc, m.bc, m.activity, m.system);
  project_to_grid(ctx, m.grid, m.particles, m.particle_loc, m.grid_nodes);
  apply_grid_loads(ctx, m.grid, m.grid_nodes, m.activity, m.particles, m.particle_loc, m.traction_points, m.traction_loc, m.bc);
  update_grid_kinematics(ctx, m.grid_nodes);
  const GridAssemblyOptions options{tangent, true};
  bench::with_threads(int(state.range(1)), [&] {
    for (auto _ : state)
      benchmark::DoNotOptimize(
          assemble_grid_system(ctx, options, m.materials, m.grid, m.activity, m.grid_nodes, m.particles, m.bc, m.particle_loc, m.system));
  });
  state.SetItemsProcessed(state.iterations() * m.particles.X.size());
  state.counters["particles"] = double(m.particles.X.size());
  state.counters["ghost_faces"] = double(m.activity.ghost_faces.size());
}

void BM_GridAssemblyTangent(benchmark::State& state) { assemble(state, true); }
void BM_GridAssemblyResidual(benchmark::State& state) { assemble(state, false); }

BENCHMARK(BM_GridAssemblyTangent)->ArgsProduct({{3, 8, 25}, {1, 2}})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GridAssemblyResidual)->ArgsProduct({{3, 8, 25}, {1, 2}})->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace loom

BENCHMARK_MAIN();
