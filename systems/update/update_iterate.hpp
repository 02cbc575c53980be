// Moves the Newton iterate: u (and phi) += step * du on every dof (free: the solved increment;
// prescribed: the remaining gap to the target, so prescribed dofs reach their values with a full step).
#pragma once

#include "engine/linalg/linear_system.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

void update_iterate(double step, const LinearSystem& system, Nodes<2>& nodes);

// Starts a (sub)step from the converged state: u = u_n, phi = phi_n (also after a failed attempt).
void reset_iterate(Nodes<2>& nodes);

}  // namespace loom
