// R3.7 of the 3D remesh (spec 3d-free-surface §3): whether a remesh may keep the previous mesh as it is. It may when
//  - every interior face is locally Delaunay at x up to a margin (the vertex across it is not inside the
//    circumsphere by more than 0.1 % of its squared radius: cospherical points that a deformation has made slightly
//    non-Delaunay one way or the other keep their cells, instead of being recut back and forth), so the previous
//    cells are, to that margin, the Delaunay cells of the body's points;
//  - no cell would tear (circumradius above alpha l_char with no face on the surface);
//  - no two surfaces can join: no two surface points within alpha l_char of each other that lie on different
//    surfaces, or far apart along one (kMergeDetour3d), with the midpoint between them outside the mesh (an empty
//    gap; the two faces of a thin plate are close, but the plate lies between them).
// A resting body then costs no Delaunay triangulation and cannot churn between equivalent triangulations of its
// cospherical points.
#pragma once

#include <array>
#include <vector>

#include "engine/core/types.hpp"

namespace loom {

// The three parts of R3.7 (remesh_3d.cpp keeps the previous mesh when all three hold; its local repair, R3.8, flips
// the faces the first fails). `tets`: 4 point indices each, positively oriented, with their tet_face_neighbours
// (engine/mesh/tet_adjacency.hpp); `average_distance` empty: l_char everywhere, else the local l_char of a cell or
// a pair of points is the mean over its points.

// Whether e lies inside the circumsphere of the tet (a, b, c, d) by more than the margin above (a flat tet counts
// as failing).
bool strictly_inside_sphere(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e);
// Every interior face locally Delaunay to that margin.
bool faces_delaunay(const std::vector<Vec3>& x, const std::vector<Index>& tets, const std::vector<std::array<Index, 4>>& neighbours);
// No cell without a face on the surface has a circumradius above alpha l_char.
bool no_tear(const std::vector<Vec3>& x, const std::vector<Index>& tets, const std::vector<std::array<Index, 4>>& neighbours, double alpha,
             const std::vector<double>& average_distance, double l_char);
// No two surfaces within alpha l_char of each other across an empty gap.
bool no_merge_possible(const std::vector<Vec3>& x, const std::vector<Index>& tets, const std::vector<std::array<Index, 4>>& neighbours,
                       double alpha, const std::vector<double>& average_distance, double l_char);

}  // namespace loom
