// Bad scenes fail early and point at the scene (DESIGN §5, STYLE §6): every file of malformed/ is a
// variation of base.toml with one defect, and `loom check` and `loom run` must both exit with code 2
// and a message naming file:line:column and the key path, without crashing and without writing output.
//
// Each case states what it expects in its own header, so adding a case is adding a file:
//   # expect-key: body[0].mesh.divisons          (each must appear in stderr)
//   # expect-message: did you mean 'divisions'   (each must appear in stderr)
//   ... a line ending in `# <-- error (column 8, 75)`: stderr must name file:<that line>:8 and :75.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <sstream>

#include "tests/scenes/scene_checks.hpp"
#include "tests/support/test_support.hpp"

namespace loom::testing {
namespace {

const std::string kMalformedDir = std::string(LOOM_SOURCE_DIR) + "/tests/scenes/malformed";
const std::string kBase = std::string(LOOM_SOURCE_DIR) + "/tests/scenes/base.toml";

struct Expectation {
  std::vector<std::string> keys, messages;
  std::vector<std::pair<int, int>> positions;  // line, column
};

Expectation expectations_of(const std::string& path) {
  Expectation e;
  std::istringstream in(read_text(path));
  const std::regex marker(R"(#\s*<-- error \(column ([0-9, ]+)\)\s*$)");
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.rfind("# expect-key: ", 0) == 0) e.keys.push_back(line.substr(14));
    if (line.rfind("# expect-message: ", 0) == 0) e.messages.push_back(line.substr(18));
    std::smatch m;
    if (line[0] != '#' && std::regex_search(line, m, marker)) {
      std::istringstream cols(m[1].str());
      for (std::string c; std::getline(cols, c, ',');) e.positions.emplace_back(n, std::stoi(c));
    }
  }
  return e;
}

std::vector<std::string> malformed_cases() {
  std::vector<std::string> r;
  for (const auto& entry : std::filesystem::directory_iterator(kMalformedDir))
    if (entry.path().extension() == ".toml") r.push_back(entry.path().stem().string());
  std::sort(r.begin(), r.end());
  return r;
}

// Every line of the report is "file:line:column: error: ..." (or "file: error: ..." without position).
void expect_report_format(const std::string& err, const std::string& file) {
  std::istringstream in(err);
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    EXPECT_EQ(line.rfind(file + ":", 0), 0u) << "a line of the report does not start with the scene file: " << line;
    EXPECT_NE(line.find(": error: "), std::string::npos) << line;
  }
}

class MalformedScene : public ::testing::TestWithParam<std::string> {};

TEST_P(MalformedScene, CheckAndRunExitWithCode2NamingLineColumnAndKey) {
  const std::string file = kMalformedDir + "/" + GetParam() + ".toml";
  const Expectation want = expectations_of(file);
  ASSERT_FALSE(want.positions.empty()) << file << " marks no line with '# <-- error (column c)'";
  ASSERT_FALSE(want.messages.empty()) << file << " states no '# expect-message:'";

  TempDir out("malformed_" + GetParam());
  const std::string out_dir = out.file("out");
  for (const auto& args :
       std::vector<std::vector<std::string>>{{"check", file}, {"info", file}, {"run", file, "--out", out_dir, "--quiet"}}) {
    SCOPED_TRACE("loom " + args[0] + " " + file);
    const Command c = run_loom(args);
    EXPECT_EQ(c.exit_code, 2) << c.err;
    EXPECT_FALSE(looks_like_crash(c.err)) << c.err;
    EXPECT_EQ(c.out, "") << "nothing on stdout for a bad scene";
    expect_report_format(c.err, file);
    for (const auto& [line, column] : want.positions) {
      const std::string where = file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": error: ";
      EXPECT_NE(c.err.find(where), std::string::npos) << "expected a message at " << where << "\ngot:\n" << c.err;
    }
    for (const auto& k : want.keys) EXPECT_NE(c.err.find(k + ": "), std::string::npos) << "key " << k << " not named in:\n" << c.err;
    for (const auto& m : want.messages) EXPECT_NE(c.err.find(m), std::string::npos) << "'" << m << "' not in:\n" << c.err;
  }
  // Validation comes before any store or file: a bad scene leaves no output directory behind.
  EXPECT_FALSE(std::filesystem::exists(out_dir)) << "loom run created " << out_dir << " for a bad scene";
}

