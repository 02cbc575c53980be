// The three stores of an MPM background grid as engine/mesh/background_grid.hpp builds them, for unit
// tests that drive the grid systems without a scene.
#pragma once

#include "engine/store/cells.hpp"
#include "engine/store/grid_layout.hpp"
#include "engine/store/nodes.hpp"

namespace loom::testing {

struct GridStores {
  Nodes<2> nodes;
  Cells cells;
  GridLayout layout;
};

}  // namespace loom::testing
