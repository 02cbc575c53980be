// locate (systems/locate): particles per second against the number of particles, 1 and 2 threads, on the
// dynamic Cook's membrane's rectangle grid (arithmetic search; triangles, and quad4 squares) and on the
// static one's skewed grid (walk from the previous cell); in 3D on a unit box of Kuhn cubes (arithmetic) and
// the same box distorted (walk), with about four particles per tetrahedron at random positions. Each iteration
// moves every particle by a small random step first, as a time step would, so walks take a step or two.
#include <benchmark/benchmark.h>

#include <random>

#include "engine/mesh/tet_background_grid.hpp"
#include "engine/mesh/tet_generators.hpp"
#include "engine/methods/model/mpm_model.hpp"
#include "perf/bench_support.hpp"
#include "systems/locate/locate_points.hpp"

namespace loom {
namespace {

// Times locate_points over `points`, moved by +-step in a random direction before each iteration.
template <int D>
void time_locate(benchmark::State& state, const StepContext& ctx, const GridLayoutT<D>& layout, const Cells& grid, const Nodes<D>& grid_nodes,
                 Points<D>& points, PointLocations& loc, double step) {
  const int threads = int(state.range(1));
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  std::vector<Vec<D>> jitter(std::size_t(points.X.size()));
  for (auto& j : jitter)
    for (int a = 0; a < D; ++a) j[a] = step * d(rng);
  int sign = 1;
  bench::with_threads(threads, [&] {
    locate_points(ctx, layout, grid, grid_nodes, points, loc);  // untimed: the first search has no previous cells to walk from
    for (auto _ : state) {
      state.PauseTiming();
      for (Index p = 0; p < points.X.size(); ++p) points.u[p] += sign * jitter[std::size_t(p)];
      sign = -sign;
      state.ResumeTiming();
      locate_points(ctx, layout, grid, grid_nodes, points, loc);
    }
  });
  state.SetItemsProcessed(state.iterations() * points.X.size());
  state.counters["particles"] = double(points.X.size());
}

void run_locate(benchmark::State& state, const SceneSpec& scene) {
  MpmModel m(scene);
  StepContext ctx;
  ctx.scene = &m.scene;
  time_locate(state, ctx, m.layout, m.grid, m.grid_nodes, m.particles, m.particle_loc, 0.02 * std::sqrt(m.grid.measure[0]));
}

// 3D: a unit box of m^3 Kuhn cubes (6 m^3 tetrahedra) holding state.range(0) particles, about four per
// tetrahedron, uniformly at random away from the boundary by more than the jitter.
void run_locate_3d(benchmark::State& state, bool distorted) {
  const Index n = Index(state.range(0));
  BoxSpec box;
  box.nx = box.ny = box.nz = std::max(2, int(std::lround(std::cbrt(double(n) / 24.0))));
  TetMeshData mesh = generate_box(box);
  if (distorted) distort_interior_nodes(mesh, 0.3, 3);
  Nodes<3> grid_nodes;
  Cells grid;
  GridLayoutT<3> layout;
  build_tet_grid(mesh, distorted ? nullptr : &box, Formulation::p1, grid_nodes, grid, layout);
  const double step = 0.02 / box.nx;
  Points<3> points;
  points.X.use(), points.u.use();
  points.resize(n);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(2.0 * step, 1.0 - 2.0 * step);
  for (Index p = 0; p < n; ++p) points.X[p] = Vec3(u(rng), u(rng), u(rng));
  PointLocations loc;
  StepContext ctx;
  time_locate(state, ctx, layout, grid, grid_nodes, points, loc, step);
  state.counters["cells"] = double(grid.size());
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

void BM_Locate3dStructured(benchmark::State& state) { run_locate_3d(state, false); }

void BM_Locate3dWalk(benchmark::State& state) { run_locate_3d(state, true); }

BENCHMARK(BM_Locate3dStructured)->ArgsProduct({{1000, 100000, 1000000}, {1, 2}})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Locate3dWalk)->ArgsProduct({{1000, 100000, 1000000}, {1, 2}})->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace loom

BENCHMARK_MAIN();
