// The loom program as a user meets it (DESIGN §5): `check` on every shipped scene, `info`, `schema`,
// `--set` (by index and by name), `--out`, `--threads`, and bad command lines (exit code 2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <regex>
#include <sstream>

#include <sys/wait.h>

#include "engine/scene/schema.hpp"
#include "tests/scenes/scene_checks.hpp"
#include "tests/support/test_support.hpp"

namespace loom::testing {
namespace {

const std::string kSource = LOOM_SOURCE_DIR;
const std::string kCook = kSource + "/scenes/cooks_membrane_linear.toml";
const std::string kBase = kSource + "/tests/scenes/base.toml";

double last(const ProbeTable& t, const std::string& name) { return t.column(name).back(); }

ProbeTable run_probes(const std::string& scene, const std::string& out, std::vector<std::string> extra = {}) {
  std::vector<std::string> args{"run", scene, "--out", out, "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  const Command c = run_loom(args);
  EXPECT_EQ(c.exit_code, 0) << c.err;
  return read_probes(out + "/probes.csv");
}

TEST(Program, CheckAcceptsEveryShippedScene) {
  std::vector<std::string> scenes;
  for (const auto& e : std::filesystem::directory_iterator(kSource + "/scenes"))
    if (e.path().extension() == ".toml") scenes.push_back(e.path().string());
  ASSERT_FALSE(scenes.empty());
  EXPECT_NE(std::find(scenes.begin(), scenes.end(), kCook), scenes.end());
  for (const auto& s : scenes) {
    const Command c = run_loom({"check", s});
    EXPECT_EQ(c.exit_code, 0) << s << "\n" << c.err;
    EXPECT_EQ(c.out, s + ": ok\n");
    EXPECT_EQ(without_warnings(c.err), "");
  }
}

TEST(Program, InfoPrintsTheStepGraphAndTheStores) {
  const Command c = run_loom({"info", kCook});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  // 16 x 16 divisions of Cook's membrane: 17 * 17 nodes, 2 * 256 triangles, one quadrature point each.
  for (const char* line : {"  nodes: 289 entities", "  cells[p1, tri3]: 512 entities", "  quad_points[p1]: 512 entities",
                           "  linear_system: 578 dofs", "  boundary_conditions: 34 prescribed dofs, 16 traction edges",
                           "step graph 'fem': 5 nodes"})
    EXPECT_NE(c.out.find(line), std::string::npos) << line << " not in:\n" << c.out;
  // The nodes in pipeline order, each after the one it depends on.
  std::size_t at = 0;
  for (const char* node : {"\n  apply_boundary_conditions\n", "\n  newton", "\n  commit\n", "\n  probes\n", "\n  output"}) {
    const auto p = c.out.find(node, at);
    ASSERT_NE(p, std::string::npos) << node << " missing or out of order in:\n" << c.out;
    at = p + 1;
  }
  for (const char* edge : {"    after: (start)", "    after: apply_boundary_conditions", "    after: newton", "    after: commit"})
    EXPECT_NE(c.out.find(edge), std::string::npos) << edge;
  // Columns that the fem recipe does not use are not allocated (DESIGN §2).
  EXPECT_NE(c.out.find("not allocated: v, v_n, a, a_n, lumped_mass"), std::string::npos) << c.out;

  const Command coarse = run_loom({"info", kCook, "--set", "body[0].mesh.divisions=[4, 2]"});
  ASSERT_EQ(coarse.exit_code, 0) << coarse.err;
  EXPECT_NE(coarse.out.find("  nodes: 15 entities"), std::string::npos) << coarse.out;
  EXPECT_NE(coarse.out.find("  cells[p1, tri3]: 16 entities"), std::string::npos) << coarse.out;
}

TEST(Program, InfoNamesTheTetrahedraOfA3dScene) {
  const Command c = run_loom({"info", kSource + "/scenes/cooks_membrane_3d.toml"});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  // 16 x 16 quadrilaterals x 1 layer: 512 prisms of 3 tetrahedra; 289 x 2 corners and the edge nodes of tet10.
  for (const char* line : {"  cells[tet10, tet10]: 1536 entities", "  quad_points[tet10]: 6144 entities", " traction faces, loads constant"})
    EXPECT_NE(c.out.find(line), std::string::npos) << line << " not in:\n" << c.out;
}

TEST(Program, SchemaListsEveryKeyAndMarkdownPrintsATable) {
  const Command plain = run_loom({"schema"});
  ASSERT_EQ(plain.exit_code, 0);
  const Command md = run_loom({"schema", "--markdown"});
  ASSERT_EQ(md.exit_code, 0);
  EXPECT_EQ(md.out.rfind("| key | type | default | meaning |\n| --- | --- | --- | --- |\n", 0), 0u) << md.out;

  std::size_t rows = 0;
  std::istringstream lines(md.out);
  for (std::string l; std::getline(lines, l);) {
    if (l.rfind("| `", 0) != 0) continue;
    ++rows;
    EXPECT_EQ(std::count(l.begin(), l.end(), '|') - std::count(l.begin(), l.end(), '\\'), 5) << "not 4 columns: " << l;
  }
  const auto& schema = scene_schema();
  EXPECT_EQ(rows, schema.size());
  for (const KeySpec& k : schema) {
    EXPECT_NE(("\n" + plain.out).find("\n" + k.path + "\n"), std::string::npos) << k.path << " missing from loom schema";
    EXPECT_NE(md.out.find("| `" + k.path + "` | "), std::string::npos) << k.path << " missing from loom schema --markdown";
  }
  for (const char* key : {"time.dt", "solver.max_cutbacks", "material[].nu", "body[].mesh.divisions", "boundary[].region.box",
                          "probe[].kind", "output.every"})
    EXPECT_NE(find_key_spec(key), nullptr) << key;
}

TEST(Program, SetChangesResultsAndAddressesArraysByIndexAndByName) {
  TempDir dir("program_set");
  const ProbeTable base = run_probes(kCook, dir.file("base"));
  const ProbeTable by_index = run_probes(kCook, dir.file("index"), {"--set", "boundary[1].traction.y=12.5"});
  const ProbeTable by_name = run_probes(kCook, dir.file("name"), {"--set", "boundary[loaded].traction.y=12.5"});
  ASSERT_GT(last(base, "uy_C"), 1.0);
  // Linear elasticity: twice the load, twice the displacement and the reaction.
  EXPECT_NEAR(last(by_index, "uy_C") / last(base, "uy_C"), 2.0, 1e-9);
  EXPECT_NEAR(last(by_index, "reaction_y"), -200.0, 1e-6);
  EXPECT_EQ(by_index.rows, by_name.rows);

  // Material by name, and a value given as a string (not valid TOML) is taken as text.
  const ProbeTable stiffer = run_probes(kCook, dir.file("stiff"), {"--set", "material[steel-like].E=500", "--set",
                                                                   "time.integrator=static"});
  EXPECT_NEAR(last(stiffer, "uy_C") / last(base, "uy_C"), 0.5, 1e-9);
  // A finer mesh through an array value.
  const ProbeTable fine = run_probes(kCook, dir.file("fine"), {"--set", "body[membrane].mesh.divisions=[24, 24]"});
  EXPECT_GT(last(fine, "uy_C"), last(base, "uy_C"));  // P1 stiffens less on a finer mesh
}

// The README's default scene ends with its probes against the references its file gives (probe[].reference).
TEST(Program, DefaultScenePrintsItsProbesAgainstTheReference) {
  TempDir dir("program_reference");
  const Command c = run_loom({"run", kSource + "/scenes/cooks_membrane.toml", "--out", dir.file("out")});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_NE(c.out.find("  uy_C        7.72169   (reference 7.771: -0.63 %)\n"), std::string::npos) << c.out;
  EXPECT_NE(c.out.find("  uy_M        7.37983   (reference 7.405: -0.34 %)\n"), std::string::npos) << c.out;
  EXPECT_NE(c.out.find("  reaction_y  -100\n"), std::string::npos) << c.out;  // no reference: the value alone
  // The locking baseline shows what it misses.
  const Command locked = run_loom({"run", kCook, "--out", dir.file("locked")});
  EXPECT_NE(locked.out.find("(reference 7.771: -72.66 %)"), std::string::npos) << locked.out;
}

TEST(Program, OutReplacesTheOutputDirectoryOfTheScene) {
  TempDir dir("program_out");
  const std::string from_scene = dir.file("from_scene"), from_cli = dir.file("from_cli");
  const Command c = run_loom({"run", kCook, "--quiet", "--set", "output.directory=" + from_scene, "--out", from_cli});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_FALSE(std::filesystem::exists(from_scene));
  for (const char* f : {"probes.csv", "run.json", "timings.json", "cooks-membrane-linear.pvd"})
    EXPECT_TRUE(std::filesystem::exists(from_cli + "/" + f)) << f;

  // Without --out the scene's directory is used.
  const Command d = run_loom({"run", kCook, "--quiet", "--set", "output.directory=" + from_scene});
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_TRUE(std::filesystem::exists(from_scene + "/probes.csv"));

  // A second run into the same directory replaces the files of the first (no appended rows or frames).
  ASSERT_EQ(run_loom({"run", kCook, "--quiet", "--out", from_cli, "--set", "time.steps=3"}).exit_code, 0);
  ASSERT_EQ(run_loom({"run", kCook, "--quiet", "--out", from_cli, "--set", "time.steps=2"}).exit_code, 0);
  EXPECT_EQ(read_probes(from_cli + "/probes.csv").rows.size(), 3u);
  EXPECT_EQ(parse_pvd(read_text(from_cli + "/cooks-membrane-linear.pvd")).size(), 3u);
  EXPECT_FALSE(std::filesystem::exists(from_cli + "/cooks-membrane-linear_000003.vtu"));  // stale frame removed
  EXPECT_EQ(parse_json(read_text(from_cli + "/run.json")).at("steps_done").number, 2.0);
}

// Progress on a log (stderr not a terminal): a plain line every LOOM_PROGRESS_SECONDS (10 s by default),
// here every 0.05 s of a run of about a second; --quiet prints none.
TEST(Program, ProgressLinesGoToALogWhenStderrIsNotATerminal) {
  TempDir dir("program_progress");
  const std::string scene = kSource + "/scenes/cooks_membrane_mpm_dynamic.toml";
  const std::string cmd = "LOOM_PROGRESS_SECONDS=0.05 " + std::string(LOOM_BINARY) + " run " + scene + " --out " + dir.file("out") +
                          " --set time.steps=12 --set output.every=0 --set body[0].particles_per_cell=3 >/dev/null 2>" + dir.file("err");
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(dir.file("err"));
  const std::string err = read_text(dir.file("err"));
  const std::regex line(R"(step ([0-9]+)/12  t = [0-9.e+-]+  newton [0-9]+  elapsed [0-9.]+ (ms|s)  remaining ~[0-9.]+ (ms|s)\n)");
  EXPECT_GE(std::distance(std::sregex_iterator(err.begin(), err.end(), line), std::sregex_iterator()), 2) << err;
}

// With --stop-after the line counts to that step, not to the scene's last: the remaining time is the run's.
TEST(Program, ProgressCountsToTheStepOfStopAfter) {
  TempDir dir("program_progress_stop_after");
  const std::string scene = kSource + "/scenes/cooks_membrane_mpm_dynamic.toml";
  const std::string cmd = "LOOM_PROGRESS_SECONDS=0.05 " + std::string(LOOM_BINARY) + " run " + scene + " --out " + dir.file("out") +
                          " --set time.steps=1000 --stop-after 12 --set output.every=0 --set body[0].particles_per_cell=3 >/dev/null 2>" +
                          dir.file("err");
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(dir.file("err"));
  const std::string err = read_text(dir.file("err"));
  const std::regex line(R"(step ([0-9]+)/12  t = )");
  EXPECT_GE(std::distance(std::sregex_iterator(err.begin(), err.end(), line), std::sregex_iterator()), 2) << err;
  EXPECT_EQ(err.find("/1000  t = "), std::string::npos) << err;
}

// Adaptive steps end at time.end: the line shows the time against it, and the remaining time follows from it.
TEST(Program, ProgressOfAdaptiveStepsCountsTime) {
  TempDir dir("program_progress_adaptive");
  const std::string scene = kSource + "/tests/scenes/es_pfem_bingham_column.toml";
  const std::string cmd = "LOOM_PROGRESS_SECONDS=0.01 " + std::string(LOOM_BINARY) + " run " + scene + " --out " + dir.file("out") +
                          " --set output.every=0 --set time.steps=1000 --set 'time.adaptive_dt={ probe = \"top\", expression = \"2e-3\" }'"
                          " --set time.end=0.06 >/dev/null 2>" + dir.file("err");
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(dir.file("err"));
  const std::string err = read_text(dir.file("err"));
  const std::regex line(R"(step ([0-9]+)  t = [0-9.e+-]+/0.06  newton [0-9]+  elapsed [0-9.]+ (ms|s)  remaining ~[0-9.]+ (ms|s)\n)");
  EXPECT_GE(std::distance(std::sregex_iterator(err.begin(), err.end(), line), std::sregex_iterator()), 2) << err;
  EXPECT_EQ(err.find("/1000"), std::string::npos) << err;
}

TEST(Program, RunPrintsTheTimingTableUnlessQuiet) {
  TempDir dir("program_table");
  const Command c = run_loom({"run", kCook, "--out", dir.path()});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  for (const char* s : {"system", "calls", "share", "newton", "commit", "output", "loom: 1 step,", "probes at step 1 (t = 1):", "  uy_C  "})
    EXPECT_NE(c.out.find(s), std::string::npos) << s << " not in:\n" << c.out;
  const Command q = run_loom({"run", kCook, "--out", dir.path(), "--quiet"});
  ASSERT_EQ(q.exit_code, 0);
  EXPECT_EQ(q.out, "");
  EXPECT_EQ(without_warnings(q.err), "");
}

// A frame is written while the next step runs; with one oneTBB thread the writer must still make progress
// (it once waited for a task that the only thread could not take: runs with frames and --threads 1 hung).
TEST(Program, OneThreadWithFramesEveryStepFinishes) {
  TempDir dir("program_one_thread_frames");
  const std::string cmd = "timeout 60 " + std::string(LOOM_BINARY) + " run " + kBase + " --threads 1 --quiet --out " + dir.path() +
                          " --set time.steps=6 --set output.every=1";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  ASSERT_EQ(WEXITSTATUS(status), 0) << "exit 124: loom hung (killed by timeout after 60 s)";
  EXPECT_EQ(parse_pvd(read_text(dir.file("malformed-base.pvd"))).size(), 7u);
}

// Assembly is coloured and reductions are ordered: the thread count must not change results (DESIGN §4).
TEST(Program, OneAndTwoThreadsGiveTheSameProbes) {
  TempDir dir("program_threads");
  const std::vector<std::pair<std::string, std::vector<std::string>>> scenes{
      {kCook, {"--set", "body[0].mesh.divisions=[32, 32]"}},
      {kBase, {"--set", "body[0].mesh.divisions=[24, 24]", "--set", "time.steps=4", "--set", "boundary[top].displacement.y=-0.1 * t"}}};
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    const auto& [scene, sets] = scenes[s];
    ProbeTable t[2];
    for (int threads : {1, 2}) {
      const std::string out = dir.file(std::to_string(s).append("_threads").append(std::to_string(threads)));
      std::vector<std::string> extra = sets;
      extra.insert(extra.end(), {"--threads", std::to_string(threads)});
      t[threads - 1] = run_probes(scene, out, extra);
      EXPECT_EQ(parse_json(read_text(out + "/run.json")).at("threads").number, threads);
    }
    ASSERT_EQ(t[0].names, t[1].names);
    ASSERT_EQ(t[0].rows.size(), t[1].rows.size());
    ASSERT_GT(t[0].rows.size(), 1u);
    for (std::size_t r = 0; r < t[0].rows.size(); ++r)
      for (std::size_t k = 0; k < t[0].names.size(); ++k)
        EXPECT_NEAR(t[0].rows[r][k], t[1].rows[r][k], 1e-12 * std::max(1.0, std::abs(t[0].rows[r][k])))
            << scene << " step " << r << " " << t[0].names[k];
  }
}

TEST(Program, BadCommandLinesExitWithCode2AndSayWhy) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {{}, "missing command"},
      {{"frobnicate", kCook}, "unknown command 'frobnicate'"},
      {{"run"}, "missing SCENE"},
      {{"run", kCook, "--bogus"}, "unknown option --bogus"},
      {{"run", kCook, "--threads", "0"}, "--threads needs a positive integer, got '0'"},
      {{"run", kCook, "--threads", "-2"}, "--threads needs a positive integer, got '-2'"},
      {{"run", kCook, "--threads", "two"}, "--threads needs a positive integer, got 'two'"},
      {{"run", kCook, "--threads", "2x"}, "--threads needs a positive integer, got '2x'"},
      {{"run", kCook, "--threads"}, "--threads needs a value"},
      {{"run", kCook, "--out"}, "--out needs a value"},
      {{"run", kCook, "extra.toml"}, "unexpected argument extra.toml"},
      {{"check", kCook, "--set", "time.dt"}, "--set time.dt: expected key.path=value"},
      {{"check", kCook, "--set", "=1"}, "--set =1: expected key.path=value"},
      {{"check", kCook, "--set", "body[3].mesh.divisions=[2, 2]"}, "body[3] does not exist (the scene has 1)"},
      {{"check", kCook, "--set", "boundary[nowhere].traction.y=1"}, "no [[boundary]] has name = \"nowhere\""},
      {{"check", kCook, "--set", "body[0.name=x"}, "missing ']'"},
      {{"check", kCook, "--set", "time..dt=1"}, "empty key in path"},
      {{"check", kCook, "--set", "scene.name.x=1"}, "'name' is not a table"},
      {{"check", kCook, "--set", "time[0].dt=1"}, "'time' is not an array of tables"},
      {{"check", kCook, "--set", "body[0]=1"}, "the path must end at a key"},
  };
  for (const auto& [args, message] : cases) {
    std::string shown = "loom";
    for (const auto& a : args) shown += " " + a;
    SCOPED_TRACE(shown);
    const Command c = run_loom(args);
    EXPECT_EQ(c.exit_code, 2);
    EXPECT_NE(c.err.find(message), std::string::npos) << "'" << message << "' not in:\n" << c.err;
    EXPECT_FALSE(looks_like_crash(c.err)) << c.err;
    EXPECT_EQ(c.out, "");
  }
}

