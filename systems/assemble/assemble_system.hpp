// Assembly of the Newton system of a mesh-based run (seed 000 eqs 4-15): internal forces and tangent of
// every cell block, inertia of the time integrator, external loads, and the Dirichlet lift.
//
// Residual on all dofs: r = f_int + M a - f_ext (on prescribed dofs this is the reaction). While a
// prescribed dof lags its target g (first iteration of a step), the free rows also get K_fp (g - u_p),
// so that one Newton step applies the prescribed increment consistently (no artificial spike).
// Blocks of seed 001's formulations (es_up, es_u, fem_up, fem_u) are integrated over `domains`
// (assemble_domains.hpp); their triangles add only the pressure terms. Cells are visited colour by colour, the cells of a colour in parallel: the result is independent of
// the thread count.
#pragma once

#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/edges.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/quad_points.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {

// static_residual: f_int - f_ext alone, without the inertia of a dynamic integrator (the equilibrium at t = 0).
enum class AssemblyMode { residual, residual_and_tangent, static_residual };

struct AssemblyResult {
  Index inverted_cells = 0;  // cells where J <= 0 at the iterate: the residual is meaningless
};

// Instantiated for D = 2 and 3; the smoothing domains exist in 2D only (seed 001's edges).
template <int D>
AssemblyResult assemble_system(const StepContext& ctx, AssemblyMode mode, const std::vector<BodyMaterial>& materials,
                               const Nodes<D>& nodes, const std::vector<Cells>& cells,
                               const BoundaryConditions<D>& bc, std::vector<QuadPoints<D>>& quad,
                               LinearSystem& system, std::vector<Edges<D>>* domains = nullptr);

}  // namespace loom
