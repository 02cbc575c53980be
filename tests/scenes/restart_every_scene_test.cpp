// Every shipped scene can be stopped and continued: each scene of scenes/ (shortened to a few steps, its largest
// meshes coarsened where a step would take seconds) runs whole, and again stopped twice (--stop-after, then
// --restart --stop-after, then --restart to the end). The continued run's probes.csv, .pvd collection and last
// frame must be those of the whole run byte for byte. A scene added to scenes/ without a case here fails the test
// that lists them, so that a new scene cannot ship without a restart that works.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <map>
#include <sstream>

#include "tests/scenes/scene_checks.hpp"
#include "tests/support/test_support.hpp"

namespace loom::testing {
namespace {

const std::string kSource = LOOM_SOURCE_DIR;

struct Case {
  int steps = 6;                  // the shortened run; it stops after steps / 3 and 2 steps / 3
  std::vector<std::string> sets;  // more --set overrides (coarser meshes, an adaptive run's end)
};

// The shortened form of each scene. Scenes of one step get three (their loads are reached in the first, or ramped by
// t; the others start from the converged state, which is what a restart must reproduce).
const std::map<std::string, Case>& cases() {
  static const std::map<std::string, Case> c = {
      {"bingham_collapse_es", {6, {}}},
      {"bingham_collapse_mpm", {6, {}}},
      {"bingham_poiseuille", {3, {}}},
      {"bingham_poiseuille_3d", {3, {}}},
      {"bingham_poiseuille_mpm", {3, {}}},
      {"block_3d", {3, {"body[0].mesh.divisions=[4,4,4]"}}},
      {"bouncing_disk", {6, {"time.end=0.03"}}},
      {"bouncing_disk_mpm_plate", {6, {"time.end=0.03"}}},
      {"cantilever_dynamic_es", {6, {}}},
      {"cantilever_dynamic_mpm", {6, {}}},
      {"cantilever_mpm_grid_newmark", {6, {}}},
      {"cantilever_mpm_particle", {6, {}}},
      {"channel_flow_es", {6, {}}},
      {"column_bending_fem", {3, {"body[0].mesh.divisions=[2,2,12]"}}},
      {"column_bending_mpm", {3, {"body[0].mesh.divisions=[2,2,12]", "grid.divisions=[16,4,14]"}}},
      {"column_slump_es_3d", {6, {}}},
      {"column_twisting_fem", {3, {"body[0].mesh.divisions=[2,2,12]"}}},
      {"column_twisting_mpm", {3, {"body[0].mesh.divisions=[2,2,12]", "grid.divisions=[8,8,14]"}}},
      {"concrete_printing_es_3d", {6, {}}},
      {"constrained_block_fem", {6, {}}},
      {"cooks_membrane", {3, {"body[0].mesh.divisions=[16,16]"}}},
      {"constrained_block_pfem", {6, {}}},
      {"constrained_block_pfem_3d", {6, {}}},
      {"granular_collapse_mpm", {6, {}}},
      {"moderate_block_pfem_3d", {6, {}}},
      {"cooks_membrane_3d", {3, {}}},
      {"cooks_membrane_es", {3, {}}},
      {"cooks_membrane_es_3d", {3, {"body[0].mesh.divisions=[8,8,1]"}}},
      {"cooks_membrane_es_u", {3, {}}},
      {"cooks_membrane_linear", {3, {}}},
      {"cooks_membrane_mpm_dynamic", {6, {}}},
      {"cooks_membrane_mpm_static",  // the body fills its grid: a grid with a margin, so that the particles can move on
       {3, {"time.dt=0.3333333333333333", "grid.generator=\"rectangle\"", "grid.origin=[-4.0,-4.0]", "grid.size=[56.0,72.0]", "grid.divisions=[14,18]"}}},
      {"cooks_membrane_nearly_incompressible", {3, {}}},
      {"cooks_membrane_neo_hooke", {3, {}}},
      {"cooks_membrane_quad9", {3, {}}},
      {"homogeneous_compression", {6, {}}},
      {"homogeneous_compression_3d", {6, {}}},
      {"mms_mpm", {3, {"time.dt=0.3333333333333333", "grid.origin=[-0.5,-0.5]", "grid.size=[2.0,2.0]", "grid.divisions=[32,32]"}}},
      {"mms_mpm_3d", {3, {"time.dt=0.1", "grid.origin=[-0.25,-0.25,-0.125]", "grid.size=[1.5,1.5,0.5]", "grid.divisions=[12,12,4]"}}},
      {"moderate_block_pfem", {6, {}}},
      {"newtonian_duct_3d", {3, {}}},
      {"plate_with_hole", {3, {}}},
      {"plate_with_hole_3d", {3, {}}},
      {"quarter_block_walls_3d", {3, {}}},
      {"rolling_disk_mpm", {6, {}}},
      {"rolling_disk_on_plate", {6, {}}},
      {"slump_flow_es_3d", {6, {"time.end=0.035"}}},
  };
  return c;
}

std::vector<std::string> shipped_scenes() {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(kSource + "/scenes"))
    if (e.path().extension() == ".toml") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(RestartEveryScene, EveryShippedSceneHasACase) {
  for (const std::string& name : shipped_scenes()) EXPECT_TRUE(cases().count(name)) << "scenes/" << name << ".toml has no restart case";
  for (const auto& [name, c] : cases()) EXPECT_TRUE(std::filesystem::exists(kSource + "/scenes/" + name + ".toml")) << name;
}

std::vector<std::string> run_args(const std::string& scene, const Case& c) {
  std::vector<std::string> args = {"run", scene, "--quiet", "--set", "time.steps=" + std::to_string(c.steps), "--set",
                                   "output.every=" + std::to_string(c.steps), "--set", "output.checkpoint_every=0"};
  for (const auto& s : c.sets) args.push_back("--set"), args.push_back(s);
  return args;
}

std::vector<std::string> with(std::vector<std::string> args, std::initializer_list<std::string> more) {
  args.insert(args.end(), more);
  return args;
}

// The frames of the last step: one file per part (mesh methods: <stem>_NNNNNN.vtu; mpm: _particles.vtp and _grid.vtu).
std::vector<std::string> last_frames(const std::string& dir, int step) {
  std::ostringstream tag;
  tag << "_" << std::setw(6) << std::setfill('0') << step;
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string f = e.path().filename().string();
    if (f.find(tag.str()) != std::string::npos && (e.path().extension() == ".vtu" || e.path().extension() == ".vtp")) files.push_back(f);
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string pvd_of(const std::string& dir) {
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".pvd") return read_text(e.path().string());
  return "";
}

class RestartScene : public ::testing::TestWithParam<std::string> {};

TEST_P(RestartScene, StoppedTwiceAndContinuedIsTheWholeRunByteForByte) {
  const std::string name = GetParam();
  ASSERT_TRUE(cases().count(name));
  const Case& c = cases().at(name);
  const std::string scene = kSource + "/scenes/" + name + ".toml";
  TempDir dir("restart_scene_" + name);
  const std::string full = dir.file("full"), part = dir.file("part");
  const std::vector<std::string> args = run_args(scene, c);
  const Command whole = run_loom(with(args, {"--out", full}));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const int first = c.steps / 3, second = 2 * c.steps / 3;
  const Command a = run_loom(with(args, {"--out", part, "--stop-after", std::to_string(first)}));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const Command b = run_loom(with(args, {"--restart", part, "--stop-after", std::to_string(second)}));
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_NE(b.err.find("stopped as asked after step " + std::to_string(second)), std::string::npos) << b.err;
  const Command rest = run_loom(with(args, {"--restart", part}));
  ASSERT_EQ(rest.exit_code, 0) << rest.err;

  EXPECT_EQ(read_text(part + "/probes.csv"), read_text(full + "/probes.csv")) << name << ": probes.csv differs";
  EXPECT_EQ(pvd_of(part), pvd_of(full)) << name << ": the .pvd collection differs";
  const int last = int(parse_json(read_text(full + "/run.json")).at("last_converged_step").number);
  EXPECT_EQ(last, c.steps);
  const std::vector<std::string> frames = last_frames(full, last);
  ASSERT_FALSE(frames.empty()) << name << ": no frame of step " << last;
  EXPECT_EQ(last_frames(part, last), frames);
  for (const std::string& f : frames) EXPECT_EQ(read_text(part + "/" + f), read_text(full + "/" + f)) << name << ": " << f << " differs";
  for (const auto& f : files_under(part)) EXPECT_EQ(f.find(".tmp"), std::string::npos) << f;
}

INSTANTIATE_TEST_SUITE_P(Scenes, RestartScene, ::testing::ValuesIn(shipped_scenes()),
                         [](const ::testing::TestParamInfo<std::string>& scene) { return scene.param; });

}  // namespace
}  // namespace loom::testing
