// Helpers of the verification tests: committed scenes by path, a run of a scene with its probes by name,
// and SteppedFem, which drives the fem recipe's own systems step by step so that a test can read each
// step's Newton residual history (FemRun keeps only iteration counts; see the note in
// cooks_membrane_neo_hooke_test.cpp).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/drivers/newton.hpp"
#include "engine/methods/model/fem_model.hpp"
#include "engine/methods/recipes/fem_method.hpp"
#include "engine/methods/recipes/fem_newton_problem.hpp"
#include "engine/scene/scene_loader.hpp"
#include "systems/loads/apply_boundary_conditions.hpp"
#include "systems/update/commit_step.hpp"
#include "systems/update/update_iterate.hpp"
#include "tests/support/test_support.hpp"

namespace loom::verification {

inline std::string scene_path(const std::string& file) { return std::string(LOOM_SOURCE_DIR) + "/scenes/" + file; }

inline double relative_error(double value, double reference) {
  return std::abs(value - reference) / std::abs(reference);
}

// The planar Bingham Poiseuille flow between plates at y = +-H, driven by a body force F per unit volume along x
// (viscosity mu, yield stress tau0 in simple shear): the plug |y| <= y0 = tau0 / F moves at the velocity of y0, and
// u(y) = F / (2 mu) (H^2 - a^2) - tau0 / mu (H - a) with a = max(|y|, y0).
inline double bingham_poiseuille_velocity(double y, double tau0, double F, double mu, double H) {
  const double y0 = tau0 / F, a = std::max(std::abs(y), y0);
  return F / (2 * mu) * (H * H - a * a) - tau0 / mu * (H - a);
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

// The same for a 3D scene (the nodal displacements are not kept).
inline SceneResult run_scene_3d(const SceneSpec& scene) {
  const auto start = std::chrono::steady_clock::now();
  auto run = testing::make_fem_run<3>(scene);
  SceneResult r;
  r.summary = run->run();
  for (std::size_t k = 0; k < scene.probes.size(); ++k) r.probes[scene.probes[k].name] = run->probe_values()[k];
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// The static fem recipe without its graph: the same builders and systems, called in the order of
// FemRun's graph (apply_boundary_conditions -> newton -> commit), one whole step at a time (no cut-back).
class SteppedFem {
 public:
  explicit SteppedFem(const SceneSpec& scene) : m_(scene), solver_(m_.linear_solver) {
    if (m_.scene.time.integrator != Integrator::static_) throw std::runtime_error("SteppedFem: static scenes only");
    ctx_.scene = &m_.scene;
  }

  // Solves the next scene step; commits it if Newton converged.
  NewtonReport step() {
    ++ctx_.step;
    ctx_.dt = m_.scene.time.dt;
    ctx_.t = ctx_.step * m_.scene.time.dt;
    ctx_.step_end = true;
    apply_boundary_conditions(ctx_, m_.nodes, m_.cells, m_.materials, m_.bc);
    reset_iterate(m_.nodes);
    FemNewtonProblem problem(ctx_, m_.materials, m_.cells, m_.bc, m_.nodes, m_.quad, m_.system, solver_, timers_);
    NewtonReport report = solve_newton(problem, newton_settings_of(m_.scene.solver), timers_);
    if (report.converged) commit_step(ctx_, m_.cells, m_.nodes, m_.quad);
    return report;
  }

  const FemModel& model() const { return m_; }
  const Nodes<2>& nodes() const { return m_.nodes; }
  Index dofs() const { return m_.system.dofs.n_free; }
  Index nearest_node(const Vec2& X) const {
    Index best = kNoIndex;
    double best_d = std::numeric_limits<double>::max();
    for (Index i = 0; i < m_.nodes.size(); ++i)
      if ((m_.nodes.X[i] - X).squaredNorm() < best_d) best_d = (m_.nodes.X[i] - X).squaredNorm(), best = i;
    return best;
  }

 private:
  FemModel m_;
  StepContext ctx_;
  Timers timers_;
  LinearSolve solver_;
};

}  // namespace loom::verification
