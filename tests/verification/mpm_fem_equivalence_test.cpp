// Method mpm with a displacement grid that is the body mesh itself, three particles per cell at the
// three-point rule, and one static step is finite elements with that quadrature: for linear triangles F is
// constant per cell, so it is exactly loom's fem p1 solution (one-point rule). The finite-strain Cook's
// membrane (Neo-Hooke, nu = 0.499, clamped, dead-load traction) checks the particle-as-quadrature assembly,
// the walk locate on a skewed grid, the traction points and the Dirichlet handling against an independent
// code path, node by node. Tolerance: 1e-8 relative (both Newton solves stop at residual 1e-10 of |r_0|).
#include <gtest/gtest.h>

#include <cstdio>

#include "engine/scene/scene_loader.hpp"
#include "tests/support/test_support.hpp"
#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

TEST(MpmOnTheBodyMesh, OneStaticStepIsTheFiniteElementSolution) {
  const std::string file = verification::scene_path("cooks_membrane_neo_hooke.toml");
  const std::vector<std::string> common = {"body[0].mesh.divisions=[16,16]", "solver.residual_relative=1e-10", "output.every=0"};
  auto mpm_sets = common;
  for (const char* s : {"scene.method=\"mpm\"", "material[0].density=1.0", "grid.generator=\"cooks_membrane\"", "grid.divisions=[16,16]",
                        "grid.pattern=\"alternating\"", "body[0].particles_per_cell=3"})
    mpm_sets.push_back(s);
  const SceneSpec fem_scene = load_scene(file, common);
  const SceneSpec mpm_scene = load_scene(file, mpm_sets);

  auto fem = testing::make_fem_run(fem_scene);
  const RunSummary fs = fem->run();
  ASSERT_TRUE(fs.converged) << fs.failure;
  auto mpm = testing::make_mpm_run(mpm_scene);
  const RunSummary ms = mpm->run();
  ASSERT_TRUE(ms.converged) << ms.failure;

  const Nodes<2>& fn = fem->nodes();
  const Nodes<2>& gn = mpm->model().grid_nodes;
  ASSERT_EQ(fn.size(), gn.size());
  ASSERT_FALSE(mpm->model().layout.structured);
  double u_max = 0.0, worst = 0.0;
  for (Index i = 0; i < fn.size(); ++i) {
    ASSERT_LE((fn.X[i] - gn.X[i]).norm(), 1e-12);
    u_max = std::max(u_max, fn.u_n[i].norm());
    worst = std::max(worst, (fn.u_n[i] - gn.u[i]).norm());
  }
  EXPECT_LE(worst, 1e-8 * u_max);
  // The particles moved with the grid: each one by the interpolated nodal displacement.
  const auto& m = mpm->model();
  for (Index p = 0; p < m.particles.X.size(); ++p) {
    const Index* corner = m.grid.cell_nodes(m.particle_loc.cell[p]);
    Vec2 u = Vec2::Zero();
    for (int a = 0; a < 3; ++a) u += m.particle_loc.N[p][a] * fn.u_n[corner[a]];
    EXPECT_LE((m.particles.u[p] - u).norm(), 1e-8 * u_max);
  }
  std::printf("[mpm = fem] %d grid nodes, %d particles: worst nodal difference %.1e of max |u| %.4f; Newton %lld (fem %lld)\n",
              int(gn.size()), int(m.particles.X.size()), worst / u_max, u_max, ms.newton_iterations, fs.newton_iterations);
}

}  // namespace
}  // namespace loom
