// Grid-to-particle interpolation and convection, seed 003 Algorithm 1 lines 44-49 (convective phase),
// on a converged step. With the grid's step displacement du_I, its Newmark acceleration a_I, pressure
// p_I and (OSGS) projections, each material point p takes
//   du_p = sum_I N_I(x_p) du_I,  u_p += du_p (the position x = X + u moves with it),
//   F_p  = (I + sum_I du_I (x) grad N_I(x_p)) F_p          (grad at the step's start position)
//   a_p  = sum_I N_I a_I,  v_p += dt ((1 - gamma) a_p^n + gamma a_p)   (Newmark at the particle)
//   p_p  = sum_I N_I p_I,  P_u, P_p likewise (OSGS, carried to the next step).
// The velocity update keeps the particles' momentum equal to the grid's: sum_p m_p a_p = sum_I m_I a_I.
// Each particle writes only its own entries.
#pragma once

#include "engine/graph/step_context.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_activity.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/point_locations.hpp"
#include "engine/store/points.hpp"

namespace loom {

inline constexpr double kNewmarkBeta = 0.25, kNewmarkGamma = 0.5;  // seed 003 §3.3

template <int D>
void interpolate_to_particles(const StepContext& ctx, const Cells& grid, const Nodes<D>& grid_nodes,
                              const PointLocations& loc, Points<D>& particles);

// Moves points that only follow the body (traction and probe points): u += sum_I N_I du_I over their host
// active cell (locate's host_active_cell; the grid is zero on inactive nodes). A point with no active cell
// near it stays where it is.
template <int D>
void move_with_grid(const StepContext& ctx, const Cells& grid, const Nodes<D>& grid_nodes, const GridActivity& activity,
                    const PointLocations& loc, Points<D>& points);

}  // namespace loom