// An output directory that cannot be written is bad input (exit 2), named by the option or key that gave it.
TEST(Program, OutputDirectoryThatCannotBeCreatedIsBadInput) {
  TempDir dir("program_unwritable");
  write_text(dir.file("a_file"), "");
  const Command c = run_loom({"run", kCook, "--quiet", "--out", dir.file("a_file") + "/out"});
  EXPECT_EQ(c.exit_code, 2) << c.err;
  EXPECT_NE(c.err.find("--out " + dir.file("a_file") + "/out: error: cannot create the output directory " + dir.file("a_file") + "/out"),
            std::string::npos) << c.err;
  EXPECT_FALSE(looks_like_crash(c.err)) << c.err;
  // From the scene: its file, line and key.
  const std::string scene = dir.file("scene.toml");
  std::string text = read_text(kCook);
  text.replace(text.find("[output]"), 8, "[output]\ndirectory = \"" + dir.file("a_file") + "/out\"");
  write_text(scene, text);
  const Command s = run_loom({"run", scene, "--quiet"});
  EXPECT_EQ(s.exit_code, 2) << s.err;
  EXPECT_NE(s.err.find(scene + ":"), std::string::npos) << s.err;
  EXPECT_NE(s.err.find(": output.directory: error: cannot create"), std::string::npos) << s.err;
}

TEST(Program, VersionAndHelpExitWithCode0) {
  const Command v = run_loom({"--version"});
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_EQ(v.out.rfind("loom ", 0), 0u);
  const Command h = run_loom({"--help"});
  EXPECT_EQ(h.exit_code, 0);
  EXPECT_NE(h.out.find("loom run SCENE"), std::string::npos);
}

}  // namespace
}  // namespace loom::testing
