// Scatter of one grid cell's local residual and tangent into the grid's Newton system (the mpm recipe's
// assembly systems): local dofs are the cell scatter's; on prescribed dofs that lag their target the
// residual gets the Dirichlet lift K (target - value), so one Newton step lands on the target. Active cells
// are visited colour by colour (cells of one colour share no node): race-free and thread-count independent.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "engine/core/parallel.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/grid_activity.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/nodes.hpp"
#include "systems/assemble/scatter_prefetch.hpp"

namespace loom {

template <class Body>
void for_each_active_cell_by_colour(const GridActivity& act, Body&& body, Index grain = kParallelGrain) {
  for (std::size_t k = 0; k + 1 < act.colour_offsets.size(); ++k)
    for_each_in(act.active_by_colour.data() + act.colour_offsets[k], act.colour_offsets[k + 1] - act.colour_offsets[k], body,
                Execution::parallel, grain);
}
// The same, with ahead(c') called for the next cell of the colour before body(c): ahead prefetches what body reads
// (PointLocations::prefetch_points_in).
template <class Ahead, class Body>
void for_each_active_cell_by_colour_looking_ahead(const GridActivity& act, Ahead&& ahead, Body&& body, Index grain = kParallelGrain) {
  for (std::size_t k = 0; k + 1 < act.colour_offsets.size(); ++k)
    for_each_in_looking_ahead(act.active_by_colour.data() + act.colour_offsets[k], act.colour_offsets[k + 1] - act.colour_offsets[k], ahead,
                              body, Execution::parallel, grain);
}

template <int D>
double grid_dof_value(const Nodes<D>& g, Index dof, int pn) {
  const Index node = dof / pn;
  const int comp = dof % pn;
  return comp < D ? g.u[node][comp] : g.p[node];
}

// Whether some prescribed dof of a cell lags its target: its residual then needs the cell's K (the lift
// below), even when no tangent is assembled.
template <int D>
bool cell_lags(Index entry, const CellScatter& sc, const BoundaryConditions<D>& bc, const Nodes<D>& g, const DofMap& dofs) {
  for (int k = 0; k < sc.dofs_per_cell; ++k) {
    const Index dof = sc.cell_dof(entry, k);
    if (dofs.kind[std::size_t(dof)] == DofKind::prescribed && bc.target[dof] != grid_dof_value(g, dof, dofs.per_node)) return true;
  }
  return false;
}

// Dormant dofs (GridActivity::dormant_dofs): an identity row scaled to the mean diagonal of the others (so
// that the factor's pivot ratio does not change) and a zero residual, so that their increment is zero and
// the other equations are those of the active set alone. Called after the cells and nodal terms.
inline void pin_dormant_dofs(const GridActivity& act, bool tangent, LinearSystem& system) {
  if (act.dormant_dofs.empty()) return;
  const DofMap& dofs = system.dofs;
  double* values = system.pattern.matrix.valuePtr();
  if (tangent) {
    double sum = 0.0;
    for (Index eq = 0; eq < dofs.n_free; ++eq) sum += std::abs(values[system.pattern.diagonal_slot[std::size_t(eq)]]);
    const Index n_live = dofs.n_free - Index(act.dormant_dofs.size());
    const double scale = n_live > 0 && sum > 0.0 ? sum / double(n_live) : 1.0;
    for (Index dof : act.dormant_dofs) values[system.pattern.diagonal_slot[std::size_t(dofs.equation[std::size_t(dof)])]] = scale;
  }
  for (Index dof : act.dormant_dofs) system.residual_full[dof] = 0.0, system.residual[dofs.equation[std::size_t(dof)]] = 0.0;
}

template <int NE, int D>
void scatter_cell(Index entry, const CellScatter& sc, const BoundaryConditions<D>& bc, const Nodes<D>& g, bool tangent,
                  Eigen::Matrix<double, NE, 1>& r, const Eigen::Matrix<double, NE, NE>& K, LinearSystem& system) {
  const int pn = system.dofs.per_node;
  Eigen::Matrix<double, NE, 1> gap = Eigen::Matrix<double, NE, 1>::Zero();
  bool lagging = false;
  for (int k = 0; k < NE; ++k) {
    const Index dof = sc.cell_dof(entry, k);
    if (system.dofs.kind[std::size_t(dof)] != DofKind::prescribed) continue;
    gap[k] = bc.target[dof] - grid_dof_value(g, dof, pn);
    lagging = lagging || gap[k] != 0.0;
  }
  if (lagging) r += K * gap;
  for (int a = 0; a < NE; ++a) system.residual_full[sc.cell_dof(entry, a)] += r[a];
  if (!tangent) return;
  double* values = system.pattern.matrix.valuePtr();
  for (int a = 0; a < NE; ++a)
    for (int b = 0; b < NE; ++b) {
      const Index s = sc.matrix_slot(entry, a, b);
      if (s != kNoIndex) values[s] += K(a, b);
    }
}

}  // namespace loom
