// locate (systems/locate): particles per second against the number of particles, 1 and 2 threads, on the
// dynamic Cook's membrane's rectangle grid (arithmetic search; triangles, and quad4 squares) and on the
// static one's skewed grid (walk from the previous cell). Each iteration moves every particle by a small random step first, as a time
// step would, so walks take a step or two.
#include <benchmark/benchmark.h>

#include <random>

#include "engine/methods/mpm_model.hpp"
#include "perf/bench_support.hpp"
#include "systems/locate/locate_points.hpp"

namespace loom {
namespace {

void run_locate(benchmark::State& state, const SceneSpec& scene) {
  const int threads = int(state.range(1));
  MpmModel m(scene);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  const double step = 0.02 * std::sqrt(m.grid.measure[0]);
  std::vector<Vec2> jitter(std::size_t(m.particles.X.size()));
  for (auto& j : jitter) j = step * Vec2(d(rng), d(rng));
  StepContext ctx;
  ctx.scene = &m.scene;
  int sign = 1;
  bench::with_threads(threads, [&] {
    for (auto _ : state) {
      state.PauseTiming();
      for (Index p = 0; p < m.particles.X.size(); ++p) m.particles.u[p] += sign * jitter[std::size_t(p)];
      sign = -sign;
      state.ResumeTiming();
      locate_points(ctx, m.layout, m.grid, m.grid_nodes, m.particles, m.particle_loc);
    }
  });
  state.SetItemsProcessed(state.iterations() * m.particles.X.size());
  state.counters["particles"] = double(m.particles.X.size());
}

void BM_LocateStructured(benchmark::State& state) { run_locate(state, bench::cooks_dynamic(state.range(0), 1)); }

void BM_LocateStructuredQuad(benchmark::State& state) { run_locate(state, bench::cooks_dynamic(state.range(0), 1, "quad4")); }

void BM_LocateWalk(benchmark::State& state) {
  const long long n = state.range(0);
  const int div = std::max(2, int(std::lround(std::sqrt(double(n) / 6.0))));
  const std::string d = "[" + std::to_string(div) + "," + std::to_string(div) + "]";
  run_locate(state, load_scene(std::string(LOOM_SOURCE_DIR) + "/scenes/cooks_membrane_mpm_static.toml",
                               {"grid.divisions=" + d, "body[0].mesh.divisions=" + d, "output.every=0"}));
}

BENCHMARK(BM_LocateStructured)->ArgsProduct({{1000, 10000, 100000}, {1, 2}})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LocateStructuredQuad)->ArgsProduct({{1000, 10000, 100000}, {1, 2}})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LocateWalk)->ArgsProduct({{1000, 10000, 100000}, {1, 2}})->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace loom

BENCHMARK_MAIN();
