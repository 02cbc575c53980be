// Method mpm on quad4 grids (grid.cells = "quad4"): the dynamic Cook's membrane (seed 003 §6.2.1,
// scenes/cooks_membrane_mpm_dynamic.toml, 12 particles per cell, h = 0.1) needs the face ghost penalty on the
// cut cells at the body's boundary. Without it (grid.ghost_penalty = 0) the bilinear cells that hold a few
// particles near their far side give their other nodes almost no mass and no stiffness; such nodes drift, a
// traction point goes with them and leaves the grid, and the run stops at step 140 (t = 3.5 s) with the last
// converged step named. With the default (0.1) the run goes on and u_y(A) follows the triangle
// grid's within 1 % (docs/mpm/README.md §6). The triangle grid's results do not change with the penalty
// off (the default for tri3), and with it on they move by under 1 % here.
// The static Cook's membrane (scenes/cooks_membrane_mpm_static.toml, E = 70, nu = 0.5, ASGS) on a
// non-conforming 48 x 60 rectangle grid of quad4 cells (6 particles per body triangle) converges toward the
// reference u_y(A) = 0.2758 from above as the grid and body mesh are refined together (observed 0.2947,
// 0.2811, 0.2794 at 16, 32, 64 cells across; 0.2771 at 128), and at 64 it is within 1 % of the triangle grid
// of the same spacing (0.2773).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "engine/scene/scene_loader.hpp"
#include "tests/support/test_support.hpp"
#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

constexpr int kSteps = 20;

struct Outcome {
  RunSummary summary;
  double uy_A = 0.0;
};

Outcome run_dynamic(const std::vector<std::string>& sets, int steps = kSteps) {
  std::vector<std::string> all = {"time.steps=" + std::to_string(steps), "output.every=0"};
  all.insert(all.end(), sets.begin(), sets.end());
  const SceneSpec scene = load_scene(verification::scene_path("cooks_membrane_mpm_dynamic.toml"), all);
  auto r = testing::make_mpm_run(scene);
  Outcome o;
  o.summary = r->run();
  for (std::size_t k = 0; k < scene.probes.size(); ++k)
    if (scene.probes[k].name == "uy_A") o.uy_A = r->probe_values()[k];
  return o;
}

TEST(MpmQuadGrid, DynamicCooksMembraneNeedsTheGhostPenaltyAndThenFollowsTheTriangleGrid) {
  const Outcome bare = run_dynamic({"grid.cells=\"quad4\"", "grid.ghost_penalty=0"}, 150);
  EXPECT_FALSE(bare.summary.converged);
  EXPECT_NE(bare.summary.failure.find("traction point"), std::string::npos) << bare.summary.failure;
  const Outcome quad = run_dynamic({"grid.cells=\"quad4\""});
  const Outcome tri = run_dynamic({}), tri_ghost = run_dynamic({"grid.ghost_penalty=0.1"});
  for (const Outcome* o : {&quad, &tri, &tri_ghost}) ASSERT_TRUE(o->summary.converged) << o->summary.failure;
  std::printf("[mpm quad4] step %d: u_y(A) quad4 + ghost %.5f, tri3 %.5f, tri3 + ghost %.5f; quad4 without ghost: %s\n", kSteps, quad.uy_A,
              tri.uy_A, tri_ghost.uy_A, bare.summary.failure.c_str());
  EXPECT_GT(tri.uy_A, 0.4);  // t = 0.5 s: rising toward the first peak
  EXPECT_NEAR(quad.uy_A, tri.uy_A, 0.01 * tri.uy_A);
  EXPECT_NEAR(tri_ghost.uy_A, tri.uy_A, 0.01 * tri.uy_A);
}

double static_cooks(int n, const std::string& cells) {
  const std::string div = "[" + std::to_string(n) + "," + std::to_string(n * 60 / 48) + "]";
  const SceneSpec scene = load_scene(verification::scene_path("cooks_membrane_mpm_static.toml"),
                                     {"grid.generator=\"rectangle\"", "grid.size=[48.0,60.0]", "grid.divisions=" + div,
                                      "grid.pattern=\"right\"", "grid.cells=\"" + cells + "\"",
                                      "body[0].mesh.divisions=[" + std::to_string(n) + "," + std::to_string(n) + "]",
                                      "body[0].particles_per_cell=6", "output.every=0"});
  auto r = testing::make_mpm_run(scene);
  const RunSummary s = r->run();
  EXPECT_TRUE(s.converged) << cells << " " << n << ": " << s.failure;
  for (std::size_t k = 0; k < scene.probes.size(); ++k)
    if (scene.probes[k].name == "uy_A") return r->probe_values()[k];
  return NAN;
}

TEST(MpmQuadGrid, StaticCooksMembraneOnANonConformingQuadGridConvergesTowardTheReference) {
  constexpr double kReference = 0.2758;
  const double u16 = static_cooks(16, "quad4"), u32 = static_cooks(32, "quad4"), u64 = static_cooks(64, "quad4");
  const double tri64 = static_cooks(64, "tri3");
  std::printf("[mpm quad4] static Cook's, non-conforming grid: u_y(A) %.5f, %.5f, %.5f at 16, 32, 64 (%+.2f %% of %.4f); tri3 at 64 %.5f\n",
              u16, u32, u64, 100 * (u64 / kReference - 1), kReference, tri64);
  EXPECT_GT(u16, u32);
  EXPECT_GT(u32, u64);
  EXPECT_GT(u64, kReference);
  EXPECT_NEAR(u64, kReference, 0.015 * kReference);
  EXPECT_NEAR(u64, tri64, 0.01 * tri64);
}

// Too few particles per quad4 cell: 960 particles on the h = 0.1 grid (0.7 per cell) leave hourglass modes, and
// the tangent is singular up to round-off from the first step. What such a run then does is decided by
// round-off, so by the CPU's BLAS kernels (tools/portability_check.sh): with OpenBLAS's Prescott, Nehalem,
// Haswell and Zen kernels UMFPACK meets a zero pivot at step 3; with SkylakeX an iterate inverts a cell at
// step 2; with Sandybridge the factorization goes through and the run goes on, wrongly, until a traction
// point leaves the active grid at step 22. What holds on every machine, and is asserted: loom says that the
// tangent is singular, names the sparse cells and says what to change -- in the failure or in a warning.
TEST(MpmQuadGrid, SparseQuadCellsGetTheirSingularTangentNamedWithTheFix) {
  const testing::Command c = testing::run_loom({"run", verification::scene_path("cooks_membrane_mpm_dynamic.toml"), "--quiet", "--set", "time.steps=" + std::to_string(kSteps),
                              "--set", "output.every=0", "--set", "grid.cells=\"quad4\"", "--set", "body[0].mesh.divisions=[16,10]", "--set",
                              "body[0].particles_per_cell=3", "--out", testing::TempDir("mpm_quad_sparse").path()});
  EXPECT_TRUE(c.exit_code == 0 || c.exit_code == 1) << c.err;
  EXPECT_NE(c.err.find("singular"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("active quad4 cells hold fewer than 4 particles"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("raise body[0].particles_per_cell"), std::string::npos) << c.err;
}

}  // namespace
}  // namespace loom
