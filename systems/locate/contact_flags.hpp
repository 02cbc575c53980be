// Where seed 004's edge terms act (Aulisa & Capodaglio §3.4, §5), decided once per step after locate:
//  - flag_soft_cells: each active cell's flag M_E, its nodes that belong neither to an inactive cell nor to
//    a boundary marked `outside` (the soft stiffness's C_E follows it); recomputed when the active set
//    changes, frozen during Newton;
//  - mark_receding_particles: the particles of a cell with a side on a wall whose last-step velocity points
//    away from that side (the receding-contact correction applies to them this step).
// find_wall_sides (once per run): the sides of each grid cell whose three nodes are held in x and y.
#pragma once

#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_activity.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/point_locations.hpp"
#include "engine/store/points.hpp"

namespace loom {

// Bit s of entry c: side s of quad9 cell c (corner s, mid-side 4 + s, corner s + 1) lies on a wall.
// interface_node (method mpm_fem): the sides whose three nodes are shared with an FEM body are walls too.
std::vector<unsigned char> find_wall_sides(const Cells& grid, const BoundaryConditions<2>& bc, Index n_nodes,
                                           const std::vector<char>* interface_node = nullptr);

void flag_soft_cells(const StepContext& ctx, const Cells& grid, const std::vector<char>& outside_node, GridActivity& activity);

void mark_receding_particles(const StepContext& ctx, const Cells& grid, const Nodes<2>& grid_nodes, const std::vector<unsigned char>& wall_sides,
                             const Points<2>& particles, PointLocations& loc);

}  // namespace loom
