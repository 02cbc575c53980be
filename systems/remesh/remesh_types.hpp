// An edge between two point indices, the unit of boundary polygons and constraints in systems/remesh.
#pragma once

#include <array>

#include "engine/core/types.hpp"

namespace loom {

using Edge = std::array<Index, 2>;

}  // namespace loom
