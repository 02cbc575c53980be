// The mesh-based recipes. fem: updated-Lagrangian finite elements on a fixed mesh, the reference every
// other method is measured against. pfem: the same, preceded by a remesh stage (seed 000 §3: triangulate
// the particles, transfer the state, rebuild the system where the connectivity changed). Per (sub)step:
//   [remesh ->] apply_boundary_conditions -> newton [assemble -> solve -> update]* -> commit -> {probes, output}
// with commit, probes and output only on a converged state, probes and output only at the end of a
// scene step, and output only on frame steps; the VTK frame is written concurrently with the next step.
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
#include "engine/linalg/linear_system.hpp"
#include "engine/methods/method.hpp"
#include "engine/methods/model/fem_model.hpp"
#include "engine/methods/pfem/pfem_remesh.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/points.hpp"
#include "engine/store/quad_points.hpp"
#include "engine/timing/timers.hpp"
#include "systems/assemble/materials/material.hpp"
#include "systems/output/evaluate_probes.hpp"

namespace loom {

struct CheckpointHeader;

// D = 2, or 3 (method fem on tetrahedra: no remesh, walls, inlets or smoothing domains).
template <int D>
class FemRunT final : public MethodRun {
 public:
  FemRunT(const SceneSpec& scene, const RunOptions& options);
  ~FemRunT() override;

  void describe(std::ostream& os) const override;
  RunSummary run() override;

  // Read access for tests and tools.
  const FemModelT<D>& model() const { return m_; }
  const Nodes<D>& nodes() const { return m_.nodes; }
  const std::vector<Cells>& cells() const { return m_.cells; }
  const std::vector<QuadPoints<D>>& quad_points() const { return m_.quad; }
  const LinearSystem& system() const { return m_.system; }
  const BoundaryConditions<D>& boundary_conditions() const { return m_.bc; }
  const std::vector<double>& probe_values() const override { return probe_values_; }
  const RemeshReport& last_remesh() const { return last_remesh_; }
  const StepGraph& graph() const { return *graph_; }
  const Timers& timers() const override { return timers_; }

 private:
  void resolve_probe_groups();
  void check_model() const;
  void check_inlets() const;
  // The particle set may change during the run (insertion, removal, inflow): the checkpoint holds its size.
  bool particles_change() const { return pfem_ && (pfem_settings_.edits.active() || !scene_.inlets.empty()); }
  void build_graph();
  void write_initial_state();
  void set_equilibrium_acceleration();
  // engine/methods/recipes/fem_checkpoint.cpp
  void write_checkpoint(int step);
  CheckpointHeader restore_checkpoint(const CheckpointReader& r);
  void remesh_node();
  void newton_node();
  void probes_node();
  void output_node();
  bool frame_due() const;
  StopCondition stop_;  // time.stop_when

  FemModelT<D> m_;  // the stores
  const SceneSpec& scene_;
  RunOptions options_;
  StepContext ctx_;
  Timers timers_;
  StepStatus status_;

  // PFEM (method = pfem): settings, the topology the next remesh starts from, the last remesh
  bool pfem_ = false;
  PfemSettings pfem_settings_;
  PfemTopologyOf<D> topology_;
  RemeshReport last_remesh_;
  RemeshReport last_change_;   // the last remesh that changed the connectivity, at step last_change_step_
  int last_change_step_ = -1;
  double new_material_mass_ = 0.0;  // added by the remeshes where gaps were filled, since the start (remesh.max_new_material)
  void check_new_material() const;

  // Per-run workspace
  LinearSolve solver_;
  ProbePlan probe_plan_;
  std::vector<double> probe_values_;
  ProbeWriter probe_writer_;
  PvdWriter pvd_;
  AsyncWriter writer_;
  std::unique_ptr<StepGraph> graph_;
  double wall_ = 0.0;
  double last_frame_time_ = -1.0;
  bool warned_singular_ = false;
};

using FemRun = FemRunT<2>;
extern template class FemRunT<2>;
extern template class FemRunT<3>;

}  // namespace loom
