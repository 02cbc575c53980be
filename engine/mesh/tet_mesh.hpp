// A tetrahedral mesh as a builder produces it, before it is loaded into stores (the 3D counterpart of
// MeshData): corner coordinates and tet4 connectivity, and the faces of its boundary.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Geometry>  // cross

#include "engine/core/types.hpp"
#include "engine/mesh/mesh_data.hpp"  // MeshRegion

namespace loom {

struct TetMeshData {
  std::vector<Vec3> X;       // corner node coordinates
  std::vector<Index> tets;   // 4 node indices per tetrahedron, positively oriented (VTK_TETRA)
  std::vector<MeshRegion> regions;      // a mesh file's physical groups, by corner nodes (no edges)
  std::vector<std::size_t> source_tag;  // per tetrahedron: its element tag in the file (for messages)
  Index n_tets() const { return Index(tets.size() / 4); }
};

// A mesh of 10-node tetrahedra: corners first (the tet4 mesh's nodes, same indices), then one mid-node per
// edge on the straight edge; cells in VTK_QUADRATIC_TETRA order (corners, then edges 01 12 20 03 13 23).
struct Tet10MeshData {
  std::vector<Vec3> X;
  std::vector<Index> cells;  // 10 per cell
  Index n_corners = 0;
  std::vector<MeshRegion> regions;  // by corner nodes, as TetMeshData's
  Index n_cells() const { return Index(cells.size() / 10); }
};

// The faces of tetrahedron corners (v0, v1, v2, v3) opposite corner 0, 1, 2, 3, each ordered so that its
// normal (b - a) x (c - a) points out of a positively oriented tetrahedron.
inline constexpr int kTetFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

// Signed volume of the tetrahedron (a, b, c, d): positive when d lies on the side (b - a) x (c - a) points to.
inline double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).cross(c - a).dot(d - a) / 6.0;
}

// Faces used by one tetrahedron only, outward-oriented, in ascending order of (tet, local face) (tet_adjacency.cpp).
struct BoundaryFace {
  std::array<Index, 3> nodes;
  Index tet;
  int local;  // the corner of `tet` the face is opposite to
};
std::vector<BoundaryFace> boundary_faces(const std::vector<Index>& tets);

}  // namespace loom
