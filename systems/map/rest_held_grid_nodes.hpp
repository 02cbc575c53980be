// Grid nodes held by a prescribed displacement that does not move this step (increment 0: a clamp, a fixed
// wall) start the grid-Newmark step at rest: v_n = a_n = 0 in the held components. The projection gives them
// the mean velocity and acceleration of the particles around them instead, and with u = 0 the Newmark update
// (systems/update/grid_newmark.hpp) turns those into a = -4 v_n / dt - a_n and v = -v_n: a node that does not
// move would carry a velocity that flips sign every step, pass the increment -2 v_n to the particles next to
// it, and put its inertia m a into the reaction. At rest, a = v = 0 and the increment is 0, as for a node of
// the explicit MPM codes' fixed boundaries. Prescribed motions (a non-zero increment) keep the projection.
#pragma once

#include "engine/graph/step_context.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

template <int D>
void rest_held_grid_nodes(const StepContext& ctx, const BoundaryConditions<D>& bc, Nodes<D>& grid_nodes);

}  // namespace loom
