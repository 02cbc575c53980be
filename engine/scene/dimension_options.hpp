// What scene.dimension decides in a scene: the elements a body may take, the 3D parts of a body's mesh
// table (the box generator's z, the extrusion of a 2D generator), and the methods, keys and probe kinds
// that exist in 3D (method fem with tetrahedra; walls, inlets, remeshing and the stress probes are 2D).
#pragma once

#include <string>

#include "engine/scene/scene_spec.hpp"
#include "engine/scene/table_reader.hpp"

namespace loom {

// tet10 only in 3D; in 3D only p1 (tet4), tet10 and p1p1_uphi (mixed tet4) with method fem, p1 and p1p1_up
// (the mixed u-p background grid) with method mpm.
void check_element_dimension(int dimension, Method method, const std::string& element, const TableReader& body);

// After read_mesh: the z parts of the generators in 3D, and the 3D-only keys refused in 2D.
void read_mesh_dimension(int dimension, const TableReader& mesh, MeshSpec& m);

// A 3D scene: method fem or mpm, no walls or inlets, probe kinds and components that exist in 3D; for mpm a
// tet4 grid (no quadrilateral cells, no ghost penalty), the grid Newmark scheme, no tractions, body meshes
// (no generated particle sets) sampled by a tetrahedral rule.
void check_dimension_support(const SceneSpec& s, const TableReader& root);

}  // namespace loom
