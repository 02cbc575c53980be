#include "systems/solve/solve_grid_step.hpp"

#include "engine/core/parallel.hpp"
#include "systems/solve/solve_linear_step.hpp"

namespace loom {

template <int D>
LinearSolveStatus solve_grid_step(const Nodes<D>& g, const BoundaryConditions<D>& bc, LinearSolve& solver, LinearSystem& system,
                                  Timers& timers) {
  give_structure(g, false, solver, system);
  if (solve_free_dofs(solver, system, timers) != LinearSolveStatus::ok) return LinearSolveStatus::singular;
  const DofMap& dofs = system.dofs;
  const int pn = dofs.per_node;
  for_each_index(dofs.n_dofs(), [&](Index dof) {
    const Index node = dof / pn;
    const int comp = dof % pn;
    switch (dofs.kind[std::size_t(dof)]) {
      case DofKind::free: system.increment_full[dof] = system.increment[dofs.equation[std::size_t(dof)]]; break;
      case DofKind::prescribed: system.increment_full[dof] = bc.target[dof] - (comp < D ? g.u[node][comp] : g.p[node]); break;
      case DofKind::tied:  // PFEM mid-nodes only; the grid has none
      case DofKind::absent: system.increment_full[dof] = 0.0; break;
    }
  });
  return LinearSolveStatus::ok;
}


template LinearSolveStatus solve_grid_step<2>(const Nodes<2>&, const BoundaryConditions<2>&, LinearSolve&, LinearSystem&, Timers&);
template LinearSolveStatus solve_grid_step<3>(const Nodes<3>&, const BoundaryConditions<3>&, LinearSolve&, LinearSystem&, Timers&);

}  // namespace loom
