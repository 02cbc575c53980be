// Evaluates the boundary conditions at the time of the step being solved: prescribed values of the
// Dirichlet dofs (target) and the nodal external forces (dead-load tractions per unit reference length,
// seed 000 eq 8, and body forces per unit mass, eq 7). External forces are recomputed only when an
// expression depends on t. Expressions are evaluated serially (they are not thread-safe, and there are
// few boundary entities).
#pragma once

#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {

// Instantiated for D = 2 (edges, triangles, quad9) and D = 3 (3- and 6-node faces, tet4 and tet10).
template <int D>
void apply_boundary_conditions(const StepContext& ctx, const Nodes<D>& nodes, const std::vector<Cells>& cells,
                               const std::vector<BodyMaterial>& materials, BoundaryConditions<D>& bc);

}  // namespace loom
