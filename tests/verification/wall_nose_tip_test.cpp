// A wedge resting on the ground on its base, its sharp tip at the origin: the single linear triangle (0, 0),
// (1, 0), (1, 0.2) of tests/meshes/wedge_tri3_v22.msh, linear elastic, static, under its weight, on a stick ground.
// Its two base nodes carry it. In linear elasticity the internal forces are orthogonal to the rigid motions, so the
// ground's vertical reactions follow from equilibrium alone: moments about the origin, F_1 * 1 = m g * 2/3 (the
// centroid), so F_tip = m g / 3 and F_1 = 2 m g / 3, whatever the stiffness. Each base node's share of the boundary
// facing the ground is half the base, so the tip sinks by F_tip / (k_N / 2) and node 1 by F_1 / (k_N / 2), the
// penetration probe (the stick springs k_N A x round-off, some 5e-8 N at x = 1, set the residual tolerance). This is the case the summed area vector got wrong: the front edge (its horizontal extent equal
// to the base's) cancelled the tip's share, the wedge could turn about node 1, and its tip went through the ground.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "tests/support/test_support.hpp"

namespace loom {
namespace {

TEST(WallNoseTip, AWedgeRestsOnItsTipAndItsBaseNodeAsEquilibriumSays) {
  const double rho = 1000.0, g = 9.81, k = 1e9, weight = rho * g * 0.5 * 1.0 * 0.2;
  const SceneSpec scene = testing::scene_from_text(
      "[scene]\nname = \"wedge\"\nmethod = \"fem\"\n"
      "[time]\nintegrator = \"static\"\ndt = 1.0\nsteps = 1\n[solver]\nresidual_relative = 1e-12\nresidual_absolute = 1e-6\n"
      "[[material]]\nname = \"m\"\nmodel = \"linear_elastic\"\nE = 1e6\nnu = 0.3\ndensity = 1000.0\n"
      "[[body]]\nname = \"wedge\"\nmaterial = \"m\"\nmesh = { file = \"" + std::string(LOOM_SOURCE_DIR) + "/tests/meshes/wedge_tri3_v22.msh\" }\n"
      "[body_force]\ny = -9.81\n"
      "[[wall]]\nname = \"ground\"\npoint = [0.0, 0.0]\nnormal = [0.0, 1.0]\npenalty = 1e9\nslip = \"stick\"\n"
      "[[probe]]\nname = \"Fy\"\nkind = \"wall_force\"\nwall = \"ground\"\ncomponent = \"y\"\n"
      "[[probe]]\nname = \"gap\"\nkind = \"penetration\"\nwall = \"ground\"\n"
      "[output]\nevery = 0\n");
  auto run = testing::make_fem_run(scene);
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto& v = run->probe_values();
  EXPECT_NEAR(v[0], weight, 1e-9 * weight);
  const Nodes<2>& nodes = run->nodes();
  ASSERT_EQ(nodes.size(), 3);
  Index tip = 0, base = 0;
  for (Index i = 0; i < 3; ++i) {
    if (nodes.X[i].isZero(0.0)) tip = i;
    if (nodes.X[i] == Vec2(1.0, 0.0)) base = i;
  }
  const double sink_tip = (weight / 3) / (k / 2), sink_base = (2 * weight / 3) / (k / 2);
  EXPECT_NEAR(-nodes.u_n[tip].y(), sink_tip, 1e-6 * sink_tip);
  EXPECT_NEAR(-nodes.u_n[base].y(), sink_base, 1e-6 * sink_base);
  EXPECT_NEAR(v[1], sink_base, 1e-6 * sink_base);
  std::printf("[wall] wedge on its tip: tip sinks %.6e (m g / 3 / (k / 2) = %.6e), base node %.6e (%.6e), wall force %.10g (weight %.10g)\n",
              -nodes.u_n[tip].y(), sink_tip, -nodes.u_n[base].y(), sink_base, v[0], weight);
}

}  // namespace
}  // namespace loom
