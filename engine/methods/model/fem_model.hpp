// The stores of a mesh-based run built from a scene (the fem recipe's step 1-3, shared with tests and
// benchmarks that drive the systems themselves): nodes with the columns the scene needs, cell blocks
// and their quadrature points with the reference geometry, materials, boundary conditions, and the
// Newton system (dof numbering, sparsity, scatter).
#pragma once

#include <vector>

#include "engine/linalg/linear_solver.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/methods/model/build_mesh.hpp"
#include "engine/scene/scene_spec.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/edges.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/points.hpp"
#include "engine/store/quad_points.hpp"
#include "engine/store/walls.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {

// D = 2, or 3 for methods fem and pfem on tetrahedra (fem: seed 001's elements on face domains, walls as planes).
template <int D>
struct FemModelT {
  // Throws InputError for scene errors that need the mesh (empty regions, degenerate meshes, ...).
  explicit FemModelT(const SceneSpec& scene);

  SceneSpec scene;
  Nodes<D> nodes;
  Points<D> points;  // not used by mesh-based FEM: no column is allocated
  std::vector<Cells> cells;
  std::vector<QuadPoints<D>> quad;
  std::vector<Edges<D>> edges;   // integration domains of seed 001's formulations (es_*, fem_*), each tied to a cell block
  std::vector<char> j_projection;  // per body: body[].j_projection
  std::vector<BodyMaterial> materials;
  BoundaryConditions<D> bc;
  WallsT<D> walls;  // rigid planes with their penalties ([[wall]]); the contact state is in nodes
  LinearSystem system;
  std::vector<Index> node_body;  // owning body of each node
  BodyRegions regions;           // per body: the physical groups of its mesh file (global corner nodes)
  bool mixed = false;            // some body carries the dilatation phi or the pressure p (D + 1 dofs per node)
  LinearSolverKind linear_solver = LinearSolverKind::automatic;  // what the tangent allows
};

using FemModel = FemModelT<2>;
extern template struct FemModelT<2>;
extern template struct FemModelT<3>;

}  // namespace loom
