// Helpers of the verification tests: committed scenes by path, a run of a scene with its probes by name,
// and SteppedFem, which drives the fem recipe's own systems step by step so that a test can read each
// step's Newton residual history (FemRun keeps only iteration counts; see the note in
// cooks_membrane_neo_hooke_test.cpp).
#pragma once

#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/drivers/newton.hpp"
#include "engine/methods/build_boundary_conditions.hpp"
#include "engine/methods/build_mesh.hpp"
#include "engine/methods/fem_method.hpp"
#include "engine/methods/fem_newton_problem.hpp"
#include "engine/scene/scene_loader.hpp"
#include "systems/assemble/compute_geometry.hpp"
#include "systems/loads/apply_boundary_conditions.hpp"
#include "systems/update/commit_step.hpp"
#include "systems/update/update_iterate.hpp"
#include "tests/support/test_support.hpp"

namespace loom::verification {

inline std::string scene_path(const std::string& file) { return std::string(LOOM_SOURCE_DIR) + "/scenes/" + file; }

inline double relative_error(double value, double reference) {
  return std::abs(value - reference) / std::abs(reference);
}

// The end state of a run: its summary, the probes of the last step by name, the nodal displacements.
struct SceneResult {
  RunSummary summary;
  std::map<std::string, double> probes;
  std::vector<Vec2> u;
  double seconds = 0.0;
};

inline SceneResult run_scene(const SceneSpec& scene) {
  const auto start = std::chrono::steady_clock::now();
  auto run = testing::make_fem_run(scene);
  SceneResult r;
  r.summary = run->run();
  for (std::size_t k = 0; k < scene.probes.size(); ++k) r.probes[scene.probes[k].name] = run->probe_values()[k];
  for (Index i = 0; i < run->nodes().size(); ++i) r.u.push_back(run->nodes().u_n[i]);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// The static fem recipe without its graph: the same builders and systems, called in the order of
// FemRun's graph (apply_boundary_conditions -> newton -> commit), one whole step at a time (no cut-back).
class SteppedFem {
 public:
  explicit SteppedFem(const SceneSpec& scene) : scene_(scene), solver_(scene.solver.linear) {
    if (scene_.time.integrator != Integrator::static_) throw std::runtime_error("SteppedFem: static scenes only");
    ctx_.scene = &scene_;
    node_body_ = build_mesh(scene_, nodes_, cells_);
    materials_ = body_materials(scene_);
    allocate_quad_points(cells_, quad_);
    if (compute_geometry(nodes_, cells_, quad_) != 0) throw std::runtime_error("SteppedFem: inverted mesh");
    bc_ = build_boundary_conditions(scene_, nodes_, cells_, node_body_, 2);
    system_.dofs.build(2, dof_kinds(bc_, nodes_.size(), 2));
    std::vector<const Cells*> blocks;
    for (const auto& c : cells_) blocks.push_back(&c);
    build_pattern(blocks, system_.dofs, system_.pattern);
    system_.scatter.resize(cells_.size());
    for (std::size_t b = 0; b < cells_.size(); ++b) build_scatter(cells_[b], system_.dofs, system_.pattern, system_.scatter[b]);
    system_.resize_vectors();
  }

  // Solves the next scene step; commits it if Newton converged.
  NewtonReport step() {
    ++ctx_.step;
    ctx_.dt = scene_.time.dt;
    ctx_.t = ctx_.step * scene_.time.dt;
    ctx_.step_end = true;
    apply_boundary_conditions(ctx_, nodes_, cells_, materials_, bc_);
    reset_iterate(nodes_);
    NewtonSettings settings;
    settings.max_iterations = scene_.solver.max_iterations;
    settings.residual_relative = scene_.solver.residual_relative;
    settings.residual_absolute = scene_.solver.residual_absolute;
    settings.increment_relative = scene_.solver.increment_relative;
    settings.line_search = scene_.solver.line_search;
    FemNewtonProblem problem(ctx_, materials_, cells_, bc_, nodes_, quad_, system_, solver_, timers_);
    NewtonReport report = solve_newton(problem, settings, timers_);
    if (report.converged) commit_step(ctx_, cells_, nodes_, quad_);
    return report;
  }

  const Nodes<2>& nodes() const { return nodes_; }
  Index dofs() const { return system_.dofs.n_free; }
  Index nearest_node(const Vec2& X) const {
    Index best = kNoIndex;
    double best_d = std::numeric_limits<double>::max();
    for (Index i = 0; i < nodes_.size(); ++i)
      if ((nodes_.X[i] - X).squaredNorm() < best_d) best_d = (nodes_.X[i] - X).squaredNorm(), best = i;
    return best;
  }

 private:
  SceneSpec scene_;
  StepContext ctx_;
  Timers timers_;
  Nodes<2> nodes_;
  std::vector<Cells> cells_;
  std::vector<QuadPoints<2>> quad_;
  std::vector<BodyMaterial> materials_;
  BoundaryConditions<2> bc_;
  LinearSystem system_;
  LinearSolve solver_;
  std::vector<Index> node_body_;
};

}  // namespace loom::verification
