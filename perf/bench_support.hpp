// Shared set-up of the MPM benchmarks: runs a body on a given number of oneTBB threads, builds the
// dynamic Cook's membrane (scenes/cooks_membrane_mpm_dynamic.toml) with about `particles` material points
// (3 per body cell; the body mesh is refined to reach the count, the grid stays h = 0.1), and times whole
// runs of the mpm recipe (the run built untimed in each benchmark iteration).
#pragma once

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/task_arena.h>

#include <cmath>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include <map>

#include "engine/methods/recipes/mpm_method.hpp"
#include "engine/scene/scene_loader.hpp"

namespace loom::bench {

template <class Body>
void with_threads(int threads, Body&& body) {
  oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  oneapi::tbb::task_arena arena(threads);
  arena.execute(body);
}

inline SceneSpec cooks_dynamic(long long particles, int steps, const std::string& cells = "tri3") {
  const int ny = std::max(2, int(std::lround(std::sqrt(double(particles) / (6.0 * 1.6)))));
  const int nx = int(std::lround(1.6 * ny));
  const std::string file = std::string(LOOM_SOURCE_DIR) + "/scenes/cooks_membrane_mpm_dynamic.toml";
  return load_scene(file, {"body[0].mesh.divisions=[" + std::to_string(nx) + "," + std::to_string(ny) + "]", "body[0].particles_per_cell=3",
                           "time.steps=" + std::to_string(steps), "output.every=0", "solver.residual_relative=1e-6",
                           "grid.cells=\"" + cells + "\""});
}

// Seed 003's twisting column (scenes/column_twisting_mpm.toml) with about `particles` material points: 24 per cell
// of a body mesh of k x k x 6k cubes, on a grid of the same spacing 1 / k over [-2, 2]^2 x [0, 7].
inline SceneSpec column_twisting(long long particles, int steps) {
  const int k = std::max(1, int(std::lround(std::cbrt(double(particles) / 864.0))));  // 6 k^3 cubes x 6 tetrahedra x 24
  const std::string file = std::string(LOOM_SOURCE_DIR) + "/scenes/column_twisting_mpm.toml";
  auto vec = [](int a, int b, int c) { return "[" + std::to_string(a) + "," + std::to_string(b) + "," + std::to_string(c) + "]"; };
  return load_scene(file, {"body[0].mesh.divisions=" + vec(k, k, 6 * k), "grid.divisions=" + vec(4 * k, 4 * k, 7 * k),
                           "time.steps=" + std::to_string(steps), "output.every=0"});
}

// Runs `scene` once per benchmark iteration on state.range(1) threads; returns the runs' timer totals (summed
// over the iterations), and the particle count, number of runs and Newton iterations.
struct MpmRunTotals {
  std::map<std::string, TimerStats> timers;
  long long particles = 0, runs = 0, newton = 0;
};
template <int D = 2>
MpmRunTotals time_mpm_runs(benchmark::State& state, const SceneSpec& scene) {
  MpmRunTotals r;
  with_threads(int(state.range(1)), [&] {
    for (auto _ : state) {
      state.PauseTiming();
      RunOptions options;
      options.write_files = false;
      options.progress = false;
      MpmRunT<D> run(scene, options);
      r.particles = run.model().particles.X.size();
      state.ResumeTiming();
      const RunSummary s = run.run();
      state.PauseTiming();
      if (!s.converged) {
        state.SkipWithError(s.failure.c_str());
        break;  // no ResumeTiming after an error
      }
      r.newton += s.newton_iterations;
      for (const auto& [name, t] : run.timers().snapshot()) r.timers[name].total += t.total, r.timers[name].calls += t.calls;
      ++r.runs;
      state.ResumeTiming();
    }
  });
  return r;
}

}  // namespace loom::bench
