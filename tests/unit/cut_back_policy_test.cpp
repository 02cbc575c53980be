// engine/methods/recipes/cut_back_policy: a halved step is retried only where it solves another problem.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/methods/recipes/cut_back_policy.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

std::string static_block(const std::string& method, const std::string& material_extra = "") {
  const bool viscous = !material_extra.empty();  // hencky_perzyna runs with the smoothed elements
  return "[scene]\nname = \"block\"\nmethod = \"" + method + "\"\n"
         "[time]\nintegrator = \"static\"\ndt = 1.0\nsteps = 2\n"
         "[[material]]\nname = \"m\"\nmodel = \"" + (viscous ? std::string("hencky_perzyna") : std::string("neo_hooke")) +
         "\"\nE = 100.0\nnu = 0.3\ndensity = 1.0\n" + material_extra +
         "[[body]]\nname = \"b\"\nmaterial = \"m\"\n" + (viscous ? std::string("element = \"es_up\"\nalpha_stab = 0.5\n") : std::string("element = \"p1\"\n")) +
         "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [1.0, 1.0], divisions = [2, 2] }\n"
         "[output]\nevery = 0\n";
}

std::vector<Expression> expressions(const std::vector<std::string>& texts) {
  std::vector<Expression> e;
  for (const std::string& t : texts) e.emplace_back(t, "test");
  return e;
}

TEST(CutBackPolicy, AStaticStepUnderConstantLoadsIsTheSameProblemHalved) {
  const SceneSpec scene = testing::scene_from_text(static_block("fem"));
  EXPECT_FALSE(shorter_step_changes_problem(scene, expressions({"-9.81", "2 * x + y"})));
}

TEST(CutBackPolicy, ALoadThatChangesInTimeMakesTheHalvedStepAnotherProblem) {
  const SceneSpec scene = testing::scene_from_text(static_block("fem"));
  EXPECT_TRUE(shorter_step_changes_problem(scene, expressions({"-9.81", "t * x"})));
}

TEST(CutBackPolicy, InertiaMakesTheHalvedStepAnotherProblem) {
  const SceneSpec scene = testing::scene_from_text(static_block("fem"), {"time.integrator=\"newmark\""});
  EXPECT_TRUE(shorter_step_changes_problem(scene, {}));
}

TEST(CutBackPolicy, AViscousMaterialMakesTheHalvedStepAnotherProblem) {
  const SceneSpec viscous = testing::scene_from_text(static_block("fem", "tau0 = 1.0\nviscosity = 0.5\n"));
  EXPECT_TRUE(shorter_step_changes_problem(viscous, {}));
}

// A retried PFEM step remeshes again from the failed attempt's mesh and particles.
TEST(CutBackPolicy, ARemeshMakesTheHalvedStepAnotherProblem) {
  EXPECT_TRUE(shorter_step_changes_problem(testing::scene_from_text(static_block("pfem")), {}));
}

}  // namespace
}  // namespace loom
