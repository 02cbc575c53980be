// Builds a 3D MPM background grid of linear tetrahedra (tet4) from a tetrahedral mesh: the node store (X),
// the cell store with colours, face neighbours and volumes (the grid never moves, so they are computed
// once), and the layout the locate system searches with (systems/locate/locate_points.hpp). The shape
// functions of a tet4 cell are its barycentric coordinates, computed from the corner positions (tet_shape_at);
// their constant gradients are stored in Cells::gradient_3d.
#pragma once

#include <Eigen/Geometry>  // cross

#include "engine/mesh/tet_generators.hpp"
#include "engine/mesh/tet_mesh.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_layout.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

// `box`: the spec the mesh was generated from by generate_box, undistorted (arithmetic locate over the Kuhn
// cubes); nullptr for any other tetrahedralisation (walk and bucket index).
// cells.neighbour: 4 per cell, entry a the cell across the face opposite corner a (kTetFaces[a]), kNoIndex
// on the boundary. cells.measure: volume, L^3. cells.gradient_3d: dN_a/dx of the corners, 1/L. Throws InputError if a
// cell is degenerate or inverted.
void build_tet_grid(const TetMeshData& mesh, const BoxSpec* box, Formulation formulation, Nodes<3>& nodes, Cells& cells,
                    GridLayoutT<3>& layout);

// Barycentric coordinates of x in tet4 cell c: N_a = the volume of the tetrahedron with x in place of corner a
// over the cell's volume (N_0 = 1 - N_1 - N_2 - N_3, so that they sum to one). Outside the cell they extend
// linearly (the most negative one names the face x is beyond).
inline Vec4 tet_shape_at(const Cells& grid, const Nodes<3>& nodes, Index c, const Vec3& x) {
  const Vec3& x0 = nodes.X[grid.node(c, 0)];
  const Vec3 e1 = nodes.X[grid.node(c, 1)] - x0, e2 = nodes.X[grid.node(c, 2)] - x0, e3 = nodes.X[grid.node(c, 3)] - x0;
  const Vec3 d = x - x0;
  // x - x0 = N_1 e1 + N_2 e2 + N_3 e3; dotting with e2 x e3, e3 x e1, e1 x e2 isolates each N_a.
  const Vec3 n1 = e2.cross(e3), n2 = e3.cross(e1), n3 = e1.cross(e2);
  const double inv_det = 1.0 / e1.dot(n1);
  Vec4 N;
  N[1] = d.dot(n1) * inv_det;
  N[2] = d.dot(n2) * inv_det;
  N[3] = d.dot(n3) * inv_det;
  N[0] = 1.0 - N[1] - N[2] - N[3];
  return N;
}

}  // namespace loom
