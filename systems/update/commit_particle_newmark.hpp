// The particle update of seed 004 after a converged step (Aulisa & Capodaglio §3.2-3.3, eqs 17-19, 34-35):
// with the grid's step displacement u~ and each particle's shape functions at its start-of-step position,
//   u~_p = sum_A N_A u~_A,  x_p += u~_p (u_p += u~_p),
//   a_p = u~_p / (beta dt^2) - v_p / (beta dt) - (1 - 2 beta) / (2 beta) a_p,  v_p += dt ((1 - gamma) a_p^n + gamma a_p),
//   F_p = (I + sum_A u~_A (x) dN*_A) F_p    (dN*: the receding-contact trial gradients where they applied).
// Nothing is interpolated back from grid velocities or accelerations: the grid carries none. Each particle
// writes only its own entries.
#pragma once

#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/point_locations.hpp"
#include "engine/store/points.hpp"

namespace loom {

void commit_particle_newmark(const StepContext& ctx, const Cells& grid, const Nodes<2>& grid_nodes, const PointLocations& loc,
                             Points<2>& particles);

// Point probes of a particle-Newmark run read the particle nearest to their `at` (the disk's centre
// particle, a beam's tip particle): points[k] takes the displacement of particles[followed[k]].
void follow_particles(const StepContext& ctx, const std::vector<Index>& followed, const Points<2>& particles, Points<2>& points);

}  // namespace loom
