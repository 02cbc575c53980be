// Cost of the PFEM remesh stage (seed 000 §3): remeshing against the bare CGAL Delaunay triangulation, the
// state transfer per quadrature point, and the share of both in whole PFEM steps.
//  - remesh/<n>: remesh_points on n points (a sqrt(n) x sqrt(n) grid on the unit square, interior points
//    moved at random by up to 0.3 of the spacing) with the grid's outline as constraints and the local
//    l_char (eqs 16-18, alpha = 2.5: the moderate block's settings), plus the eq 17 distances on the
//    previous mesh; items = points.
//  - delaunay/<n>: CGAL's Delaunay_triangulation_2 of the same points with their indices (spatially sorted
//    insertion, what remesh_points starts with); the ratio remesh / delaunay is the cost of the
//    constraints, the alpha test and the outline.
//  - map_points/<n>/<scheme>: map_state of the ~3n quadrature points of a P1 mesh of the n points onto the
//    quadrature points of the same mesh after every point moved by 0.1 of the spacing (nothing coincides, so
//    every point is searched and interpolated): scheme 0 CPM, 1-3 BTM-ISO0/1/2; items = new quadrature
//    points, so the figure reads as points per second (the background triangulation included).
//  - pfem_step/<n>/<scheme>: 4 whole PFEM steps (FemRun, p1p1_uphi, static) of a unit square block of n x n
//    alternating cells with distorted interior nodes, compressed by 10 % per step between rollers, so that
//    every remesh changes the connectivity (the first because the distorted mesh is not Delaunay, the
//    others because the compression flips edges). Counters: the shares of the step time spent in remesh
//    (triangulate + rebuild cells + map + rebuild dofs/sparsity), in its parts, and in the linear solves
//    (factorize + back-substitute), and the points.
//    n = 32 (the seed's 32x32) and 316 (1.0e5 particles); scheme 0 CPM, 3 BTM-ISO2.
// Usage (figures in docs/pfem_performance.md):
//   OPENBLAS_NUM_THREADS=1 build/perf/bench_remesh --benchmark_repetitions=5 --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "engine/methods/recipes/fem_method.hpp"
#include "engine/scene/scene_loader.hpp"
#include "systems/map/map_state.hpp"
#include "systems/remesh/remesh.hpp"

namespace loom {
namespace {

struct Cloud {
  std::vector<Vec2> x;
  std::vector<Index> triangles;  // the grid's own cells (the previous mesh)
  std::vector<Edge> outline;
};

// side x side points on the unit square; interior points moved at random by up to 0.3 h.
Cloud jittered_grid(int side) {
  Cloud c;
  const double h = 1.0 / (side - 1);
  std::mt19937_64 gen(12345);
  std::uniform_real_distribution<double> u(-0.3 * h, 0.3 * h);
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      Vec2 p(i * h, j * h);
      if (i > 0 && j > 0 && i < side - 1 && j < side - 1) p += Vec2(u(gen), u(gen));
      c.x.push_back(p);
    }
  for (int j = 0; j + 1 < side; ++j)
    for (int i = 0; i + 1 < side; ++i) {
      const Index a = j * side + i, b = a + 1, d = a + side, e = d + 1;
      // The diagonal that keeps both triangles counter-clockwise and positive after the jitter.
      c.triangles.insert(c.triangles.end(), {a, b, e, a, e, d});
    }
  c.outline = boundary_of(c.triangles);
  return c;
}

int side_of(std::int64_t n) { return int(std::lround(std::sqrt(double(n)))); }

void remesh(benchmark::State& state) {
  const Cloud c = jittered_grid(side_of(state.range(0)));
  const RemeshSettings settings{2.5, 0.0, true};
  std::vector<double> d_avg;
  RemeshResult r;
  for (auto _ : state) {
    average_neighbour_distance(c.x, c.triangles, d_avg);
    remesh_points(c.x, c.outline, settings, d_avg, r);
    benchmark::DoNotOptimize(r.triangles.data());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(c.x.size()));
  state.counters["triangles"] = double(r.triangles.size() / 3);
  state.counters["rejected"] = double(r.rejected);
}

void delaunay(benchmark::State& state) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<Index, Kernel>;
  using Dt = CGAL::Delaunay_triangulation_2<Kernel, CGAL::Triangulation_data_structure_2<Vb>>;
  const Cloud c = jittered_grid(side_of(state.range(0)));
  std::vector<std::pair<Kernel::Point_2, Index>> points;
  for (std::size_t i = 0; i < c.x.size(); ++i) points.emplace_back(Kernel::Point_2(c.x[i].x(), c.x[i].y()), Index(i));
  for (auto _ : state) {
    Dt dt(points.begin(), points.end());
    benchmark::DoNotOptimize(dt.number_of_faces());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(c.x.size()));
}

