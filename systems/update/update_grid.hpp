// Moves the Newton iterate of an MPM grid: u (and p) += step * du on every dof, then the grid's Newmark
// velocity and acceleration follow (seed 003 Algorithm 1 lines 28-31, corrector).
#pragma once

#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

template <int D>
void update_grid_iterate(const StepContext& ctx, double step, const LinearSystem& system, Nodes<D>& grid_nodes);

// v and a of every node with mass from its step displacement (Newmark); no-op for static runs.
template <int D>
void update_grid_kinematics(const StepContext& ctx, Nodes<D>& grid_nodes);

}  // namespace loom
