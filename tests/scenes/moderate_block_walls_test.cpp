// scenes/moderate_block_pfem.toml with its walls ([Schewe 2024] §5.2; docs/moderate_block/README.md, "With walls"):
//  - the first 400 steps: the reading's path (the numbers of the study), the symmetry line carrying tension (why u = 0
//    is kept beside the wall: a wall alone lets the half block peel off it), the walls untouched until the loaded
//    surface folds onto x = 0 at step 350, and no particle behind x = 0 or y = 0 by more than the penetration probe
//    at any step;
//  - the loaded part of the top held horizontally, quasi-statically (the set-up the paper's curves need): 1000 steps,
//    a smooth, stiffening path, the penetration of either line below 0.1 mm (3 % of the spacing) at every step.
// The scene as committed, to step 1000 after its fold, is a stress test (tests/stress/moderate_block_walls_full_test.cpp):
// which variants get there after the fold depends on round-off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/scene/scene_loader.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

const std::string kScene = std::string(LOOM_SOURCE_DIR) + "/scenes/moderate_block_pfem.toml";

testing::ProbeTable run_scene(const std::vector<std::string>& overrides, const std::string& name, RunSummary& summary) {
  return testing::run_for_probes(load_scene(kScene, overrides), name, &summary);
}

TEST(ModerateBlockWalls, FollowsTheReadingAndNoParticleCrossesALine) {
  RunSummary summary;
  const auto p = run_scene({"time.steps=400", "output.every=0"}, "moderate_walls", summary);
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto u = p.column("u_y_mid"), pen = p.column("penetration"), x_min = p.column("x_min"), y_min = p.column("y_min"),
             wall = p.column("symmetry_wall_force"), reaction = p.column("symmetry_reaction");
  ASSERT_EQ(u.size(), 401u);
  EXPECT_NEAR(u[100], -7.8887, 0.01);
  EXPECT_NEAR(u[200], -17.946, 0.05);
  EXPECT_NEAR(u[300], -20.164, 0.1);
  EXPECT_LT(reaction[200], -20.0);  // the line pulls: -30.8 N/mm
  for (std::size_t k = 0; k < u.size(); ++k) {
    EXPECT_LE(std::max({-x_min[k], -y_min[k], 0.0}), pen[k] + 1e-12) << "step " << k;
    if (k <= 349) {
      EXPECT_EQ(pen[k], 0.0) << "step " << k;
      EXPECT_EQ(wall[k], 0.0) << "step " << k;
    }
  }
  EXPECT_GT(wall[400], 50.0);  // the folded surface on its mirror image: 181 N/mm
  EXPECT_LT(*std::max_element(pen.begin(), pen.end()), 0.1);
}

TEST(ModerateBlockWalls, WithTheLoadedTopHeldReachesTheLastStepSmoothly) {
  RunSummary summary;
  const auto p = run_scene({"boundary[load].displacement.x=0.0", "material[rubber].density=1.1e-9", "output.every=0"}, "moderate_walls_held", summary);
  ASSERT_TRUE(summary.completed) << summary.failure;
  const auto u = p.column("u_y_mid"), pen = p.column("penetration"), x_min = p.column("x_min"), y_min = p.column("y_min");
  ASSERT_EQ(u.size(), 1001u);
  EXPECT_NEAR(u[500], -27.66, 0.1);
  EXPECT_NEAR(u[1000], -35.95, 0.5);
  EXPECT_LT(*std::max_element(pen.begin(), pen.end()), 0.1);
  for (std::size_t k = 0; k < u.size(); ++k)  // consistency of the probes: no particle deeper than the penetration
    EXPECT_LE(std::max({-x_min[k], -y_min[k], 0.0}), pen[k] + 1e-12) << "step " << k;
  double worst_rise = 0.0;  // no jump back up along the path
  for (std::size_t k = 1; k < u.size(); ++k) worst_rise = std::max(worst_rise, u[k] - u[k - 1]);
  EXPECT_LT(worst_rise, 0.2);
}

}  // namespace
}  // namespace loom
