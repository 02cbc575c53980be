#include "systems/solve/solve_linear_step.hpp"

#include <algorithm>
#include <cmath>

#include "engine/core/parallel.hpp"

namespace loom {

LinearSolveStatus solve_free_dofs(LinearSolve& solver, LinearSystem& system, Timers& timers, bool refactorize) {
  if (refactorize) {
    ScopedTimer t(timers, "newton/solve/factorize");
    if (system.dofs.n_free > 0) {
      if (!solver.analysed(system.pattern)) {  // timed apart: its count is the number of new sparsity patterns
        ScopedTimer a(timers, "newton/solve/factorize/analyze");
        solver.analyze(system.pattern);
      }
      if (!solver.factorize(system.pattern)) return LinearSolveStatus::singular;
    }
  }
  if (system.dofs.n_free == 0) return LinearSolveStatus::ok;
  const Eigen::VectorXd rhs = -system.residual;
  if (solver.deferred()) {  // reuse_factor: GMRES on the kept factorisation, timed as the solve it replaces
    bool solved = false;
    {
      ScopedTimer t(timers, "newton/solve/back_substitute");
      solved = solver.solve_deferred(rhs, system.increment);
    }
    if (solved) return system.increment.allFinite() ? LinearSolveStatus::ok : LinearSolveStatus::singular;
    ScopedTimer t(timers, "newton/solve/factorize");  // GMRES was too slow: the fresh factorisation it falls back on
    if (!solver.factorize_deferred()) return LinearSolveStatus::singular;
  }
  ScopedTimer t(timers, "newton/solve/back_substitute");
  if (!solver.solve(rhs, system.increment) || !system.increment.allFinite()) return LinearSolveStatus::singular;
  return LinearSolveStatus::ok;
}

template <int D>
void give_structure(const Nodes<D>& nodes, bool current, LinearSolve& solver, const LinearSystem& system) {
  if (!solver.wants_structure() || solver.analysed(system.pattern)) return;
  SolveStructure s;
  s.dim = D;
  s.dofs = system.dofs;
  const Index n = std::min(system.dofs.n_nodes(), nodes.X.size());
  s.coordinates.assign(std::size_t(system.dofs.n_nodes()) * D, 0.0);
  for (Index i = 0; i < n; ++i)
    for (int c = 0; c < D; ++c) s.coordinates[std::size_t(i) * D + std::size_t(c)] = nodes.X[i][c] + (current ? nodes.u[i][c] : 0.0);
  solver.set_structure(std::move(s));
}

template <int D>
LinearSolveStatus solve_linear_step(const Nodes<D>& nodes, const BoundaryConditions<D>& bc, LinearSolve& solver,
                                    LinearSystem& system, Timers& timers, bool refactorize) {
  if (refactorize) give_structure(nodes, true, solver, system);
  if (solve_free_dofs(solver, system, timers, refactorize) != LinearSolveStatus::ok) return LinearSolveStatus::singular;
  const DofMap& dofs = system.dofs;
  for_each_index(dofs.n_dofs(), [&](Index dof) {
    switch (dofs.kind[std::size_t(dof)]) {
      case DofKind::free: system.increment_full[dof] = system.increment[dofs.equation[std::size_t(dof)]]; break;
      case DofKind::prescribed:  // only displacement components are ever prescribed
        system.increment_full[dof] = bc.target[dof] - nodes.u[dof / dofs.per_node][dof % dofs.per_node];
        break;
      case DofKind::tied:  // set below from the masters
      case DofKind::absent: system.increment_full[dof] = 0.0; break;
    }
  });
  for (const Tie& tie : dofs.ties)
    system.increment_full[tie.dof] = 0.5 * (system.increment_full[tie.master[0]] + system.increment_full[tie.master[1]]);
  return LinearSolveStatus::ok;
}

template void give_structure<2>(const Nodes<2>&, bool, LinearSolve&, const LinearSystem&);
template void give_structure<3>(const Nodes<3>&, bool, LinearSolve&, const LinearSystem&);
template LinearSolveStatus solve_linear_step<2>(const Nodes<2>&, const BoundaryConditions<2>&, LinearSolve&, LinearSystem&, Timers&, bool);
template LinearSolveStatus solve_linear_step<3>(const Nodes<3>&, const BoundaryConditions<3>&, LinearSolve&, LinearSystem&, Timers&, bool);

}  // namespace loom
