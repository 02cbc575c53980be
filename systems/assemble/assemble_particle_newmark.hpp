// Assembly of the Newton system of a particle-Newmark MPM step (seed 004, Aulisa & Capodaglio §3): on every
// active cell, the particles it holds as quadrature points with their inertia, stress and body force
// (elements/particle_newmark_point.hpp; under receding contact with the trial gradients of
// elements/receding_contact.hpp), plus the soft stiffness of the cell's flag (elements/soft_stiffness.hpp).
// The grid starts every step undeformed, so the gradients are those of the grid at X. Inactive nodes are
// absent from the system (equivalent to the paper's eq 27 lumped "mass" rows, which drive them to zero).
// Prescribed dofs enter through the Dirichlet lift; cells are visited colour by colour and the particles of
// a cell in index order: results do not depend on the thread count. The deformation gradient of each
// particle at the iterate is stored in the locations' F column. Method mpm_fem's FEM cells (GridActivity::
// always_active_from) are assembled in a pass of their own before the cells with particles when `timers` is given,
// each timed (newton/assemble/fem_cells, newton/assemble/particle_cells).
#pragma once

#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_activity.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/point_locations.hpp"
#include "engine/store/points.hpp"
#include "engine/timing/timers.hpp"
#include "systems/assemble/assemble_system.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {

AssemblyResult assemble_particle_newmark(const StepContext& ctx, bool tangent, const std::vector<BodyMaterial>& materials, const Cells& grid,
                                         const GridActivity& activity, const Nodes<2>& grid_nodes, const Points<2>& particles,
                                         const BoundaryConditions<2>& bc, PointLocations& loc, LinearSystem& system, Timers* timers = nullptr);

// The trial gradients a particle's F is built from: dN, or T^T dN when it recedes from a wall (quad9).
template <int NEN>
Eigen::Matrix<double, NEN, 2> particle_trial_gradients(const Eigen::Matrix<double, NEN, 2>& dN, Index receding_side, double c_c);

}  // namespace loom
