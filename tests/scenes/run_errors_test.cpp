// Errors and warnings that need the built model or the run (the malformed/ cases cover the static ones
// that name a line): memory, a PFEM alpha shape that leaves nothing, a singular tangent, p1 locking.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>

#include "tests/scenes/scene_checks.hpp"
#include "tests/support/test_support.hpp"

namespace loom::testing {
namespace {

const std::string kSource = LOOM_SOURCE_DIR;
const std::string kBase = kSource + "/tests/scenes/base.toml";

// Displacement-only linear triangles lock as nu -> 1/2: allowed, but said (exit 0).
TEST(RunErrors, P1NearlyIncompressibleWarnsAndNamesTheElementsThatDoNotLock) {
  const Command locking = run_loom({"check", kBase, "--set", "material[0].nu=0.4999"});
  EXPECT_EQ(locking.exit_code, 0) << locking.err;
  EXPECT_NE(locking.err.find(kBase + ":"), std::string::npos) << locking.err;
  EXPECT_NE(locking.err.find(": warning: body[0].element: p1 (linear displacement triangles) locks"), std::string::npos) << locking.err;
  EXPECT_NE(locking.err.find("nu = 0.4999 > 0.49"), std::string::npos) << locking.err;
  EXPECT_NE(locking.err.find("\"p1p1_uphi\""), std::string::npos) << locking.err;
  EXPECT_NE(locking.err.find("\"tri6\""), std::string::npos) << locking.err;
  const Command fine = run_loom({"check", kBase, "--set", "material[0].nu=0.3"});
  EXPECT_EQ(fine.err, "");
  const Command tri6 = run_loom({"check", kBase, "--set", "material[0].nu=0.4999", "--set", "body[0].element=\"tri6\""});
  EXPECT_EQ(tri6.err, "");
}

// [2000, 2000] divisions under a 3 GB address-space limit: the estimate (about 18 GB) is refused before
// anything is allocated (it ended in std::bad_alloc, exit 1).
TEST(RunErrors, DivisionsThatCannotFitInMemoryAreBadInputWithTheEstimate) {
  TempDir dir("errors_memory");
  const std::string cmd = "ulimit -v 3000000; exec " + std::string(LOOM_BINARY) + " run " + kSource +
                          "/scenes/cooks_membrane_linear.toml --quiet --out " + dir.file("out") +
                          " --set 'body[0].mesh.divisions=[2000,2000]' 2>" + dir.file("err");
  const int status = std::system(("sh -c \"" + cmd + "\"").c_str());
  ASSERT_TRUE(WIFEXITED(status));
  const std::string err = read_text(dir.file("err"));
  EXPECT_EQ(WEXITSTATUS(status), 2) << err;
  EXPECT_NE(err.find("error: body[0].mesh.divisions: [2000, 2000] makes about 8e+06 cells; the run would need about"), std::string::npos) << err;
  EXPECT_NE(err.find("ulimit -v"), std::string::npos) << err;
  EXPECT_FALSE(looks_like_crash(err)) << err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
}

// The same in 3D names the three numbers of a box's divisions (it named two).
TEST(RunErrors, ThreeDimensionalDivisionsThatCannotFitNameTheirThreeNumbers) {
  TempDir dir("errors_memory_3d");
  const std::string cmd = "ulimit -v 3000000; exec " + std::string(LOOM_BINARY) + " run " + kSource +
                          "/scenes/block_3d.toml --quiet --out " + dir.file("out") +
                          " --set 'body[0].mesh.divisions=[300,200,100]' 2>" + dir.file("err");
  const int status = std::system(("sh -c \"" + cmd + "\"").c_str());
  ASSERT_TRUE(WIFEXITED(status));
  const std::string err = read_text(dir.file("err"));
  EXPECT_EQ(WEXITSTATUS(status), 2) << err;
  EXPECT_NE(err.find("error: body[0].mesh.divisions: [300, 200, 100] makes about 3.6e+07 cells; the run would need about"), std::string::npos)
      << err;
  EXPECT_FALSE(looks_like_crash(err)) << err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
}

// An alpha so small that the alpha shape removes every triangle: the run stops at once (exit 1) with that
// reason; halving the step could not bring the triangles back, so no cut-back is tried.
TEST(RunErrors, PfemAlphaThatRemovesTheWholeBodyStopsAtOnce) {
  TempDir dir("errors_alpha");
  const Command c = run_loom({"run", kSource + "/scenes/constrained_block_pfem.toml", "--quiet", "--out", dir.path(), "--set", "remesh.alpha=0.01"});
  EXPECT_EQ(c.exit_code, 1) << c.err;
  EXPECT_NE(c.err.find("removed every triangle of body \"block\": raise remesh.alpha"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("last converged step 0"), std::string::npos) << c.err;
  EXPECT_EQ(c.err.find("cutting the step back"), std::string::npos) << c.err;
  EXPECT_EQ(parse_json(read_text(dir.file("run.json"))).at("cutbacks").number, 0.0);
}

// The same in 3D: a constant l_char of a hundredth of the spacing tears every interior tetrahedron of a BCC block.
TEST(RunErrors, Pfem3dLcharThatRemovesTheWholeBodyStopsAtOnce) {
  TempDir dir("errors_alpha_3d");
  const Command c = run_loom({"run", kSource + "/scenes/homogeneous_compression_3d.toml", "--quiet", "--out", dir.path(), "--set", "scene.method=pfem",
                              "--set", "body[0].mesh.lattice=bcc", "--set", "body[0].mesh.distortion=0.0", "--set", "remesh.lchar=0.01"});
  EXPECT_EQ(c.exit_code, 1) << c.err;
  EXPECT_NE(c.err.find("removed every tetrahedron of body \"block\": raise remesh.alpha, or remesh.lchar"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("last converged step 0"), std::string::npos) << c.err;
  EXPECT_EQ(c.err.find("cutting the step back"), std::string::npos) << c.err;
  EXPECT_EQ(parse_json(read_text(dir.file("run.json"))).at("cutbacks").number, 0.0);
  EXPECT_TRUE(std::filesystem::exists(dir.file("homogeneous-compression-3d_000000.vtu")));
}

// The equal-order mixed element without stabilisation (nu = 0.5) is singular in its spurious pressure modes:
// UMFPACK's pivot ratio is ~1e-17. The run goes on (it is the Galerkin reference of the stabilisation study)
// but says that its tangent is singular up to round-off and what that means.
TEST(RunErrors, ANearlySingularTangentIsNamedWithItsPivotRatio) {
  TempDir dir("errors_singular");
  const Command c = run_loom({"run", kSource + "/scenes/cooks_membrane_mpm_static.toml", "--quiet", "--out", dir.path(), "--set",
                              "body[0].stabilisation=\"none\""});
  EXPECT_EQ(c.exit_code, 0) << c.err;
  EXPECT_NE(c.err.find("warning: step 1 (t = 1): the tangent matrix is singular up to round-off (pivot ratio "), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("spurious modes"), std::string::npos) << c.err;
  const Command stabilised = run_loom({"run", kSource + "/scenes/cooks_membrane_mpm_static.toml", "--quiet", "--out", dir.path()});
  EXPECT_EQ(stabilised.exit_code, 0) << stabilised.err;
  EXPECT_EQ(stabilised.err.find("singular"), std::string::npos) << stabilised.err;
}

// The nearly incompressible Cook's membrane with p1p1_uphi at nu = 0.49999 stagnates above residual_relative = 1e-8
// (its round-off floor: K / G = 5e4): the failure names the level and the key to loosen, and no cut-back is tried --
// a static step under a constant load solves the same problem when halved (it was cut back five times for nothing).
TEST(RunErrors, AStagnatingStaticStepSaysWhatToLoosenAndIsNotCutBack) {
  TempDir dir("errors_stagnation");
  const std::string scene = kSource + "/scenes/cooks_membrane_nearly_incompressible.toml";
  const std::vector<std::string> sets = {"--set", "body[0].element=\"p1p1_uphi\"", "--set", "material[0].nu=0.49999", "--set",
                                         "body[0].mesh.divisions=[16,16]", "--set", "solver.residual_relative=1e-12"};
  std::vector<std::string> args = {"run", scene, "--quiet", "--out", dir.path()};
  args.insert(args.end(), sets.begin(), sets.end());
  const Command c = run_loom(args);
  ASSERT_EQ(c.exit_code, 1) << c.err;
  EXPECT_NE(c.err.find("the residual stagnated at "), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("above solver.residual_relative = 1e-12: loosen it (solver.residual_relative = "), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("no cut-back was tried: a shorter step solves the same problem here"), std::string::npos) << c.err;
  EXPECT_EQ(parse_json(read_text(dir.file("run.json"))).at("cutbacks").number, 0.0);
  EXPECT_FALSE(looks_like_crash(c.err)) << c.err;
}

// A scene in mm, N, MPa with a density in kg/m^3 and g in m/s^2: the weight is 1e9 times too large, the first Newton
// update moves the block by thousands of its sizes and a cell inverts. The failure says so and points at the units.
TEST(RunErrors, LoadsOutOfScaleWithTheBodyAreNamedWithAUnitsHint) {
  TempDir dir("errors_units");
  const std::string scene = dir.file("units.toml");
  std::string text = read_text(kBase);
  text.replace(text.find("nu = 0.3"), 8, "nu = 0.3\ndensity = 1000.0");
  text.replace(text.find("displacement = { y = \"-0.05 * t\" }"), std::string("displacement = { y = \"-0.05 * t\" }").size(), "displacement = { x = 0.0 }");
  text.replace(text.find("component = \"y\""), 15, "component = \"x\"");  // the top is held in x only
  text += "\n[body_force]\ny = -9.81\n";
  write_text(scene, text);
  const Command c = run_loom({"run", scene, "--quiet", "--out", dir.file("out")});
  ASSERT_EQ(c.exit_code, 1) << c.err;
  EXPECT_NE(c.err.find("the first Newton update moved nodes by "), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("times the body's size"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("one system of units"), std::string::npos) << c.err;
  EXPECT_FALSE(looks_like_crash(c.err)) << c.err;
}

}  // namespace
}  // namespace loom::testing
