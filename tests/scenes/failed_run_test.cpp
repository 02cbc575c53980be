// A run that cannot go on (DESIGN §5, §6): exit code 1, the failed step and the last converged step
// named on stderr, and the output of the converged steps intact (probes.csv rows, a valid .pvd that
// references existing frames, run.json with converged = false).
#include <gtest/gtest.h>

#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "tests/scenes/scene_checks.hpp"
#include "tests/support/test_support.hpp"

namespace loom::testing {
namespace {

// A Neo-Hooke block clamped at the bottom and the top, compressed by 0.5 % in steps 1 and 2, then by
// 95 % at once in step 3 (t >= 2.5, so the halved step fails as well): the cells at the corners invert.
// (Rollers would not do: the homogeneous compression is affine, and Newton solves it from the linear
// predictor even at 95 %.)
const char* kCrushed = R"(
[scene]
name = "crushed"

[time]
dt = 1.0
steps = 4

[solver]
max_iterations = 6
max_cutbacks = 1

[[material]]
name = "rubber"
model = "neo_hooke"
E = 10.0
nu = 0.3

[[body]]
name = "block"
material = "rubber"
mesh = { generator = "rectangle", size = [1.0, 1.0], divisions = [6, 6], pattern = "alternating" }

[[boundary]]
name = "bottom"
region = { box = [[0.0, 0.0], [1.0, 0.0]] }
displacement = { x = 0.0, y = 0.0 }

[[boundary]]
name = "top"
region = { box = [[0.0, 1.0], [1.0, 1.0]] }
displacement = { x = 0.0, y = "t < 2.5 ? -0.005 * t : -0.95" }

[[probe]]
name = "reaction_top"
kind = "reaction"
boundary = "top"
component = "y"

[[probe]]
name = "newton"
kind = "newton"
)";

void expect_intact_output(const std::string& dir, const std::string& stem, std::size_t probe_rows) {
  // probes.csv keeps the rows of the converged steps, and nothing else.
  const ProbeTable probes = read_probes(dir + "/probes.csv");
  ASSERT_EQ(probes.rows.size(), probe_rows);
  for (std::size_t r = 0; r < probe_rows; ++r) {
    EXPECT_EQ(probes.rows[r][0], double(r));
    for (double v : probes.rows[r]) EXPECT_TRUE(std::isfinite(v));
  }
  // The .pvd is well-formed and every frame it lists exists and reads back.
  const auto entries = parse_pvd(read_text(dir + "/" + stem + ".pvd"));
  ASSERT_FALSE(entries.empty());
  for (const auto& e : entries) {
    ASSERT_TRUE(std::filesystem::exists(dir + "/" + e.file)) << e.file;
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName((dir + "/" + e.file).c_str());
    reader->Update();
    EXPECT_EQ(reader->GetErrorCode(), 0) << e.file;
    EXPECT_GT(reader->GetOutput()->GetNumberOfPoints(), 0) << e.file;
    EXPECT_LE(e.time, double(probe_rows - 1) + 1e-12) << "a frame of a step that did not converge: " << e.file;
  }
  for (const auto& f : files_under(dir)) EXPECT_EQ(f.find(".tmp"), std::string::npos) << f;
}

TEST(FailedRun, NewtonGivesUpWithExitCode1AndKeepsTheConvergedOutput) {
  TempDir dir("failed_newton");
  write_text(dir.file("crushed.toml"), kCrushed);
  const std::string out = dir.file("out");
  const Command c = run_loom({"run", dir.file("crushed.toml"), "--out", out});
  ASSERT_EQ(c.exit_code, 1) << c.out << c.err;
  EXPECT_FALSE(looks_like_crash(c.err)) << c.err;
  EXPECT_NE(c.err.find("loom: the run failed: step 3 did not converge after 1 cut-backs"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("loom: last converged step 2 (t = 2)"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find(out), std::string::npos) << "stderr should say where the output is:\n" << c.err;
  // Each attempt is reported as it is cut back.
  EXPECT_NE(c.err.find("step 3 (t = 3, dt = 1): "), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("step 3 (t = 2.5, dt = 0.5): "), std::string::npos) << c.err;

  expect_intact_output(out, "crushed", 3);
  const Json run = parse_json(read_text(out + "/run.json"));
  EXPECT_FALSE(run.at("converged").boolean);
  EXPECT_EQ(run.at("last_converged_step").number, 2.0);
  EXPECT_EQ(run.at("last_converged_time").number, 2.0);
  EXPECT_EQ(run.at("steps_done").number, 2.0);
  EXPECT_EQ(run.at("steps_requested").number, 4.0);
  EXPECT_EQ(run.at("cutbacks").number, 1.0);
  EXPECT_NE(run.at("failure").string.find("step 3"), std::string::npos);
  EXPECT_TRUE(parse_json(read_text(out + "/timings.json")).has("timers"));
}

// --quiet prints no line per cut-back: the failure and the run's count of cut-backs say what happened.
TEST(FailedRun, QuietPrintsNoCutBackLinesButCountsThem) {
  TempDir dir("failed_quiet");
  write_text(dir.file("crushed.toml"), kCrushed);
  const Command c = run_loom({"run", dir.file("crushed.toml"), "--out", dir.file("out"), "--quiet"});
  ASSERT_EQ(c.exit_code, 1) << c.err;
  EXPECT_EQ(c.err.find("cutting the step back"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("loom: the run failed: step 3 did not converge after 1 cut-backs"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("; 1 cut-back in the run; "), std::string::npos) << c.err;
  const Command loud = run_loom({"run", dir.file("crushed.toml"), "--out", dir.file("loud")});
  EXPECT_NE(loud.err.find("cutting the step back"), std::string::npos) << loud.err;
}

TEST(FailedRun, ConvergedSubStepsOfTheFailedStepAreKeptAsALastFrame) {
  // 50 % more compression per step from step 2 on: some step fails after some of its halved sub-steps
  // converged. The state they reached is written as a last frame, after the probes of the last
  // converged step; whichever step it is, the output must say so consistently.
  TempDir dir("failed_substep");
  std::string text = kCrushed;
  const std::string from = "\"t < 2.5 ? -0.005 * t : -0.95\"", to = "\"t <= 1 ? -0.005 * t : -0.005 - 0.5 * (t - 1)\"";
  text.replace(text.find(from), from.size(), to);
  write_text(dir.file("crushed.toml"), text);
  const std::string out = dir.file("out");
  const Command c = run_loom({"run", dir.file("crushed.toml"), "--out", out, "--quiet", "--set", "solver.max_cutbacks=3",
                              "--set", "solver.max_iterations=5"});
  ASSERT_EQ(c.exit_code, 1) << c.err;
  const Json run = parse_json(read_text(out + "/run.json"));
  EXPECT_FALSE(run.at("converged").boolean);
  const int n = int(run.at("last_converged_step").number);
  const double t = run.at("last_converged_time").number;
  ASSERT_GE(n, 1);
  EXPECT_NE(c.err.find("loom: the run failed: step " + std::to_string(n + 1) + " did not converge after 3 cut-backs"),
            std::string::npos) << c.err;
  EXPECT_NE(c.err.find("loom: last converged step " + std::to_string(n) + " (t = " + std::to_string(n) + ")"), std::string::npos)
      << c.err;
  ASSERT_GT(t, n) << "no sub-step converged: the scene no longer tests what it says";
  ASSERT_LT(t, n + 1);
  EXPECT_NE(c.err.find("sub-steps of the failed step converged up to t = "), std::string::npos) << c.err;

  EXPECT_EQ(read_probes(out + "/probes.csv").rows.size(), std::size_t(n + 1));
  const auto entries = parse_pvd(read_text(out + "/crushed.pvd"));
  ASSERT_EQ(entries.size(), std::size_t(n + 2));  // steps 0..n and the sub-step state
  EXPECT_EQ(entries.back().time, t);
  for (const auto& e : entries) {
    ASSERT_TRUE(std::filesystem::exists(out + "/" + e.file)) << e.file;
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName((out + "/" + e.file).c_str());
    reader->Update();
    EXPECT_EQ(reader->GetErrorCode(), 0) << e.file;
  }
}

TEST(FailedRun, ExpressionThatIsNotFiniteStopsTheRunNamingTheKey) {
  // 1 / (t < 2.5) divides by zero from step 3 on: a run-time failure (exit 1) naming the scene position.
  TempDir dir("failed_expression");
  std::string text = kCrushed;
  const std::string from = "\"t < 2.5 ? -0.005 * t : -0.95\"", to = "\"-0.005 * t / (t < 2.5)\"";
  text.replace(text.find(from), from.size(), to);
  const std::string scene = dir.file("crushed.toml");
  write_text(scene, text);
  const std::string out = dir.file("out");
  const Command c = run_loom({"run", scene, "--out", out, "--quiet"});
  ASSERT_EQ(c.exit_code, 1) << c.err;
  EXPECT_FALSE(looks_like_crash(c.err)) << c.err;
  const auto at = text.find(to);
  const auto line_start = text.rfind('\n', at) + 1;
  const std::string where = scene + ":" + std::to_string(1 + std::count(text.begin(), text.begin() + long(at), '\n')) + ":" +
                            std::to_string(at - line_start + 1) + ": boundary[1].displacement.y: ";
  EXPECT_NE(c.err.find(where), std::string::npos) << where << " not in:\n" << c.err;
  EXPECT_NE(c.err.find("loom: the run failed: step 3 stopped: in system apply_boundary_conditions: "), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("is not finite at t = 3"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("loom: last converged step 2 (t = 2); "), std::string::npos) << c.err;
  expect_intact_output(out, "crushed", 3);
  const Json run = parse_json(read_text(out + "/run.json"));
  EXPECT_FALSE(run.at("converged").boolean);
  EXPECT_EQ(run.at("last_converged_step").number, 2.0);
}

TEST(FailedRun, ExpressionThatIsNotFiniteAtTheStartNamesTheKey) {
  // -0.005 / t is -inf at t = 0: the initial state cannot be set up; run.json still records the failure.
  TempDir dir("failed_start");
  std::string text = kCrushed;
  const std::string from = "\"t < 2.5 ? -0.005 * t : -0.95\"", to = "\"-0.005 / t\"";
  text.replace(text.find(from), from.size(), to);
  const std::string scene = dir.file("crushed.toml");
  write_text(scene, text);
  const Command c = run_loom({"run", scene, "--out", dir.file("out"), "--quiet"});
  EXPECT_EQ(c.exit_code, 1) << c.err;
  EXPECT_FALSE(looks_like_crash(c.err)) << c.err;
  EXPECT_NE(c.err.find("boundary[1].displacement.y: expression \"-0.005 / t\" is not finite at t = 0"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find(scene + ":"), std::string::npos) << c.err;
  const Json run = parse_json(read_text(dir.file("out") + "/run.json"));
  EXPECT_FALSE(run.at("converged").boolean);
  EXPECT_EQ(run.at("last_converged_step").number, 0.0);
  EXPECT_EQ(run.at("steps_done").number, 0.0);
}

}  // namespace
}  // namespace loom::testing