// Three points per cell at (2/3, 1/6, 1/6) and permutations, as the 3-point rules of the PFEM elements.
std::vector<Vec2> quadrature_points(const std::vector<Vec2>& x, const std::vector<Index>& tris) {
  std::vector<Vec2> q;
  for (std::size_t t = 0; t < tris.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const Vec2 &a = x[std::size_t(tris[t + std::size_t(k)])], &b = x[std::size_t(tris[t + std::size_t((k + 1) % 3)])],
                 &c = x[std::size_t(tris[t + std::size_t((k + 2) % 3)])];
      q.push_back((4.0 * a + b + c) / 6.0);
    }
  return q;
}

void map_points(benchmark::State& state) {
  const Cloud c = jittered_grid(side_of(state.range(0)));
  const double h = 1.0 / (side_of(state.range(0)) - 1);
  const std::vector<Vec2> old_q = quadrature_points(c.x, c.triangles);
  std::vector<Vec2> moved = c.x;
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI);
  for (std::size_t i = 0; i < moved.size(); ++i) {
    const Vec2 p = moved[i] + 0.1 * h * Vec2(std::cos(angle(gen)), std::sin(angle(gen)));
    if (p.x() > 0.0 && p.x() < 1.0 && p.y() > 0.0 && p.y() < 1.0) moved[i] = p;  // the outline stays
  }
  const std::vector<Vec2> new_q = quadrature_points(moved, c.triangles);
  // A smooth, isochoric-free history: F = R(theta) diag(l, 1/l, 1) varying over the block.
  std::vector<Mat3> old_F;
  for (const Vec2& p : old_q) {
    const double t = 0.3 * p.x(), l = 1.0 + 0.5 * p.y();
    Mat3 F = Mat3::Identity();
    F(0, 0) = std::cos(t) * l, F(0, 1) = -std::sin(t) / l, F(1, 0) = std::sin(t) * l, F(1, 1) = std::cos(t) / l;
    old_F.push_back(F);
  }
  MapSettings s;
  const int scheme = int(state.range(1));
  s.scheme = scheme == 0 ? MapScheme::cpm : MapScheme::btm;
  s.iso = scheme <= 1 ? IsoMode::iso0 : scheme == 2 ? IsoMode::iso1 : IsoMode::iso2;
  const std::vector<Index> copy_from(new_q.size(), kNoIndex);
  std::vector<Mat3> new_F;
  MapStats stats;
  for (auto _ : state) {
    map_state(old_q, old_F, new_q, copy_from, s, new_F, stats);
    benchmark::DoNotOptimize(new_F.data());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(new_q.size()));
  state.counters["interpolated"] = double(stats.interpolated);
  state.counters["fallback"] = double(stats.fallback);
  state.SetLabel(scheme == 0 ? "cpm" : scheme == 1 ? "btm-iso0" : scheme == 2 ? "btm-iso1" : "btm-iso2");
}

