// Adjacency of a tetrahedral mesh in linear time: faces, edges and cells are bucketed by their smallest corner
// (a counting sort over the points) and only the few records of one bucket are sorted. A remesh every step of 10^5
// points builds these several times; a global sort of 4 x 6 x 10^5 face records was a third of its cost. Every
// result is deterministic and independent of hashing, and equals what a global lexicographic sort gives.
#pragma once

#include <array>
#include <utility>
#include <vector>

#include "engine/core/types.hpp"
#include "engine/mesh/tet_mesh.hpp"  // BoundaryFace

namespace loom {

// Marks a face found in more than two tetrahedra (a non-manifold input).
inline constexpr Index kNonManifold = -2;

// Per tetrahedron, the tetrahedron across the face opposite each corner (kTetFaces order): kNoIndex on the surface,
// kNonManifold when the face is in three or more.
std::vector<std::array<Index, 4>> tet_face_neighbours(const std::vector<Index>& tets);

// boundary_faces (tet_mesh.hpp) of `tets` whose tet_face_neighbours are known.
std::vector<BoundaryFace> boundary_faces(const std::vector<Index>& tets, const std::vector<std::array<Index, 4>>& neighbours);

// The edges of `tets` as (a, b) with a < b, each once, in ascending lexicographic order.
std::vector<std::pair<Index, Index>> tet_edges(const std::vector<Index>& tets);

// The cells of a mesh as sets of corners, for "is this cell (any order of its corners) one of them?".
class TetCellSet {
 public:
  explicit TetCellSet(const std::vector<Index>& tets);
  // The index of the cell with corners {v[0..3]}, or kNoIndex.
  Index find(const Index* v) const;
  bool contains(const Index* v) const { return find(v) != kNoIndex; }

 private:
  std::vector<Index> first_;                // per smallest corner, its cells' range in rest_
  std::vector<std::array<Index, 4>> rest_;  // the other three corners ascending, and the cell's index
};

// The cells' indices in ascending lexicographic order of their sorted corners (no two cells share all four).
std::vector<Index> tet_sorted_order(const std::vector<Index>& tets);

}  // namespace loom
