// Scene validation (engine/scene/schema_validator, scene_loader) through load_scene_text: each error names
// test.toml:LINE:COL and the key path, all errors come at once in file order, --set values are checked
// like the others. Expected positions are looked up in the fixture text itself.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "engine/core/errors.hpp"
#include "engine/scene/scene_loader.hpp"

namespace loom {
namespace {

const std::string kScene = R"([scene]
name = "unit"

[time]
dt = 0.5
steps = 2

[[material]]
name = "rubber"
model = "neo_hooke"
E = 3.0
nu = 0.25

[[body]]
name = "block"
material = "rubber"
mesh = { generator = "rectangle", size = [2.0, 1.0], divisions = [2, 1] }
)";

// The text with the first occurrence of `from` replaced by `to` (which must exist).
std::string with(const std::string& text, const std::string& from, const std::string& to) {
  const auto p = text.find(from);
  EXPECT_NE(p, std::string::npos) << "fixture lacks " << from;
  if (p == std::string::npos) return text;
  return text.substr(0, p) + to + text.substr(p + from.size());
}

// "test.toml:LINE:COL" of the first occurrence of `token` on the first line holding `line_text`.
std::string at(const std::string& text, const std::string& line_text, const std::string& token) {
  std::istringstream in(text);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n)
    if (line.find(line_text) != std::string::npos) {
      const auto c = line.find(token);
      EXPECT_NE(c, std::string::npos) << token << " not on line " << line;
      return "test.toml:" + std::to_string(n) + ":" + std::to_string(c + 1);
    }
  ADD_FAILURE() << "no line holds " << line_text;
  return {};
}