SceneSpec compressed_block(int n, int scheme) {
  std::ostringstream s;
  s << "[scene]\nname = \"bench-remesh\"\nmethod = \"pfem\"\n[time]\ndt = 1.0\nsteps = 4\n"
       "[[material]]\nname = \"rubber\"\nmodel = \"neo_hooke\"\nK = 501.0\nG = 3.2296\n"
       "[[body]]\nname = \"block\"\nmaterial = \"rubber\"\nelement = \"p1p1_uphi\"\n"
       "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [1.0, 1.0], divisions = ["
    << n << ", " << n << "], pattern = \"alternating\", distortion = 0.25, seed = 3 }\n"
    << "[[boundary]]\nname = \"left\"\nregion = { box = [[0.0, 0.0], [0.0, 1.0]] }\ndisplacement = { x = 0.0 }\n"
       "[[boundary]]\nname = \"bottom\"\nregion = { box = [[0.0, 0.0], [1.0, 0.0]] }\ndisplacement = { y = 0.0 }\n"
       "[[boundary]]\nname = \"top\"\nregion = { box = [[0.0, 1.0], [1.0, 1.0]] }\ndisplacement = { y = \"-0.1 * t\" }\n"
       "[remesh]\nalpha = 2.5\nlchar = \"local\"\n"
       "[map]\nscheme = \""
    << (scheme == 0 ? "cpm" : "btm") << "\"\niso = " << (scheme <= 1 ? 0 : scheme - 1) << "\n[output]\nevery = 0\n";
  return load_scene_text(s.str(), "bench_remesh.toml", {});
}

void pfem_step(benchmark::State& state) {
  const SceneSpec scene = compressed_block(int(state.range(0)), int(state.range(1)));
  RunOptions options;
  options.write_files = false;
  options.progress = false;
  double remesh_s = 0.0, map_s = 0.0, triangulate_s = 0.0, rebuild_s = 0.0, solve_s = 0.0, step_s = 0.0;
  Index points = 0;
  for (auto _ : state) {
    state.PauseTiming();
    FemRun run(scene, options);
    points = run.model().nodes.size();
    state.ResumeTiming();
    const RunSummary summary = run.run();
    if (!summary.converged) state.SkipWithError(summary.failure.c_str());
    const auto t = run.timers().snapshot();
    auto total = [&](const char* name) { return t.count(name) ? t.at(name).total : 0.0; };
    remesh_s += total("remesh"), map_s += total("remesh/map"), triangulate_s += total("remesh/triangulate");
    rebuild_s += total("remesh/rebuild_cells") + total("remesh/rebuild_system"), solve_s += total("newton/solve");
    step_s += total("remesh") + total("apply_boundary_conditions") + total("newton") + total("commit") + total("probes");
  }
  state.counters["points"] = double(points);
  state.counters["remesh_share"] = remesh_s / step_s;
  state.counters["map_share"] = map_s / step_s;
  state.counters["triangulate_share"] = triangulate_s / step_s;
  state.counters["rebuild_share"] = rebuild_s / step_s;  // cells, quadrature points, dofs, sparsity, scatter
  state.counters["linear_solve_share"] = solve_s / step_s;
  state.counters["ms_per_step"] = 1e3 * step_s / (4.0 * double(state.iterations()));
  state.counters["remesh_ms_per_step"] = 1e3 * remesh_s / (4.0 * double(state.iterations()));
  state.SetLabel(state.range(1) == 0 ? "cpm" : "btm-iso2");
}

BENCHMARK(remesh)->Arg(1024)->Arg(16384)->Arg(102400)->Arg(1048576)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(delaunay)->Arg(1024)->Arg(16384)->Arg(102400)->Arg(1048576)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(map_points)->ArgsProduct({{1024, 16384, 102400}, {0, 1, 2, 3}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(pfem_step)->ArgsProduct({{32, 316}, {0, 3}})->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace loom

BENCHMARK_MAIN();
