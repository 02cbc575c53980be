// Accepts a converged (sub)step: the iterate becomes the history (u_n, v_n, a_n, phi_n, F_n; for mixed
// u-phi cells F holds F~ so F_n becomes F~_n, seed 000 eq 28) and the
// updated-Lagrangian reference B_n moves to the converged configuration (new dN/dX_n and dV_n).
// Velocities and accelerations follow the scene's integrator (time_integrator.hpp); Euler backward
// (seed 000 eq 12) keeps its own expressions: v = (u - u_n) / dt, a = (v - v_n) / dt.
#pragma once

#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/quad_points.hpp"

namespace loom {

// Instantiated for D = 2 and 3 (3D: tet4, tet10 cells; not the smoothed-domain formulations).
template <int D>
void commit_step(const StepContext& ctx, const std::vector<Cells>& cells, Nodes<D>& nodes, std::vector<QuadPoints<D>>& quad);

}  // namespace loom