INSTANTIATE_TEST_SUITE_P(Files, MalformedScene, ::testing::ValuesIn(malformed_cases()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

TEST(MalformedScenes, CoverAtLeastFourteenCases) { EXPECT_GE(malformed_cases().size(), 14u); }

TEST(MalformedScenes, BaseSceneIsValidAndRuns) {
  const Command check = run_loom({"check", kBase});
  EXPECT_EQ(check.exit_code, 0) << check.err;
  EXPECT_EQ(check.out, kBase + ": ok\n");
  TempDir out("malformed_base");
  const Command run = run_loom({"run", kBase, "--out", out.path(), "--quiet"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(read_probes(out.file("probes.csv")).rows.size(), 3u);
}

TEST(MalformedScenes, EveryErrorIsReportedAtOnceInFileOrder) {
  TempDir dir("malformed_many");
  std::string text = read_text(kBase);
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"dt = 1.0", "dt = 0.0"}, {"nu = 0.3", "nu = 0.7"}, {"component = \"y\"", "component = \"w\""}}) {
    ASSERT_NE(text.find(from), std::string::npos);
    text.replace(text.find(from), from.size(), to);
  }
  const std::string file = dir.file("many.toml");
  write_text(file, text);
  const Command c = run_loom({"check", file});
  EXPECT_EQ(c.exit_code, 2);
  const auto dt = c.err.find(file + ":10:6: error: time.dt: must be > 0"), nu = c.err.find(file + ":20:6: error: material[0].nu:"),
             comp = c.err.find(file + ":41:13: error: probe[0].component: \"w\" is not one of: x, y, z");
  ASSERT_NE(dt, std::string::npos) << c.err;
  ASSERT_NE(nu, std::string::npos) << c.err;
  ASSERT_NE(comp, std::string::npos) << c.err;
  EXPECT_LT(dt, nu);
  EXPECT_LT(nu, comp);
}

TEST(MalformedScenes, ValueFromSetIsValidatedAndNamesTheCommandLine) {
  const Command c = run_loom({"check", kBase, "--set", "time.dt=-2"});
  EXPECT_EQ(c.exit_code, 2);
  EXPECT_NE(c.err.find("command line (--set): error: time.dt: must be > 0, got -2"), std::string::npos) << c.err;
  const Command typo = run_loom({"check", kBase, "--set", "body[block].mesh.divisons=[2, 2]"});
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_NE(typo.err.find("body[0].mesh.divisons: unknown key (did you mean 'divisions'?)"), std::string::npos) << typo.err;
}

TEST(MalformedScenes, MissingOrUnreadableSceneFile) {
  TempDir dir("malformed_missing");
  for (const auto& [path, why] : std::vector<std::pair<std::string, std::string>>{
           {dir.file("no_such_scene.toml"), "cannot read the scene file"}, {dir.path(), "it is a directory"}}) {
    for (const char* command : {"check", "run", "info"}) {
      const Command c = run_loom({command, path, "--quiet"});
      EXPECT_EQ(c.exit_code, 2) << command << " " << path;
      EXPECT_EQ(c.err.rfind(path + ": error: ", 0), 0u) << c.err;
      EXPECT_NE(c.err.find(why), std::string::npos) << c.err;
      EXPECT_FALSE(looks_like_crash(c.err)) << c.err;
    }
  }
}

TEST(MalformedScenes, EmptyFileReportsMissingTablesAtLineOne) {
  TempDir dir("malformed_empty");
  write_text(dir.file("empty.toml"), "");
  const Command c = run_loom({"check", dir.file("empty.toml")});
  EXPECT_EQ(c.exit_code, 2);
  for (const char* key : {"scene", "time", "material", "body"})
    EXPECT_NE(c.err.find(dir.file("empty.toml") + ":1:1: error: " + key + ": missing required"), std::string::npos) << c.err;
}

}  // namespace
}  // namespace loom::testing
