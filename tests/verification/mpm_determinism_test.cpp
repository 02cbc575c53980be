// Method mpm does not depend on the thread count (DESIGN §4): the dynamic Cook's membrane (non-conforming
// grid, particles crossing cells, the active set and with it the sparsity pattern changing between steps),
// coarsened to run in seconds, with 1 and with 2 oneTBB threads, on the triangle grid and on a quad4 grid
// (with its default ghost penalty, whose faces are assembled colour by colour too). Projection, load and assembly scatters run
// cell by cell in colour order with the particles of a cell in index order, so the results are expected to
// agree bitwise; tolerance 1e-12 relative (the figure), the observed difference is reported. The same
// with solver.linear = "cholmod_bisected" (two factorisation tasks), which also agrees with CHOLMOD's result.
#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/task_arena.h>

#include <cstdio>
#include <string>
#include <vector>

#include "engine/scene/scene_loader.hpp"
#include "tests/support/test_support.hpp"
#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

struct Result {
  RunSummary summary;
  std::vector<double> probes;
  std::vector<Vec2> u, v;
  std::vector<double> p;
  int rebuilds = 0;
  std::uint64_t changes = 0;
};

Result run_with_threads(const SceneSpec& scene, int threads) {
  oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  oneapi::tbb::task_arena arena(threads);
  Result r;
  arena.execute([&] {
    auto run = testing::make_mpm_run(scene);
    r.summary = run->run();
    r.probes = run->probe_values();
    const auto& pts = run->model().particles;
    for (Index p = 0; p < pts.X.size(); ++p) {
      r.u.push_back(pts.u[p]), r.v.push_back(pts.v[p]);
      if (pts.pressure.used()) r.p.push_back(pts.pressure[p]);
    }
    r.rebuilds = run->model().activity.rebuilds;
    r.changes = run->model().activity.version;
  });
  return r;
}

// The largest difference between two runs' particle states (relative to each field's largest value) and probes.
double worst_difference(const Result& one, const Result& two) {
  double worst = 0.0, u_max = 0.0, v_max = 0.0, p_max = 0.0;
  for (std::size_t k = 0; k < one.u.size(); ++k) {
    u_max = std::max(u_max, one.u[k].norm()), v_max = std::max(v_max, one.v[k].norm());
    if (k < one.p.size()) p_max = std::max(p_max, std::abs(one.p[k]));
  }
  for (std::size_t k = 0; k < one.u.size(); ++k) {
    worst = std::max(worst, (one.u[k] - two.u[k]).norm() / u_max);
    worst = std::max(worst, (one.v[k] - two.v[k]).norm() / v_max);
    if (k < one.p.size()) worst = std::max(worst, std::abs(one.p[k] - two.p[k]) / p_max);
  }
  for (std::size_t k = 0; k < one.probes.size(); ++k)
    worst = std::max(worst, std::abs(one.probes[k] - two.probes[k]) / std::max(1.0, std::abs(one.probes[k])));
  return worst;
}

class MpmDeterminism : public ::testing::TestWithParam<const char*> {};  // the grid's cells

TEST_P(MpmDeterminism, OneAndTwoThreadsGiveTheSameResult) {
  const SceneSpec scene = load_scene(verification::scene_path("cooks_membrane_mpm_dynamic.toml"),
                                     {"time.steps=12", "body[0].particles_per_cell=3", "output.every=0",
                                      std::string("grid.cells=\"") + GetParam() + "\""});
  if (std::string(GetParam()) == "quad4") {
    ASSERT_GT(scene.grid.ghost_penalty, 0.0);  // quad4's default: the ghost faces are assembled too
  }
  const Result one = run_with_threads(scene, 1), two = run_with_threads(scene, 2);
  ASSERT_TRUE(one.summary.converged && two.summary.converged) << one.summary.failure << two.summary.failure;
  EXPECT_GT(one.u.size(), 8000u);
  EXPECT_GT(one.changes, 2u);  // the active set changed during the run
  EXPECT_GE(one.rebuilds, 1);  // and the Newton system was built at least once
  EXPECT_EQ(one.summary.newton_iterations, two.summary.newton_iterations);
  const double worst = worst_difference(one, two);
  EXPECT_LE(worst, 1e-12);
  std::printf("[mpm determinism] %s: %zu particles, %d active sets, %d pattern rebuilds: worst relative difference 1 vs 2 threads %.1e\n",
              GetParam(), one.u.size(), int(one.changes), one.rebuilds, worst);
}

// The bisected CHOLMOD back-end runs its two halves as two tasks: its results do not depend on the thread count,
// bit for bit, and differ from the unsplit CHOLMOD's in round-off only (the two factorisations order differently).
// The SPD case: the benchmark cantilever (linear elastic, displacement grid; perf/compare), 25 of its steps.
TEST(MpmDeterminismBisected, BisectedCholmodIsThreadIndependentAndAgreesWithCholmod) {
  const std::string path = verification::scene_path("../perf/compare/cantilever_mpm.toml");
  const std::vector<std::string> sets = {"time.steps=25", "output.every=0"};
  const SceneSpec reference = load_scene(path, sets);
  std::vector<std::string> bisected_sets = sets;
  bisected_sets.push_back("solver.linear=\"cholmod_bisected\"");
  const SceneSpec bisected = load_scene(path, bisected_sets);
  const Result ref = run_with_threads(reference, 1), one = run_with_threads(bisected, 1), two = run_with_threads(bisected, 2);
  ASSERT_TRUE(ref.summary.converged && one.summary.converged && two.summary.converged);
  EXPECT_EQ(ref.summary.linear_solver, "cholmod");
  EXPECT_EQ(one.summary.linear_solver, "cholmod_bisected");
  EXPECT_GE(one.rebuilds, 1);
  const double threads = worst_difference(one, two);
  EXPECT_EQ(threads, 0.0);
  const double to_cholmod = worst_difference(ref, one);
  EXPECT_LE(to_cholmod, 1e-9);
  std::printf("[mpm determinism] bisected cholmod: 1 vs 2 threads %.1e; against cholmod %.1e\n", threads, to_cholmod);
}

INSTANTIATE_TEST_SUITE_P(Grid, MpmDeterminism, ::testing::Values("tri3", "quad4"),
                         [](const ::testing::TestParamInfo<const char*>& p) { return std::string(p.param); });

}  // namespace
}  // namespace loom
