// The free-surface scenes, short (the full runs are the studies tools/studies/channel_flow_es.toml and
// bingham_collapse_es.toml), against the shallow-layer model of the same flows (tools/lubrication_spreading.py):
//  - scenes/channel_flow_es.toml, the first 5 s at dt = 1e-3 s: the mass downstream of the inlet is rho (A_0 + Q t)
//    at every step (to the gaps that merges close at the rolling front); the front is where the lubrication model
//    has it at 5 s (0.175 m); no boundary edge crosses another; the stick ground lets no particle sink by 1 % of the
//    spacing;
//  - the same on the finest of the paper's meshes, its first second: the area within 0.5 % of the poured area;
//  - scenes/bingham_collapse_es.toml, the first 5 s: the front against the model's 0.2596 m, the mass unchanged;
//    a thin sheet on a graded ground, its first second: the mass unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/scene/scene_loader.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

testing::ProbeTable run_scene(const std::string& scene, const std::vector<std::string>& overrides, const std::string& name) {
  RunSummary summary;
  auto probes = testing::run_for_probes(load_scene(std::string(LOOM_SOURCE_DIR) + "/scenes/" + scene, overrides), name, &summary);
  EXPECT_TRUE(summary.converged) << summary.failure;
  return probes;
}

// The finest of the paper's three meshes (n = 22, h = 2.84 mm), its first second: the current area is the poured area
// A_0 + Q t within 0.5 % at every step (observed 0.29 %, at the first steps: the paste's elastic compression under its
// own weight; the coarse mesh's u-p dilation, 1.6 % above, falls with h). About 20 s.
TEST(ChannelFlow, OnTheFinestMeshTheAreaIsThePouredAreaWithinHalfAPercent) {
  const auto p = run_scene("channel_flow_es.toml",
                           {"time.dt=1e-3", "time.steps=1000", "output.every=0", "remesh.spacing=0.00284091",
                            "inlet[0].spacing=0.00284091", "body[0].mesh.divisions=[9,22]"},
                           "channel_fine_short");
  const auto t = p.column("time"), area = p.column("area"), mass = p.column("mass");
  ASSERT_EQ(t.size(), 1001u);
  const double rho = 2300.0, A0 = 0.025 * 0.0625, Q = 0.001;
  double worst_area = 0.0, worst_mass = 0.0;
  for (std::size_t k = 1; k < t.size(); ++k) {
    const double poured = A0 + Q * t[k];
    worst_area = std::max(worst_area, std::abs(area[k] - poured) / poured);
    worst_mass = std::max(worst_mass, std::abs(mass[k] / rho - poured) / poured);
  }
  EXPECT_LT(worst_area, 5e-3);
  EXPECT_LT(worst_mass, 5e-3);
  std::printf("[channel n = 22, 1 s] area %.1e, mass %.1e off the poured\n", worst_area, worst_mass);
}

TEST(ChannelFlow, PoursTheRightMassAndSpreadsAsTheShallowLayerModel) {
  const auto p = run_scene("channel_flow_es.toml", {"time.dt=1e-3", "time.steps=5000", "output.every=0"}, "channel_short");
  const auto t = p.column("time"), mass = p.column("mass"), area = p.column("area"), front = p.column("front"),
             crossings = p.column("crossings"), penetration = p.column("penetration");
  ASSERT_EQ(t.size(), 5001u);
  const double rho = 2300.0, A0 = 0.025 * 0.0625, Q = 0.001, h = 0.00625;
  double worst_mass = 0.0, worst_area = 0.0;
  for (std::size_t k = 1; k < t.size(); ++k) {
    const double poured = A0 + Q * t[k];
    worst_mass = std::max(worst_mass, std::abs(mass[k] / rho - poured) / poured);
    worst_area = std::max(worst_area, std::abs(area[k] - poured) / poured);
    EXPECT_EQ(crossings[k], 0.0) << "step " << k;
    EXPECT_LT(penetration[k], 0.01 * h) << "step " << k;
  }
  EXPECT_LT(worst_mass, 5e-3);
  // The current area adds the paste's elastic compression (-0.3 %) and the coarse ES u-p mesh's dilation under shear
  // (about +1 % with alpha_stab = 200: docs/free_surface.md).
  EXPECT_LT(worst_area, 2e-2);
  EXPECT_NEAR(front.back(), 0.175, 0.03 * 0.175);
  std::printf("[channel, 5 s] front %.4f m (shallow-layer model 0.175); mass %.1e, area %.1e off the poured\n", front.back(),
              worst_mass, worst_area);
}

TEST(BinghamCollapse, SlumpsAsTheShallowLayerModel) {
  const auto p = run_scene("bingham_collapse_es.toml", {"time.steps=2500", "output.every=0"}, "collapse_short");
  const auto front = p.column("front"), mass = p.column("mass"), crossings = p.column("crossings");
  ASSERT_EQ(front.size(), 2501u);
  EXPECT_NEAR(front.back(), 0.2596, 0.03 * 0.2596);
  for (std::size_t k = 1; k < front.size(); ++k) {
    EXPECT_NEAR(mass[k], 11.5, 1e-9 * 11.5) << "step " << k;
    EXPECT_EQ(crossings[k], 0.0) << "step " << k;
  }
  std::printf("[collapse, 5 s] front %.4f m (shallow-layer model 0.2596)\n", front.back());
}

// A thin sheet (tau0 = 5 Pa) on a ground graded to a quarter of the spacing (`wall[0].spacing`): the fine rows that
// the stick ground shears make triangles of fine corners whose empty circles reach into the coarse cells above. The
// alpha test against the corners' l_char^loc alone took them for the body opening and dropped them, with the mass
// of the corners left without a triangle (steps 257, 333 and 436 of this run lost 0.008, 0.004, 0.042 %); against the
// graded spacing at the circumcentre they stay, and the mass is exact at every step.
TEST(BinghamCollapse, KeepsItsMassOnAGradedGround) {
  const auto p = run_scene("bingham_collapse_es.toml",
                           {"material[0].tau0=5.0", "wall[0].spacing=0.00125", "time.steps=500", "output.every=0"}, "collapse_graded");
  const auto mass = p.column("mass");
  ASSERT_EQ(mass.size(), 501u);
  for (std::size_t k = 1; k < mass.size(); ++k) EXPECT_NEAR(mass[k], 11.5, 1e-9 * 11.5) << "step " << k;
}

}  // namespace
}  // namespace loom
