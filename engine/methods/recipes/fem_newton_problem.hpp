// The Newton problem of the fem recipe: binds NonlinearProblem's operations to the assemble, solve and
// update systems on the run's stores.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/drivers/newton.hpp"
#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_solver.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/quad_points.hpp"
#include "systems/assemble/assemble_system.hpp"
#include "systems/assemble/wall_contact.hpp"
#include "systems/solve/solve_linear_step.hpp"
#include "systems/update/update_iterate.hpp"

namespace loom {

inline NewtonSettings newton_settings_of(const SolverSpec& solver) {
  NewtonSettings s;
  s.max_iterations = solver.max_iterations;
  s.residual_relative = solver.residual_relative;
  s.residual_absolute = solver.residual_absolute;
  s.increment_relative = solver.increment_relative;
  s.line_search = solver.line_search;
  s.tangent_once_per_step = solver.tangent == TangentUpdate::once_per_step;
  return s;
}

template <int D>
class FemNewtonProblemT final : public NonlinearProblem {
 public:
  FemNewtonProblemT(const StepContext& ctx, const std::vector<BodyMaterial>& materials, const std::vector<Cells>& cells,
                   const BoundaryConditions<D>& bc, Nodes<D>& nodes, std::vector<QuadPoints<D>>& quad,
                   LinearSystem& system, LinearSolve& solver, Timers& timers, std::vector<Edges<D>>* domains = nullptr)
      : ctx_(ctx), materials_(materials), cells_(cells), bc_(bc), nodes_(nodes), quad_(quad), system_(system),
        solver_(solver), timers_(timers), domains_(domains) {}

  // Rigid walls act on the nodes of the given bodies (systems/assemble/wall_contact.hpp).
  void set_walls(const WallsT<D>* walls, const std::vector<Index>* node_body) { walls_ = walls, node_body_ = node_body; }

  bool assemble(bool with_tangent) override {
    const auto mode = with_tangent ? AssemblyMode::residual_and_tangent : AssemblyMode::residual;
    fresh_tangent_ = fresh_tangent_ || with_tangent;
    const bool ok = assemble_system<D>(ctx_, mode, materials_, nodes_, cells_, bc_, quad_, system_, domains_).inverted_cells == 0;
    if (walls_ && !walls_->empty()) {
      ScopedTimer t(timers_, "newton/assemble/walls");
      add_wall_contact(*walls_, *node_body_, nodes_, with_tangent, system_);
    }
    return ok;
  }
  double residual_norm() const override { return system_.residual.norm(); }
  bool solve() override {
    const bool refactorize = fresh_tangent_;
    fresh_tangent_ = false;
    return solve_linear_step(nodes_, bc_, solver_, system_, timers_, refactorize) == LinearSolveStatus::ok;
  }
  std::string solve_failure() const override { return solver_.failure().empty() ? "the tangent matrix is singular" : solver_.failure(); }
  void update(double step) override { update_iterate<D>(step, system_, nodes_); }
  // |du| on the displacement dofs when a pressure is an unknown too (stress units do not compare with
  // step_change_norm's lengths).
  double increment_norm() const override {
    return blocks() == 1 ? system_.increment.norm() : block_part_norm(system_.increment, false);
  }
  double step_change_norm() const override {
    double s = 0.0;
    for (Index i = 0; i < nodes_.size(); ++i) s += (nodes_.u[i] - nodes_.u_n[i]).squaredNorm();
    return std::sqrt(s);
  }
  // |f_ext| and the reactions |r| on prescribed dofs: the forces the converged state balances.
  double force_scale() const override {
    double s = bc_.external.squaredNorm();
    for (const auto& p : bc_.prescribed) s += system_.residual_full[p.dof] * system_.residual_full[p.dof];
    return std::sqrt(s);
  }
  // u-p formulations (seed 001): the momentum and the pressure residuals are converged separately.
  int blocks() const override { return nodes_.p_n.used() && system_.dofs.per_node == D + 1 ? 2 : 1; }
  double block_norm(int block) const override {
    return blocks() == 1 ? residual_norm() : block_part_norm(system_.residual, block == 1);
  }
  // max |du| over the nodes' displacements against the diagonal of the bodies' bounding box at the step's start.
  double increment_over_size() const override {
    if (nodes_.size() == 0 || system_.increment_full.size() != nodes_.size() * system_.dofs.per_node) return 0.0;
    Vec<D> lo = nodes_.position_n(0), hi = lo;
    double largest = 0.0;
    for (Index i = 0; i < nodes_.size(); ++i) {
      const Vec<D> x = nodes_.position_n(i);
      lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
      for (int d = 0; d < D; ++d) largest = std::max(largest, std::abs(system_.increment_full[i * system_.dofs.per_node + d]));
    }
    const double size = (hi - lo).norm();
    return size > 0.0 ? largest / size : 0.0;
  }
  bool prescribed_pending() const override {
    for (const auto& p : bc_.prescribed) {
      const double target = bc_.target[p.dof], u = nodes_.u[p.node][p.dof % bc_.per_node];
      if (std::abs(target - u) > 1e-13 * (std::abs(target) + std::abs(u)) + 1e-300) return true;
    }
    return false;
  }

 private:
  const StepContext& ctx_;
  const std::vector<BodyMaterial>& materials_;
  const std::vector<Cells>& cells_;
  const BoundaryConditions<D>& bc_;
  Nodes<D>& nodes_;
  std::vector<QuadPoints<D>>& quad_;
  LinearSystem& system_;
  LinearSolve& solver_;
  Timers& timers_;
  // Norm of the entries of an equation-indexed vector that belong to the pressure dofs (or to the others).
  double block_part_norm(const Eigen::VectorXd& v, bool pressure) const {
    const DofMap& dofs = system_.dofs;
    double sum = 0.0;
    for (Index dof = 0; dof < dofs.n_dofs(); ++dof)
      if (const Index eq = dofs.equation[std::size_t(dof)]; eq != kNoIndex && (dof % dofs.per_node == D) == pressure) sum += v[eq] * v[eq];
    return std::sqrt(sum);
  }

  std::vector<Edges<D>>* domains_;
  const WallsT<D>* walls_ = nullptr;
  const std::vector<Index>* node_body_ = nullptr;
  bool fresh_tangent_ = false;  // a tangent was assembled since the last factorisation
};

using FemNewtonProblem = FemNewtonProblemT<2>;

}  // namespace loom
