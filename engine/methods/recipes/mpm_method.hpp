// The mpm recipe: the implicit mixed u-p material point method of seed 003 (Algorithm 1). Per (sub)step
// the graph runs
//   locate_particles, locate_traction_points -> activate_grid -> project_to_grid -> apply_grid_loads
//     -> newton [assemble -> solve -> update]* -> interpolate_to_particles, move_traction_points
//     -> {probes, output}
// (phase 1: lines 5-15; phase 2: lines 17-42; phase 3: lines 44-49). The grid is reset every step, so a
// failed Newton solve leaves the particles untouched and the time loop simply reruns the step with half the
// time step. Interpolation, probes and output run only on a converged state; the VTK files (particles
// .vtp, active grid .vtu, both in the .pvd) are written while the next step runs.
// With mpm.scheme = "particle_newmark" (seed 004, Aulisa & Capodaglio) the graph is
//   locate_particles -> activate_grid -> flag_soft_cells -> mark_receding_particles -> apply_grid_loads
//     -> newton [assemble_particle_newmark -> solve -> update]* -> commit_particle_newmark, follow_particles
//     -> {probes, output}
// (nothing projected: the particles carry the Newmark state).
#pragma once

#include <memory>
#include <vector>

#include "engine/drivers/step_status.hpp"
#include "engine/graph/step_graph.hpp"
#include "engine/io/async_writer.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/io/probe_writer.hpp"
#include "engine/io/pvd_writer.hpp"
#include "engine/linalg/linear_solver.hpp"
#include "engine/methods/method.hpp"
#include "engine/methods/model/mpm_model.hpp"
#include "engine/timing/timers.hpp"
#include "systems/output/particle_probes.hpp"

namespace loom {

struct CheckpointHeader;

// D = 2 or 3 (3D: tet4 grids, the grid Newmark scheme; engine/methods/model/mpm_model.hpp).
template <int D>
class MpmRunT final : public MethodRun {
 public:
  MpmRunT(const SceneSpec& scene, const RunOptions& options);
  ~MpmRunT() override;

  void describe(std::ostream& os) const override;
  RunSummary run() override;
  const Timers& timers() const override { return timers_; }

  // Read access for tests, tools and benchmarks.
  const MpmModelT<D>& model() const { return m_; }
  const std::vector<double>& probe_values() const override { return probe_values_; }
  const StepGraph& graph() const { return *graph_; }
  const LinearSolve& solver() const { return solver_; }

 private:
  void name_stores(StepGraph& g);
  void add_output_nodes(StepGraph& g);
  void build_graph();
  void build_particle_newmark_graph();
  void write_initial_state();
  // engine/methods/recipes/mpm_checkpoint.cpp
  void write_checkpoint(int step);
  CheckpointHeader restore_checkpoint(const CheckpointReader& r);
  void initial_acceleration();
  void fem_nodes_equilibrium_acceleration();
  void newton_node();
  void probes_node();
  void output_node();
  bool frame_due() const;
  StopCondition stop_;  // time.stop_when

  MpmModelT<D> m_;
  const SceneSpec& scene_;
  RunOptions options_;
  StepContext ctx_;
  Timers timers_;
  StepStatus status_;

  LinearSolve solver_;
  ParticleProbePlan probe_plan_;
  std::vector<double> probe_values_;
  ProbeWriter probe_writer_;
  PvdWriter pvd_;
  AsyncWriter writer_;
  std::unique_ptr<StepGraph> graph_;
  double last_frame_time_ = -1.0;
  bool warned_singular_ = false;
};

using MpmRun = MpmRunT<2>;

}  // namespace loom
