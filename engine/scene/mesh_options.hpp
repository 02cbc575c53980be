// Mesh-generator keys of a scene: a body's `mesh` table and method mpm's [grid] (the same generators, plus
// the grid's cell type and ghost penalty), read into MeshSpec / GridSpec with the checks the schema cannot
// express (a generator's required keys, quad4's restrictions).
#pragma once

#include "engine/scene/scene_spec.hpp"
#include "engine/scene/table_reader.hpp"

namespace loom {

void read_mesh(const TableReader& mesh, MeshSpec& m);
void read_grid(const TableReader& grid, GridSpec& g);

}  // namespace loom
