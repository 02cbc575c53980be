// Helpers shared by the tests: build and run scenes from text, run the loom program, temporary dirs.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/methods/recipes/fem_method.hpp"
#include "engine/methods/recipes/mpm_method.hpp"
#include "engine/scene/scene_spec.hpp"

namespace loom::testing {

// Parses a scene given as text (the label names it in messages).
SceneSpec scene_from_text(const std::string& text, const std::vector<std::string>& overrides = {});

// Builds an FemRun that writes no files (output_directory empty) unless `out` is given.
template <int D = 2>
std::unique_ptr<FemRunT<D>> make_fem_run(const SceneSpec& scene, const std::string& out = "");
// Same for an MpmRun (method mpm).
template <int D = 2>
std::unique_ptr<MpmRunT<D>> make_mpm_run(const SceneSpec& scene, const std::string& out = "");

struct Command {
  int exit_code = -1;
  std::string out, err;
};
// Runs the loom program with the arguments (each quoted for the shell), capturing both streams.
Command run_loom(const std::vector<std::string>& args);

// A fresh empty directory under the build tree's temporary area, removed at destruction.
class TempDir {
 public:
  explicit TempDir(const std::string& name);
  ~TempDir();
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

void write_text(const std::string& path, const std::string& text);
std::string read_text(const std::string& path);

// Reads probes.csv into columns by name.
struct ProbeTable {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  std::vector<double> column(const std::string& name) const;
};
ProbeTable read_probes(const std::string& path);

// Runs a mesh-based scene (fem, pfem, es_pfem; fem in 3D) writing into a temporary directory `name` and returns its probes;
// the run's summary goes to `summary` when given.
ProbeTable run_for_probes(const SceneSpec& scene, const std::string& name, RunSummary* summary = nullptr);

}  // namespace loom::testing
