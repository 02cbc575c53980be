// Seed 004's implicit MPM (mpm.scheme = "particle_newmark"): a whole step of the mpm recipe's particle-Newmark
// graph on the rolling disk (scenes/rolling_disk_mpm.toml at J = 3, the disk resting on the ground so that
// every step has contact (the disk touches the ground at t = 0), receding contact and edge-cell soft stiffness), against the number of particles
// (the disk generator's n_theta and layer factor (250, 1.14), (300, 1.14: the paper's disk), (800, 1.05): 12 839,
// 48 738 and 219 330 particles; the smoke test runs the first, 1 thread) and 1, 2 threads. Each
// benchmark iteration builds the run (not timed) and runs 4 steps. Counters per step (ms, from the run's own
// timers): the systems; newton_iteration_ms = newton / iterations; solve_share = newton/solve / newton;
// assembly rate particles_per_s_assemble = particles x assemblies / newton/assemble time.
//
//   build/perf/bench_particle_newmark --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <iomanip>
#include <sstream>

#include "engine/mesh/particle_generators.hpp"
#include "engine/methods/recipes/mpm_method.hpp"
#include "perf/bench_support.hpp"

namespace loom {
namespace {

constexpr int kSteps = 4;

// The disk touching the ground at t = 0: its generated outer radius R' (a little over R = 1.6, more for few
// particles) above the ground at y = -1.6.
struct DiskSize {
  int n_theta;
  double factor;
};
constexpr DiskSize kSizes[] = {{250, 1.14}, {300, 1.14}, {800, 1.05}};

SceneSpec rolling_disk(const DiskSize& size) {
  DiskParticleSpec d;
  d.radius = 1.6, d.core_radius = 1.4, d.n_theta = size.n_theta, d.factor = size.factor, d.density = 1000.0;
  double outer = 0.0;
  for (const Vec2& x : generate_disk_particles(d).X) outer = std::max(outer, x.norm());
  std::ostringstream centre_text;
  centre_text << std::setprecision(17) << "[0.0, " << outer - 1.6 + 1e-9 << "]";
  const std::string centre = centre_text.str();
  const std::string file = std::string(LOOM_SOURCE_DIR) + "/scenes/rolling_disk_mpm.toml";
  std::ostringstream factor;
  factor << size.factor;
  return load_scene(file, {"body[0].particles.n_theta=" + std::to_string(size.n_theta), "body[0].particles.factor=" + factor.str(),
                           "body[0].particles.centre=" + centre,
                           "probe[0].at=" + centre, "probe[1].at=" + centre, "grid.refinements=3",
                           "time.steps=" + std::to_string(kSteps), "output.every=0"});
}

void BM_ParticleNewmarkStep(benchmark::State& state) {
  const SceneSpec scene = rolling_disk(kSizes[state.range(0)]);
  bench::MpmRunTotals r = bench::time_mpm_runs(state, scene);
  auto& totals = r.timers;
  const long long particles = r.particles, runs = r.runs, newton = r.newton;
  const long long assemblies = totals["newton/assemble"].calls;
  const double steps = double(runs) * kSteps;
  state.SetItemsProcessed(int64_t(double(particles) * steps));
  state.counters["particles"] = double(particles);
  state.counters["newton_per_step"] = double(newton) / steps;
  state.counters["newton_iteration_ms"] = 1e3 * totals["newton"].total / double(std::max(1LL, newton));
  state.counters["solve_share"] = totals["newton/solve"].total / totals["newton"].total;
  state.counters["particles_per_s_assemble"] = double(particles) * double(assemblies) / totals["newton/assemble"].total;
  for (const char* name : {"locate_particles", "activate_grid", "flag_soft_cells", "mark_receding_particles", "apply_grid_loads", "newton",
                           "newton/assemble", "newton/solve", "commit_particle_newmark"})
    state.counters[std::string(name) + "_ms"] = 1e3 * totals[name].total / steps;
}

BENCHMARK(BM_ParticleNewmarkStep)->ArgsProduct({{0, 1, 2}, {1, 2}})->UseRealTime()->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace loom

BENCHMARK_MAIN();
