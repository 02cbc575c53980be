// Results do not depend on the thread count (DESIGN §4: race-free colouring, deterministic order): the
// committed finite-strain Cook's membrane (32 x 32 alternating, 2048 cells; every colour holds more cells
// than the parallel grain, so assembly really runs in parallel) with 1 and with 2 oneTBB threads.
//
// Tolerance 1e-12 relative (the figure); the assembly sums every entry in a fixed order, so the
// results are expected to be bitwise equal, and the observed difference is reported.
#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/task_arena.h>

#include <cstdio>

#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

verification::SceneResult run_with_threads(const SceneSpec& scene, int threads) {
  oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  oneapi::tbb::task_arena arena(threads);  // explicit: 2 slots even on a single-core machine
  verification::SceneResult r;
  arena.execute([&] {
    EXPECT_EQ(oneapi::tbb::this_task_arena::max_concurrency(), threads);
    r = verification::run_scene(scene);
  });
  return r;
}

TEST(Determinism, OneAndTwoThreadsGiveTheSameResult) {
  const SceneSpec scene = load_scene(verification::scene_path("cooks_membrane_neo_hooke.toml"), {"output.every=0"});
  const auto one = run_with_threads(scene, 1);
  const auto two = run_with_threads(scene, 2);
  ASSERT_TRUE(one.summary.converged && two.summary.converged);
  EXPECT_GT(one.summary.cells, 1000);
  EXPECT_EQ(one.summary.newton_iterations, two.summary.newton_iterations);

  double worst_probe = 0.0;
  for (const auto& [name, value] : one.probes) {
    const double other = two.probes.at(name);
    const double rel = std::abs(value - other) / std::max(std::abs(value), 1e-300);
    worst_probe = std::max(worst_probe, value == other ? 0.0 : rel);
    EXPECT_LE(rel, 1e-12) << name << ": " << value << " (1 thread) vs " << other << " (2 threads)";
  }
  ASSERT_EQ(one.u.size(), two.u.size());
  double u_max = 0.0, worst_u = 0.0;
  for (const auto& u : one.u) u_max = std::max(u_max, u.cwiseAbs().maxCoeff());
  for (std::size_t i = 0; i < one.u.size(); ++i) worst_u = std::max(worst_u, (one.u[i] - two.u[i]).cwiseAbs().maxCoeff());
  EXPECT_LE(worst_u, 1e-12 * u_max);  // relative to the largest displacement
  std::printf("[determinism] %lld cells: 1 thread %.3f s, 2 threads %.3f s; worst relative difference: probes %.1e, "
              "nodal displacements %.1e (of max |u| %.4f)\n",
              one.summary.cells, one.seconds, two.seconds, worst_probe, worst_u / u_max, u_max);
}

}  // namespace
}  // namespace loom
