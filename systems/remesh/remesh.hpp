// PFEM remeshing (seed 000 §3.1): a constrained Delaunay triangulation of the points at their converged
// positions X_n, with the previous boundary polygon as constraints (Fig 2a), followed by the alpha-shape
// test of every triangle (eq 16): a triangle whose circumradius exceeds alpha * l_char is not part of the
// body. l_char is a constant, or the local l_char^loc of eqs 17-18: the mean over the triangle's corners of
// each point's average distance to its neighbours in the previous mesh. The boundary of the new mesh is
// the set of edges used by one triangle; it constrains the next remesh.
#pragma once

#include <array>
#include <vector>

#include "engine/core/types.hpp"

namespace loom {

using Edge = std::array<Index, 2>;

struct RemeshSettings {
  double alpha = 1.0;
  double l_char = 0.0;        // constant characteristic length (used when local == false)
  bool local = false;         // l_char^loc from `average_distance` (eq 18)
};

struct RemeshResult {
  std::vector<Index> triangles;   // 3 point indices per triangle, counter-clockwise
  std::vector<Edge> boundary;     // edges used by one triangle, oriented as in their triangle
  Index rejected = 0;             // triangles removed by the alpha test
  Index isolated = 0;             // points in no triangle (left out of the solve)
  double area = 0.0;              // total area of the kept triangles
};

// What a probe can read of the step's remesh (all bodies together).
struct RemeshStats {
  bool changed = false;
  Index rejected = 0, isolated = 0;
  double area_change = 0.0;  // area after - area before
};

// Triangulates `positions` (one per point; coincident points are an error) with the `constraints`
// (edges between point indices, e.g. the previous boundary) and applies the alpha test.
// `average_distance` is read only when settings.local (one value per point).
void remesh_points(const std::vector<Vec2>& positions, const std::vector<Edge>& constraints,
                   const RemeshSettings& settings, const std::vector<double>& average_distance, RemeshResult& out);

// eq 17: for each point, the mean distance to its neighbours along the edges of `triangles` (points in
// no triangle get 0).
void average_neighbour_distance(const std::vector<Vec2>& positions, const std::vector<Index>& triangles,
                                std::vector<double>& average_distance);

// Edges used by exactly one triangle, oriented as in that triangle (counter-clockwise outline).
std::vector<Edge> boundary_of(const std::vector<Index>& triangles);

}  // namespace loom
