// Greedy colouring of cells so that no two cells of one colour share a node (STYLE §4): assembly runs the
// colours one after the other and the cells of a colour in parallel, each writing its own matrix entries,
// so the result does not depend on the thread count.
#pragma once

#include "engine/store/cells.hpp"

namespace loom {

// Fills cells.colour, cells.by_colour and cells.colour_offsets. n_nodes bounds the node indices.
void colour_cells(Cells& cells, Index n_nodes);

}  // namespace loom