// The InputError message of loading `text`, or "" if it loaded.
std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    load_scene_text(text, "test.toml", overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST(LoadSceneText, AcceptsTheFixtureAndDerivesLameConstants) {
  const SceneSpec s = load_scene_text(kScene, "test.toml");
  EXPECT_EQ(s.scene.name, "unit");
  EXPECT_EQ(s.time.dt, 0.5);
  EXPECT_EQ(s.time.steps, 2);
  ASSERT_EQ(s.materials.size(), 1u);
  // E = 3, nu = 0.25: mu = E / (2 (1 + nu)) = 1.2, lambda = E nu / ((1 + nu)(1 - 2 nu)) = 1.2.
  EXPECT_DOUBLE_EQ(s.materials[0].mu, 1.2);
  EXPECT_DOUBLE_EQ(s.materials[0].lambda, 1.2);
  ASSERT_EQ(s.bodies.size(), 1u);
  EXPECT_EQ(s.bodies[0].mesh.nx, 2);
  EXPECT_EQ(s.output.directory, "out/unit");  // default from the scene name
}

TEST(LoadSceneText, BulkAndShearModuliGiveTheSameLameConstants) {
  // K = lambda + 2 mu / 3 = 2.0, G = mu = 1.2
  const std::string text = with(with(kScene, "E = 3.0", "K = 2.0"), "nu = 0.25", "G = 1.2");
  const SceneSpec s = load_scene_text(text, "test.toml");
  EXPECT_DOUBLE_EQ(s.materials[0].mu, 1.2);
  EXPECT_NEAR(s.materials[0].lambda, 1.2, 1e-15);
  EXPECT_NEAR(s.materials[0].E, 3.0, 1e-15);
  EXPECT_NEAR(s.materials[0].nu, 0.25, 1e-15);
}

TEST(LoadSceneText, UnknownKeySuggestsTheClosestKnownKey) {
  const std::string text = with(kScene, "steps = 2", "steps = 2\nstesp = 3");
  const std::string msg = error_of(text);
  EXPECT_NE(msg.find(at(text, "stesp", "stesp") + ": error: time.stesp: unknown key (did you mean 'steps'?)"), std::string::npos)
      << msg;
}

TEST(LoadSceneText, TypoInANestedKeyIsReportedWithItsPath) {
  const std::string text = with(kScene, "divisions = [2, 1]", "divisons = [2, 1]");
  const std::string msg = error_of(text);
  EXPECT_NE(msg.find(at(text, "divisons", "divisons") + ": error: body[0].mesh.divisons: unknown key (did you mean 'divisions'?)"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("body[0].mesh.divisions: missing required key"), std::string::npos) << msg;
}

TEST(LoadSceneText, UnknownKeyWithoutNearMatchListsTheKnownKeys) {
  const std::string text = with(kScene, "name = \"unit\"", "name = \"unit\"\ncolourmap = 3");
  const std::string msg = error_of(text);
  EXPECT_NE(msg.find(at(text, "colourmap", "colourmap") + ": error: scene.colourmap: unknown key; known keys here: name, method"),
            std::string::npos)
      << msg;
}

TEST(LoadSceneText, WrongTypeNamesExpectedAndActual) {
  const std::string text = with(kScene, "steps = 2", "steps = \"two\"");
  const std::string msg = error_of(text);
  EXPECT_NE(msg.find(at(text, "steps", "\"two\"") + ": error: time.steps: expected integer, got the string \"two\""), std::string::npos)
      << msg;
}

TEST(LoadSceneText, RangeViolationNamesTheRange) {
  const std::string text = with(kScene, "nu = 0.25", "nu = 0.6");
  const std::string msg = error_of(text);
  EXPECT_NE(msg.find(at(text, "nu = ", "0.6") + ": error: material[0].nu: must be in (-1, 0.5], got 0.6"), std::string::npos) << msg;
}

TEST(LoadSceneText, NegativeTimeStepIsOutOfRange) {
  const std::string text = with(kScene, "dt = 0.5", "dt = -1");
  const std::string msg = error_of(text);
  EXPECT_NE(msg.find(at(text, "dt = ", "-1") + ": error: time.dt: must be > 0, got -1"), std::string::npos) << msg;
}

TEST(LoadSceneText, MissingRequiredKeyPointsAtItsTable) {
  const std::string text = with(kScene, "dt = 0.5\n", "");
  const std::string msg = error_of(text);
  EXPECT_NE(msg.find(at(text, "[time]", "[time]") + ": error: time.dt: missing required key"), std::string::npos) << msg;
}

TEST(LoadSceneText, MissingRequiredKeyOfAnArrayEntry) {
  const std::string text = with(kScene, "model = \"neo_hooke\"\n", "");
  const std::string msg = error_of(text);
  EXPECT_NE(msg.find(at(text, "[[material]]", "[[material]]") + ": error: material[0].model: missing required key"), std::string::npos)
      << msg;
}

TEST(LoadSceneText, MissingRequiredTable) {
  const std::string text = with(kScene, "[time]\ndt = 0.5\nsteps = 2\n", "");
  const std::string msg = error_of(text);
  EXPECT_NE(msg.find("test.toml:1:1: error: time: missing required table"), std::string::npos) << msg;
}

TEST(LoadSceneText, ReportsAllErrorsAtOnceInFileOrder) {
  const std::string text = with(with(kScene, "steps = 2", "steps = 2.5"), "nu = 0.25", "nu = -2");
  const std::string msg = error_of(text);
  const auto first = msg.find(at(text, "steps", "2.5") + ": error: time.steps");
  const auto second = msg.find(at(text, "nu = ", "-2") + ": error: material[0].nu");
  ASSERT_NE(first, std::string::npos) << msg;
  ASSERT_NE(second, std::string::npos) << msg;
  EXPECT_LT(first, second);
}

TEST(LoadSceneText, SyntaxErrorNamesTheLine) {
  const std::string text = with(kScene, "steps = 2", "steps = = 2");
  const std::string msg = error_of(text);
  const std::string line = at(text, "steps", "steps");
  EXPECT_NE(msg.find(line.substr(0, line.rfind(':') + 1)), std::string::npos) << msg;  // test.toml:LINE:
  EXPECT_NE(msg.find("syntax"), std::string::npos) << msg;
}

TEST(LoadSceneText, UnknownMaterialReferenceListsTheKnownOnes) {
  const std::string text = with(kScene, "material = \"rubber\"", "material = \"steel\"");
  const std::string msg = error_of(text);
  EXPECT_NE(msg.find("body[0].material: no [[material]] named \"steel\" (known: rubber)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("test.toml:"), std::string::npos) << msg;
}

TEST(LoadSceneText, OverriddenValuesAreValidatedAndBlameTheCommandLine) {
  const std::string msg = error_of(kScene, {"time.dt=-1"});
  EXPECT_NE(msg.find("command line (--set): error: time.dt: must be > 0, got -1"), std::string::npos) << msg;
}

TEST(LoadSceneText, OverrideReplacingATableIsATypeError) {
  const std::string msg = error_of(kScene, {"time=3"});
  EXPECT_NE(msg.find("time: expected table, got the integer 3"), std::string::npos) << msg;
}

TEST(LoadSceneText, OverridesApplyBeforeValidation) {
  const SceneSpec s = load_scene_text(kScene, "test.toml", {"time.steps=7", "body[block].mesh.divisions=[3, 4]", "solver.linear=umfpack"});
  EXPECT_EQ(s.time.steps, 7);
  EXPECT_EQ(s.bodies[0].mesh.nx, 3);
  EXPECT_EQ(s.bodies[0].mesh.ny, 4);
  EXPECT_EQ(s.solver.linear, LinearSolverKind::umfpack);
  EXPECT_NE(s.text_hash, load_scene_text(kScene, "test.toml").text_hash);
}

}  // namespace loom
