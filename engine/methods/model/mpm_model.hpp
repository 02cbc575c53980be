// The stores of an MPM run built from a scene (the mpm recipe's setup, shared with tests and benchmarks
// that drive the systems themselves): the background grid (nodes, cells, layout, activity), the
// material points and the traction points with their locations, materials, the grid's boundary
// conditions, and the Newton system. The particles are located and the grid activated once here, so that
// a body that does not fit in the grid is a scene error (exit 2) and `loom info` shows real sizes.
// D = 2: triangle, quadrilateral and quad9 grids, every scheme (engine/methods/model/mpm_model.cpp); D = 3: tet4 grids,
// the grid Newmark scheme, method mpm (engine/methods/model/mpm_model_3d.cpp). The mpm_fem and particle-Newmark
// members are 2D and stay empty in 3D.
#pragma once

#include <vector>

#include "engine/linalg/linear_solver.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/mesh/coupled_grid.hpp"
#include "engine/scene/scene_spec.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_activity.hpp"
#include "engine/store/grid_layout.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/point_locations.hpp"
#include "engine/store/points.hpp"
#include "systems/assemble/materials/material.hpp"
#include "systems/update/coupled_fem.hpp"

namespace loom {

struct StepContext;

template <int D>
struct MpmModelT {
  // Throws InputError for scene errors that need the grid or the particles.
  explicit MpmModelT(const SceneSpec& scene);

  SceneSpec scene;
  // Background grid
  Nodes<D> grid_nodes;
  Cells grid;
  GridLayoutT<D> layout;
  GridActivity activity;
  // Material points and the points that carry boundary tractions (on edges in 2D, faces in 3D)
  Points<D> particles;
  PointLocations particle_loc;
  Points<D> traction_points;
  PointLocations traction_loc;
  // Point probes follow massless tracer points that move with the grid like the traction points.
  Points<D> probe_points;
  PointLocations probe_loc;

  std::vector<BodyMaterial> materials;
  BoundaryConditions<D> bc;  // on the grid's dofs
  LinearSystem system;
  // Particle Newmark (seed 004): the boundary nodes that lower the soft-stiffness flags, each cell's wall
  // sides (receding contact), and the particle each point probe follows.
  std::vector<char> outside_node;
  std::vector<unsigned char> wall_sides;
  std::vector<Index> probe_particle;

  // Method mpm_fem (seed 004 §4): the FEM bodies' cells follow the grid's in `grid` and share its nodes; the grid
  // moves with the reset field (systems/update/coupled_fem.hpp).
  bool coupled = false;
  CoupledMesh coupled_mesh;
  ResetField reset;

  bool dynamic = false;  // newmark
  bool particle_newmark = false;  // mpm.scheme
  bool mixed = false;    // p1p1_up: D + 1 dofs per grid node
  bool osgs = false;
  LinearSolverKind linear_solver = LinearSolverKind::automatic;

 private:
  void build_particle_newmark_data();
  void build_coupled_model_grid();
  void set_columns(const BodySpec& body);
  void choose_linear_solver();
  void finish_conditions();
  void locate_probe_points(const StepContext& ctx);
};

using MpmModel = MpmModelT<2>;

// Prescribed dofs on the grid nodes of each [[boundary]] box (displacements, and the pressure of p1p1_up);
// body-force expressions per body. InputError for a prescribing region without grid nodes, or a
// displacement that does not vanish at t = 0.
template <int D>
void build_grid_conditions(const SceneSpec& scene, const Nodes<D>& nodes, const GridLayoutT<D>& layout, BoundaryConditions<D>& bc);
template <>
MpmModelT<2>::MpmModelT(const SceneSpec& scene);
template <>
MpmModelT<3>::MpmModelT(const SceneSpec& scene);

}  // namespace loom
