// One conforming quad9 mesh for method mpm_fem (seed 004 §4): the MPM background grid (a graded rectangle,
// engine/mesh/quad9_grid.hpp) and the FEM bodies' blocks (rectangles of quad9 cells outside it) with the nodes of
// their common sides shared, so that one displacement field lives on both and continuity and traction balance
// hold without multipliers or contact search. The grid keeps its numbering (cells 0 .. NX NY - 1, located by
// the layout); the blocks' cells follow, tagged with their body, and their new nodes follow the grid's.
#pragma once

#include <string>
#include <vector>

#include "engine/mesh/quad9_grid.hpp"

namespace loom {

struct FemBlock {
  GradedRectangle rectangle;  // refined like the grid (the same J), so that the common side conforms
  Index body = 0;
  std::string name;           // for messages
};

struct CoupledMesh {
  Index grid_cells = 0;          // cells [0, grid_cells) are the background grid, the rest FEM cells
  std::vector<char> fem_node;    // per node: belongs to an FEM cell (interface nodes included)
  std::vector<char> interface_node;  // per node: shared by a grid cell and an FEM cell
};

// Throws InputError naming the body when a block overlaps the grid, touches it nowhere, or meets it with nodes
// that are not the grid's (a mesh that does not conform).
CoupledMesh build_coupled_grid(const GradedRectangle& grid, const std::vector<FemBlock>& blocks, Formulation formulation, Nodes<2>& nodes,
                               Cells& cells, GridLayout& layout);

}  // namespace loom
