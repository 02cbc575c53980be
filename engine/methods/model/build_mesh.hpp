// Builds the mesh stores of a scene: the nodes of every body (concatenated, body by body) and one Cells
// store per element formulation in use, with the owning body of each cell.
#pragma once

#include <vector>

#include "engine/mesh/mesh_data.hpp"
#include "engine/scene/scene_spec.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

// Generates the mesh of one body from its spec (generator, distortion, scale), or reads its mesh file.
MeshData generate_body_mesh(const MeshSpec& spec);

// The named regions (physical groups of a mesh file) of each body, with global node indices.
using BodyRegions = std::vector<std::vector<MeshRegion>>;

// Fills nodes.X (sizing every used node column) and the cell blocks (coloured). Corner nodes of all
// bodies come first, mid-nodes of quadratic cells after them: a file's own mid-nodes (curved edges) when it
// has 6-node triangles, else new ones on the straight edges. Returns the body of each node; `regions`, if
// given, receives each body's regions.
std::vector<Index> build_mesh(const SceneSpec& scene, Nodes<2>& nodes, std::vector<Cells>& cells, BodyRegions* regions = nullptr);

}  // namespace loom
