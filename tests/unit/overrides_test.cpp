// `--set key.path=value` (engine/scene/overrides): entries of arrays of tables by index or by name,
// missing tables created, values read as TOML with a string fallback, and errors for paths that cannot
// be resolved.
#include <gtest/gtest.h>

#include <string>

#include <toml++/toml.h>

#include "engine/core/errors.hpp"
#include "engine/scene/overrides.hpp"

namespace loom {
namespace {

toml::table base() {
  return toml::parse(R"(
[time]
dt = 1.0
steps = 4

[[body]]
name = "block"
mesh = { generator = "rectangle", divisions = [2, 2] }

[[body]]
name = "plate"
material = "steel"
)");
}

// The InputError message of apply_override, or "" if it did not throw.
std::string error_of(toml::table& t, const std::string& assignment) {
  try {
    apply_override(t, assignment);
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST(ApplyOverride, AddressesAnArrayOfTablesEntryByIndex) {
  toml::table t = base();
  apply_override(t, "body[1].mesh.divisions=[4, 3]");
  const auto* div = t["body"][1]["mesh"]["divisions"].as_array();
  ASSERT_NE(div, nullptr);
  ASSERT_EQ(div->size(), 2u);
  EXPECT_EQ((*div)[0].value<int64_t>(), 4);
  EXPECT_EQ((*div)[1].value<int64_t>(), 3);
  EXPECT_EQ(t["body"][0]["mesh"]["divisions"][0].value<int64_t>(), 2);  // the other entry is untouched
}

TEST(ApplyOverride, AddressesAnArrayOfTablesEntryByName) {
  toml::table t = base();
  apply_override(t, "body[plate].material=rubber");
  EXPECT_EQ(t["body"][1]["material"].value<std::string>(), "rubber");
  EXPECT_FALSE(t["body"][0]["material"]);
  apply_override(t, "body[block].mesh.divisions=[8, 8]");
  EXPECT_EQ(t["body"][0]["mesh"]["divisions"][1].value<int64_t>(), 8);
}

TEST(ApplyOverride, CreatesMissingTables) {
  toml::table t = base();
  apply_override(t, "solver.line_search=true");
  ASSERT_TRUE(t["solver"].is_table());
  EXPECT_EQ(t["solver"]["line_search"].value<bool>(), true);
  apply_override(t, "body[0].body_force.y=-9.81");
  EXPECT_EQ(t["body"][0]["body_force"]["y"].value<double>(), -9.81);
}

TEST(ApplyOverride, ValuesAreTypedAsToml) {
  toml::table t = base();
  apply_override(t, "time.dt=1e-3");
  apply_override(t, "time.steps=10");
  apply_override(t, "solver.line_search=false");
  apply_override(t, R"(scene.name="quoted name")");
  EXPECT_TRUE(t["time"]["dt"].is_floating_point());
  EXPECT_EQ(t["time"]["dt"].value<double>(), 1e-3);
  EXPECT_TRUE(t["time"]["steps"].is_integer());
  EXPECT_EQ(t["time"]["steps"].value<int64_t>(), 10);
  EXPECT_TRUE(t["solver"]["line_search"].is_boolean());
  EXPECT_EQ(t["scene"]["name"].value<std::string>(), "quoted name");
}

TEST(ApplyOverride, TextThatIsNotTomlIsAString) {
  toml::table t = base();
  apply_override(t, "time.integrator=euler_backward");
  EXPECT_TRUE(t["time"]["integrator"].is_string());
  EXPECT_EQ(t["time"]["integrator"].value<std::string>(), "euler_backward");
  apply_override(t, "body[0].mesh.generator=cooks_membrane");
  EXPECT_EQ(t["body"][0]["mesh"]["generator"].value<std::string>(), "cooks_membrane");
}

TEST(ApplyOverride, ReplacesAnExistingValueOfAnotherType) {
  toml::table t = base();
  apply_override(t, "time.dt=\"0.5*x\"");
  EXPECT_EQ(t["time"]["dt"].value<std::string>(), "0.5*x");
}

TEST(ApplyOverride, BadIndexIsAnError) {
  toml::table t = base();
  const std::string msg = error_of(t, "body[2].name=x");
  EXPECT_NE(msg.find("body[2] does not exist"), std::string::npos) << msg;
  EXPECT_NE(msg.find("has 2"), std::string::npos) << msg;
}

TEST(ApplyOverride, UnknownNameIsAnError) {
  toml::table t = base();
  const std::string msg = error_of(t, "body[wall].name=x");
  EXPECT_NE(msg.find("no [[body]] has name = \"wall\""), std::string::npos) << msg;
}

TEST(ApplyOverride, SubscriptOfAPlainTableIsAnError) {
  toml::table t = base();
  const std::string msg = error_of(t, "time[0].dt=2");
  EXPECT_NE(msg.find("'time' is not an array of tables"), std::string::npos) << msg;
}

TEST(ApplyOverride, PathEndingAtATableIsAnError) {
  toml::table t = base();
  const std::string msg = error_of(t, "body[0]=3");
  EXPECT_NE(msg.find("must end at a key"), std::string::npos) << msg;
}

TEST(ApplyOverride, PathThroughAValueIsAnError) {
  toml::table t = base();
  const std::string msg = error_of(t, "time.dt.x=1");
  EXPECT_NE(msg.find("'dt' is not a table"), std::string::npos) << msg;
}

TEST(ApplyOverride, MalformedAssignmentsAreErrors) {
  toml::table t = base();
  EXPECT_NE(error_of(t, "time.dt").find("expected key.path=value"), std::string::npos);
  EXPECT_NE(error_of(t, "=3").find("expected key.path=value"), std::string::npos);
  EXPECT_NE(error_of(t, "time..dt=3").find("empty key"), std::string::npos);
  EXPECT_NE(error_of(t, "body[0.name=3").find("missing ']'"), std::string::npos);
  EXPECT_NE(error_of(t, "body[0]name=3").find("expected '.' after ']'"), std::string::npos);
}

}  // namespace loom
