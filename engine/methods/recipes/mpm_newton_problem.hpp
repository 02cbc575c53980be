// The Newton problem of the mpm recipe (seed 003 Algorithm 1 phase 2, lines 17-37): binds the driver's
// operations to the grid systems. OSGS recomputes the residual projections from the current iterate before
// every assembly but the first of a step, which uses the projections the particles carried (line 20),
// and, since its tangent leaves their derivative out, mixes the Newton increments (anderson_mixing.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/drivers/newton.hpp"
#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_solver.hpp"
#include "engine/methods/model/mpm_model.hpp"
#include "engine/methods/recipes/anderson_mixing.hpp"
#include "systems/assemble/assemble_grid_system.hpp"
#include "systems/assemble/assemble_particle_newmark.hpp"
#include "systems/map/project_residuals.hpp"
#include "systems/solve/solve_grid_step.hpp"
#include "systems/update/update_grid.hpp"

namespace loom {

template <int D>
class MpmNewtonProblemT final : public NonlinearProblem {
 public:
  MpmNewtonProblemT(const StepContext& ctx, MpmModelT<D>& m, LinearSolve& solver, Timers& timers, bool inertia = true)
      : ctx_(ctx), m_(m), solver_(solver), timers_(timers), inertia_(inertia) {}

  bool assemble(bool with_tangent) override {
    if (m_.osgs && assembled_) {
      ScopedTimer t(timers_, "newton/assemble/project_residuals");  // inside newton/assemble's scope
      project_residuals(ctx_, m_.materials, m_.grid, m_.activity, m_.particles, m_.particle_loc, m_.bc, m_.grid_nodes);
    }
    assembled_ = true;
    if constexpr (D == 2)
      if (m_.particle_newmark)
        return assemble_particle_newmark(ctx_, with_tangent, m_.materials, m_.grid, m_.activity, m_.grid_nodes, m_.particles, m_.bc,
                                         m_.particle_loc, m_.system, &timers_)
                   .inverted_cells == 0;
    const GridAssemblyOptions options{with_tangent, inertia_};
    return assemble_grid_system(ctx_, options, m_.materials, m_.grid, m_.activity, m_.grid_nodes, m_.particles, m_.bc, m_.particle_loc,
                                m_.system)
               .inverted_cells == 0;
  }
  double residual_norm() const override { return m_.system.residual.norm(); }
  bool solve() override {
    if (solve_grid_step(m_.grid_nodes, m_.bc, solver_, m_.system, timers_) != LinearSolveStatus::ok) return false;
    if (m_.osgs) mix_increment();
    return true;
  }
  std::string solve_failure() const override { return solver_.failure().empty() ? "the tangent matrix is singular" : solver_.failure(); }
  void update(double step) override {
    applied_ += step;
    update_grid_iterate(ctx_, step, m_.system, m_.grid_nodes);
  }
  double increment_norm() const override { return m_.system.increment.norm(); }
  double step_change_norm() const override {
    double s = 0.0;
    for (Index i = 0; i < m_.grid_nodes.size(); ++i) s += m_.grid_nodes.u[i].squaredNorm();
    return std::sqrt(s);
  }
  double force_scale() const override {
    double s = m_.bc.external.squaredNorm();
    for (const auto& p : m_.bc.prescribed) s += m_.system.residual_full[p.dof] * m_.system.residual_full[p.dof];
    return std::sqrt(s);
  }
  // max |du| over the grid's displacements against the diagonal of the particles' bounding box.
  double increment_over_size() const override {
    const Points<D>& pts = m_.particles;
    const int pn = m_.system.dofs.per_node;
    if (pts.X.size() == 0 || m_.system.increment_full.size() != m_.grid_nodes.size() * pn) return 0.0;
    Vec<D> lo = pts.X[0] + pts.u[0], hi = lo;
    for (Index p = 0; p < pts.X.size(); ++p) lo = lo.cwiseMin(pts.X[p] + pts.u[p]), hi = hi.cwiseMax(pts.X[p] + pts.u[p]);
    double largest = 0.0;
    for (Index i = 0; i < m_.grid_nodes.size(); ++i)
      for (int d = 0; d < D; ++d) largest = std::max(largest, std::abs(m_.system.increment_full[i * pn + d]));
    const double size = (hi - lo).norm();
    return size > 0.0 ? largest / size : 0.0;
  }
  bool prescribed_pending() const override {
    const int pn = m_.bc.per_node;
    for (const auto& p : m_.bc.prescribed) {
      if (m_.system.dofs.kind[std::size_t(p.dof)] != DofKind::prescribed) continue;  // inactive node
      const int comp = p.dof % pn;
      const double target = m_.bc.target[p.dof], value = comp < D ? m_.grid_nodes.u[p.node][comp] : m_.grid_nodes.p[p.node];
      if (std::abs(target - value) > 1e-13 * (std::abs(target) + std::abs(value)) + 1e-300) return true;
    }
    return false;
  }

 private:
  // OSGS: Anderson mixing of the free dofs' increments (the prescribed ones are applied as solved).
  void mix_increment() {
    LinearSystem& sys = m_.system;
    const Eigen::VectorXd mixed = anderson_.mix(sys.increment, applied_);
    applied_ = 0.0;
    const DofMap& dofs = sys.dofs;
    for (Index dof = 0; dof < dofs.n_dofs(); ++dof)
      if (dofs.kind[std::size_t(dof)] == DofKind::free) sys.increment_full[dof] = mixed[dofs.equation[std::size_t(dof)]];
    sys.increment = mixed;
  }

  const StepContext& ctx_;
  MpmModelT<D>& m_;
  LinearSolve& solver_;
  Timers& timers_;
  bool inertia_;
  bool assembled_ = false;
  AndersonMixing anderson_;
  double applied_ = 0.0;  // multiple of the last increment added to the iterate since the last solve
};

using MpmNewtonProblem = MpmNewtonProblemT<2>;

}  // namespace loom
