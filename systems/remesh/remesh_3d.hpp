// PFEM remeshing on tetrahedra (spec 3d-free-surface §3; seed 001 §3.1's 3D rule with seed 000's alpha test). CGAL
// has no constrained Delaunay in 3D, so the previous mesh at x_n plays the role the boundary constraints play in 2D:
//  R3.1 a Delaunay_triangulation_3 of the points (sequential, spatially sorted, degeneracies resolved by a symbolic
//       perturbation: unique, and nothing after depends on the order it stores cells or their vertices in, so the
//       result depends on neither the thread count nor the insertion order);
//  R3.2 every finite cell (classified in parallel, on its corners in canonical order) is kept or dropped: a cell
//       whose centroid lies in the previous mesh (a cell with its four corners on the previous surface only if the
//       centroid lies a tenth of its smallest altitude below that surface: not a flat cap on a flat or convex face)
//       is kept when it passes the alpha test (circumradius <= alpha l_char, eq 16 with eqs 17-18's local l_char) or
//       has a face on the previous surface, and dropped otherwise (the body tears open inside); a cell outside is
//       kept only when all its edges are within alpha l_char and it joins two surfaces (surface_graph.hpp) or fills a
//       void of the body (merged);
//  R3.4 slivers removed by flips with the points fixed (tet_flips.hpp);
//  R3.5 cells in the order of their sorted corner quadruples, each with its corners in a canonical positive order;
//  R3.6 the surface: the faces used by one cell, outward;
//  R3.7 a previous mesh that is still Delaunay (every interior face locally Delaunay at x_n, cospherical counts),
//       that no cell of it would tear and where no two surfaces are closer than alpha l_char, is kept as it is:
//       a resting body costs nothing and does not churn between equivalent triangulations of cospherical points.
//  R3.8 a previous mesh that fails R3.7 only by faces that are no longer Delaunay is repaired in place by Lawson's
//       flips (tet_flips.hpp: repair_delaunay), none of which makes a sliver, then R3.4; only if a face cannot be
//       flipped (stuck) or a repaired cell would tear is the body triangulated again (R3.1-R3.6). Cells away from
//       the faces that failed keep their corners, a flow pays for the faces it moved across, and near-cospherical
//       cells (an extruded prism, a BCC pyramid) are not recut into slivers the flips then cut another way.
// Without a previous mesh (the first mesh of a point set), every cell that passes the alpha test is kept.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "engine/core/types.hpp"

namespace loom {

struct Remesh3dSettings {
  double alpha = 1.0;
  double l_char = 0.0;        // constant characteristic length (used when local == false)
  bool local = false;         // l_char^loc: the mean over a cell's corners of `average_distance`
  bool keep_delaunay = true;  // R3.7
  double flip_quality = 0.2;  // R3.4: cells below this 3 r_in / R are improved (0: no flips)
  bool repair = false;        // R3.8 (with keep_delaunay)
};

struct Remesh3dResult {
  std::vector<Index> tets;                     // 4 point indices per cell, positively oriented
  std::vector<std::array<Index, 3>> surface;   // faces used by one cell, outward
  std::vector<std::array<Index, 4>> neighbours;  // tet_face_neighbours of tets (engine/mesh/tet_adjacency.hpp)
  std::vector<char> merged_cell;               // per cell: 1 if it lies outside the previous mesh (it held no material)
  bool kept_previous = false;                  // R3.7 (or R3.8 with nothing to flip): the previous mesh, unchanged
  Index repaired = 0;   // R3.8: flips of the local repair (0 when the body was triangulated again)
  Index rejected = 0;   // cells inside the previous mesh dropped by the alpha test (the body tearing open)
  Index isolated = 0;   // points in no cell
  Index merged = 0;     // cells outside the previous mesh kept (two surfaces met, a void filled)
  Index capped = 0;     // cells with every corner on the previous surface dropped as flat caps
  Index flipped = 0;    // flips done by R3.4 (2-3, 3-2 and edge removals)
  Index slivers = 0;    // cells below 0.1 in 3 r_in / R after R3.4
  double volume = 0.0;  // of the kept cells
};

// `previous_tets`: the previous mesh on the same points, at `positions` (empty: a first mesh); `average_distance`:
// one value per point when settings.local (eq 17 on the previous mesh); `previous_neighbours`: the previous mesh's
// tet_face_neighbours when known (a previous result's `neighbours`), else they are found. Coincident points are a
// RunError.
void remesh_points_3d(const std::vector<Vec3>& positions, const std::vector<Index>& previous_tets, const Remesh3dSettings& settings,
                      const std::vector<double>& average_distance, Remesh3dResult& out,
                      const std::vector<std::array<Index, 4>>* previous_neighbours = nullptr);

// eq 17 in 3D: each point's mean distance to its neighbours along the edges of `tets` (0 for points in none).
void average_neighbour_distance_3d(const std::vector<Vec3>& positions, const std::vector<Index>& tets, std::vector<double>& average_distance);

// The faces used by one tetrahedron, outward (the surface of a mesh), in ascending order of (tet, local face).
std::vector<std::array<Index, 3>> surface_of(const std::vector<Index>& tets);

// A cell's corners in the canonical positive order: the smallest first, then the other three rotated (an even
// permutation, so the orientation is kept) to start at their smallest.
std::array<Index, 4> canonical_tet(const std::array<Index, 4>& positive);

}  // namespace loom
