// The Walls store of a mesh-based run from the scene's [[wall]] tables, with the default penalty where the scene
// leaves it to loom: k_N = 100 E / h (E the largest Young's modulus, h the mean boundary edge length at the start,
// of the bodies the wall acts on; in 3D the mean edge length of their surface triangles), so that a node pressed with a contact pressure p sinks g = p / k_N, below
// 1 % of h while p < E.
#pragma once

#include <vector>

#include "engine/scene/scene_spec.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/walls.hpp"

namespace loom {

template <int D>
WallsT<D> build_walls(const SceneSpec& scene, const Nodes<D>& nodes, const std::vector<Cells>& cells, const std::vector<Index>& node_body);

}  // namespace loom
