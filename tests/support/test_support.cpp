#include "tests/support/test_support.hpp"
#include "tests/support/run_comparison.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "engine/scene/scene_loader.hpp"

namespace loom::testing {

SceneSpec scene_from_text(const std::string& text, const std::vector<std::string>& overrides) {
  return load_scene_text(text, "test.toml", overrides);
}

template <int D>
std::unique_ptr<FemRunT<D>> make_fem_run(const SceneSpec& scene, const std::string& out) {
  RunOptions options;
  options.output_directory = out;
  options.write_files = !out.empty();
  options.progress = false;
  return std::make_unique<FemRunT<D>>(scene, options);
}
template std::unique_ptr<FemRunT<2>> make_fem_run<2>(const SceneSpec&, const std::string&);
template std::unique_ptr<FemRunT<3>> make_fem_run<3>(const SceneSpec&, const std::string&);

template <int D>
std::unique_ptr<MpmRunT<D>> make_mpm_run(const SceneSpec& scene, const std::string& out) {
  RunOptions options;
  options.output_directory = out;
  options.write_files = !out.empty();
  options.progress = false;
  return std::make_unique<MpmRunT<D>>(scene, options);
}
template std::unique_ptr<MpmRunT<2>> make_mpm_run<2>(const SceneSpec&, const std::string&);
template std::unique_ptr<MpmRunT<3>> make_mpm_run<3>(const SceneSpec&, const std::string&);

std::string shell_quote(const std::string& s) {
  std::string r = "'";
  for (char c : s) {
    if (c == '\'') r += "'\\''";
    else r += c;
  }
  return r + "'";
}

Command run_loom(const std::vector<std::string>& args) {
  static int counter = 0;
  const std::string base = std::filesystem::temp_directory_path().string() + "/loom_cmd_" + std::to_string(getpid()) + "_" +
                           std::to_string(counter++);
  std::string cmd = shell_quote(LOOM_BINARY);
  for (const auto& a : args) cmd += " " + shell_quote(a);
  cmd += " >" + shell_quote(base + ".out") + " 2>" + shell_quote(base + ".err");
  const int status = std::system(cmd.c_str());
  Command c;
  c.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  c.out = read_text(base + ".out");
  c.err = read_text(base + ".err");
  std::filesystem::remove(base + ".out");
  std::filesystem::remove(base + ".err");
  return c;
}

TempDir::TempDir(const std::string& name) {
  path_ = std::filesystem::temp_directory_path().string() + "/loom_test_" + name + "_" + std::to_string(getpid());
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<double> ProbeTable::column(const std::string& name) const {
  for (std::size_t k = 0; k < names.size(); ++k)
    if (names[k] == name) {
      std::vector<double> c;
      for (const auto& r : rows) c.push_back(r[k]);
      return c;
    }
  throw std::runtime_error("no probe column " + name);
}

ProbeTable read_probes(const std::string& path) {
  ProbeTable t;
  std::istringstream in(read_text(path));
  std::string line;
  if (!std::getline(in, line)) return t;
  std::istringstream header(line);
  for (std::string cell; std::getline(header, cell, ',');) t.names.push_back(cell);
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::vector<double> values;
    for (std::string cell; std::getline(row, cell, ',');) values.push_back(std::stod(cell));
    t.rows.push_back(values);
  }
  return t;
}

double probe_difference(const ProbeTable& a, const ProbeTable& b) {
  EXPECT_EQ(a.names, b.names);
  EXPECT_EQ(a.rows.size(), b.rows.size());
  double worst = 0.0;
  for (const std::string& name : a.names) {
    if (name == "step" || name == "time") continue;
    const std::vector<double> x = a.column(name), y = b.column(name);
    double scale = 0.0, difference = 0.0;
    for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
      scale = std::max(scale, std::abs(x[i]));
      difference = std::max(difference, std::abs(x[i] - y[i]));
    }
    if (scale > 1e-12) worst = std::max(worst, difference / scale);
    else if (difference > 1e-12) worst = INFINITY;
  }
  return worst;
}

ProbeTable run_for_probes(const SceneSpec& scene, const std::string& name, RunSummary* summary) {
  TempDir dir(name);
  const RunSummary done = scene.scene.dimension == 3 ? make_fem_run<3>(scene, dir.path())->run() : make_fem_run(scene, dir.path())->run();
  if (summary) *summary = done;
  return read_probes(dir.file("probes.csv"));
}

}  // namespace loom::testing
