// Scene errors that need the built model (exit 2, naming the key and what to change): a static model that
// does not hold every rigid motion of each body (engine/methods/model/rigid_motions.hpp), and a point probe whose
// point lies outside every body.
#pragma once

#include <vector>

#include "engine/scene/scene_spec.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

// Static runs only (the inertia of a dynamic run holds the rigid motions). `node_body` names the body of a
// piece; `active` restricts the cells (the active grid of mpm).
void check_rigid_motions_held(const SceneSpec& scene, const Nodes<2>& nodes, const std::vector<const Cells*>& blocks,
                              const BoundaryConditions<2>& bc, const std::vector<Index>& node_body,
                              const std::vector<Index>* active = nullptr);

// Each point or stress probe's `at` must lie in a cell of its body (of any body when it names none), in reference
// coordinates: cells given by their first three (corner) nodes, to a tolerance of 1e-6 of the cell size.
void check_point_probes_inside(const SceneSpec& scene, const std::vector<Vec2>& X, const std::vector<Index>& corners,
                               const std::vector<Index>& corner_body);

// 3D: each stress probe must have found a tetrahedron of its body that holds its point (`cells_found[k]` of them
// for probe k; the 2D check above runs before the plan).
void check_stress_probes_found(const SceneSpec& scene, const std::vector<std::size_t>& cells_found);

}  // namespace loom
