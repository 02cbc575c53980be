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

// Starts a step of a second-order integrator from u = u_n + dt v_n + dt^2 a_n / 2 (a_{n+1} = a_n extrapolated;
// phi, p from the last step). Newmark's residual there is M a_n + f_int(u) - f_ext, about f_int(u) - f_int(u_n):
// small along a smooth motion, where u = u_n leaves M (dt v_n + ...) / (beta dt^2) to the first update.
template <int D>
void predict_iterate(double dt, Nodes<D>& nodes);

}  // namespace loom
