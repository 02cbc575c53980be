// Builds the mesh stores of a scene: the nodes of every body (concatenated, body by body) and one Cells
// store per element formulation in use, with the owning body of each cell.
#pragma once

#include <vector>

#include "engine/mesh/mesh_data.hpp"
#include "engine/scene/scene_spec.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

// Generates the mesh of one body from its spec (generator, distortion, scale).
MeshData generate_body_mesh(const MeshSpec& spec);

// Fills nodes.X (sizing every used node column) and the cell blocks (coloured). Corner nodes of all
// bodies come first, mid-nodes of quadratic cells after them. Returns the body of each node.
std::vector<Index> build_mesh(const SceneSpec& scene, Nodes<2>& nodes, std::vector<Cells>& cells);

}  // namespace loom
