// Builds an MPM background grid (seed 003 §3) from a generated triangulation or a rectangle of quad4 cells: the node store (X), the cell
// store with colours, neighbours, areas and shape gradients (the grid never moves, so they are computed
// once), and the layout the locate system searches with.
#pragma once

#include "engine/mesh/generators.hpp"
#include "engine/mesh/mesh_data.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_layout.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

// `rectangle`: the spec the mesh was generated from when it is a rectangle with pattern right or
// alternating (arithmetic locate); nullptr for any other triangulation (walk).
// Throws InputError if a cell is degenerate or clockwise.
void build_background_grid(const MeshData& mesh, const RectangleSpec* rectangle, Formulation formulation, Nodes<2>& nodes,
                           Cells& cells, GridLayout& layout);

// A rectangle of nx x ny axis-aligned quad4 cells (bilinear), cell k = j nx + i, corners counter-clockwise
// from the lower left; located by arithmetic. Throws InputError for an empty rectangle.
void build_quad_grid(const RectangleSpec& rectangle, Formulation formulation, Nodes<2>& nodes, Cells& cells, GridLayout& layout);

// Fills cells.neighbour (one per side, Cells::side_corners: the cell across it).
void find_cell_neighbours(Cells& cells, Index n_nodes);

}  // namespace loom
