#include "tests/stress/stress_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

namespace loom::stress {

std::string scene_path(const std::string& file) { return std::string(LOOM_SOURCE_DIR) + "/scenes/" + file; }
std::string stress_scene(const std::string& file) { return std::string(LOOM_SOURCE_DIR) + "/tests/stress/scenes/" + file; }

std::string format(double v, int digits) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

Outcome run_checked(const std::string& scene, const std::string& out, const std::vector<std::string>& extra) {
  std::vector<std::string> args{"run", scene, "--out", out, "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  const testing::Command c = testing::run_loom(args);
  Outcome o;
  o.exit_code = c.exit_code;
  o.err = c.err;
  auto unclean = [&](const std::string& why) {
    if (o.why_unclean.empty()) o.why_unclean = why;
  };
  if (testing::looks_like_crash(c.err)) unclean("crash or internal error on stderr");
  if (c.exit_code != 0 && c.exit_code != 1) unclean("exit code " + std::to_string(c.exit_code));
  if (!std::filesystem::exists(out + "/run.json") || !std::filesystem::exists(out + "/probes.csv")) {
    unclean("run.json or probes.csv missing");
  } else {
    const testing::Json run = testing::parse_json(testing::read_text(out + "/run.json"));
    o.converged = run.at("converged").boolean;
    o.last_converged_step = int(run.at("last_converged_step").number);
    o.steps_requested = int(run.at("steps_requested").number);
    o.newton_iterations = (long long)run.at("newton_iterations").number;
    o.cutbacks = int(run.at("cutbacks").number);
    o.wall_seconds = run.at("wall_seconds").number;
    o.failure = run.at("failure").string;
    o.probes = testing::read_probes(out + "/probes.csv");
    for (const auto& row : o.probes.rows)
      for (double v : row)
        if (!std::isfinite(v)) unclean("a non-finite probe value in probes.csv (step " + format(row[0]) + ")");
    if (c.exit_code == 0) {
      if (!o.converged) unclean("exit code 0 but run.json says converged = false");
      if (o.probes.rows.size() != std::size_t(o.steps_requested) + 1) unclean("probes.csv does not hold every step");
    } else if (c.exit_code == 1) {
      if (o.converged) unclean("exit code 1 but run.json says converged = true");
      const std::string said = "loom: last converged step " + std::to_string(o.last_converged_step) + " (t = ";
      if (c.err.find("loom: the run failed: ") == std::string::npos) unclean("stderr does not say that the run failed");
      if (c.err.find(said) == std::string::npos) unclean("stderr does not name the last converged step as run.json does");
      if (o.failure.empty()) unclean("run.json names no failure");
      if (o.probes.rows.size() != std::size_t(o.last_converged_step) + 1) unclean("probes.csv rows do not end at the last converged step");
    }
  }
  o.clean = o.why_unclean.empty();
  EXPECT_TRUE(o.clean) << scene << ": " << o.why_unclean << "\nexit " << c.exit_code << "\nstderr:\n" << c.err;
  return o;
}

double last(const Outcome& o, const std::string& probe) {
  if (o.probes.rows.empty()) return std::numeric_limits<double>::quiet_NaN();
  return o.probes.column(probe).back();
}

ThreadComparison run_with_one_and_two_threads(const std::string& scene, const std::vector<std::string>& sets) {
  ThreadComparison t;
  for (int threads : {1, 2}) {
    testing::TempDir out("stress_threads_" + std::to_string(threads));
    std::vector<std::string> args{"--threads", std::to_string(threads)};
    for (const auto& s : sets) args.insert(args.end(), {"--set", s});
    (threads == 1 ? t.one : t.two) = run_checked(scene, out.path(), args);
  }
  t.same_shape = t.one.probes.rows.size() == t.two.probes.rows.size();
  for (std::size_t r = 0; t.same_shape && r < t.one.probes.rows.size(); ++r)
    for (std::size_t k = 0; k < t.one.probes.rows[r].size(); ++k) {
      const double a = t.one.probes.rows[r][k], b = t.two.probes.rows[r][k];
      t.worst = std::max(t.worst, a == b ? 0.0 : std::abs(a - b) / std::max(std::abs(a), std::abs(b)));
    }
  return t;
}

std::string ThreadComparison::detail() const {
  return "worst relative difference of the probes " + format(worst, 2) + "; Newton " + std::to_string(one.newton_iterations) +
         " / " + std::to_string(two.newton_iterations) + "; wall " + format(one.wall_seconds, 3) + " s / " +
         format(two.wall_seconds, 3) + " s";
}

namespace {
std::string csv_cell(std::string s) {
  for (char& ch : s)
    if (ch == '\n' || ch == '|') ch = ' ';
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string q = "\"";
  for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}
}  // namespace

void record(const std::string& group, const std::string& case_name, const Outcome& o, const std::string& detail,
            const std::string& check) {
  std::string outcome;
  if (o.exit_code == -1 && o.clean) outcome = "not run";
  else if (!o.clean) outcome = "UNCLEAN: " + o.why_unclean;
  else if (o.converged) outcome = o.cutbacks ? "converged, " + std::to_string(o.cutbacks) + " cut-backs" : "converged";
  else outcome = "failed cleanly after step " + std::to_string(o.last_converged_step) + ": " + o.failure;
  std::printf("[stress] %s | %s | %s | %s | %s\n", group.c_str(), case_name.c_str(), outcome.c_str(), detail.c_str(), check.c_str());
  const char* path = std::getenv("LOOM_STRESS_CSV");
  if (!path || !*path) return;
  const bool fresh = !std::filesystem::exists(path);
  std::ostringstream row;
  if (fresh) row << "group,case,outcome,exit,steps,detail,check\n";
  row << csv_cell(group) << "," << csv_cell(case_name) << "," << csv_cell(outcome) << "," << o.exit_code << ","
      << o.last_converged_step << "/" << o.steps_requested << "," << csv_cell(detail) << "," << csv_cell(check) << "\n";
  std::ofstream(path, std::ios::app) << row.str();  // one short append per case
}

}  // namespace loom::stress
