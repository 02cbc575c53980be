// The stores of a three-dimensional fem scene: the tetrahedral meshes of its bodies (the box generator, a 2D
// generator extruded along z, or a gmsh file of 4- or 10-node tetrahedra) and their boundary conditions
// (nodes in a box or a physical group; face tractions on the boundary faces with every corner in the region).
// The 3D counterparts of build_mesh and build_boundary_conditions (whose quadrilaterals and graded walls have no 3D
// counterpart); PFEM's mid-node ties and frozen traction faces as in 2D.
#pragma once

#include <vector>

#include "engine/mesh/tet_mesh.hpp"
#include "engine/methods/model/build_mesh.hpp"
#include "engine/scene/scene_spec.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

// Fills nodes.X and one cell block per formulation (p1: tet4, tri6: tet10, p1p1_uphi: tet4), coloured. A box is
// meshed as Kuhn tetrahedra, or as the body-centred cubic lattice (mesh.lattice = "bcc"). Corner
// nodes of every body first, then the tet10 mid-nodes (a file's own, else on the straight edges). Returns the
// body of each node; `regions` receives each body's physical groups (corner nodes).
std::vector<Index> build_mesh_3d(const SceneSpec& scene, Nodes<3>& nodes, std::vector<Cells>& cells, BodyRegions* regions = nullptr);

// The linear tetrahedra of a 3D mesh spec (box, extruded plane mesh or gmsh file; a file's quadratic cells by
// their corners), distorted and scaled as the spec says: the MPM's background grid and body meshes.
TetMeshData tet4_mesh_of(const MeshSpec& spec);

// pfem (tie_mid_nodes): the tet10 mid-nodes of the edges of held or loaded boundary faces are tied to the mean of
// their corners ([Schewe 2024] eq 24, as the 2D TRI6 edges), and `frozen_tractions`, the dead-load faces of the
// initial mesh on corners, replace the region's faces (a remeshed surface is not the loaded one).
BoundaryConditions<3> build_boundary_conditions_3d(const SceneSpec& scene, const Nodes<3>& nodes, const std::vector<Cells>& cells,
                                                   const std::vector<Index>& node_body, const BodyRegions& regions, int dofs_per_node,
                                                   bool tie_mid_nodes = false, const std::vector<TractionFace>* frozen_tractions = nullptr);

}  // namespace loom
