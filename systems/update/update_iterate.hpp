// Moves the Newton iterate: u (and phi) += step * du on every dof (free: the solved increment;
// prescribed: the remaining gap to the target, so prescribed dofs reach their values with a full step).
#pragma once

#include "engine/linalg/linear_system.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

// Instantiated for D = 2 and 3; the dof after a node's D displacements (per_node = D + 1) is phi or p.
template <int D>
void update_iterate(double step, const LinearSystem& system, Nodes<D>& nodes);

// Starts a (sub)step from the converged state: u = u_n, phi = phi_n (also after a failed attempt).
template <int D>
void reset_iterate(Nodes<D>& nodes);

}  // namespace loom
