// The faces of the active grid that carry the ghost penalty (grid.ghost_penalty; the kernel is
// systems/assemble/elements/ghost_face.hpp): every side shared by two active cells of which at least one
// is cut, i.e. has a corner that an inactive cell shares (a corner on the grid's outer boundary alone does
// not count: there the body is clamped or the grid is too small, not cut). Called by activate_grid when the
// active set changes; fills activity.ghost_faces (nodes in the kernel's order, coloured), ghost_cells and
// ghost_ends, in ascending order of the left cell.
#pragma once

#include <utility>
#include <vector>

#include "engine/store/cells.hpp"
#include "engine/store/grid_activity.hpp"

namespace loom {

void find_ghost_faces(const Cells& grid, Index n_nodes, GridActivity& activity);

// Appends the face between cell c and its neighbour n across side a in the kernel's local order (c's
// corners, then n's corners off the face, in n's order); returns the face's corners.
std::pair<Index, Index> append_face_nodes(const Cells& grid, Index c, int a, Index n, std::vector<Index>& conn);

}  // namespace loom
