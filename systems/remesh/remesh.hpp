// PFEM remeshing (seed 000 §3.1; seed 001 §3.1): a constrained Delaunay triangulation of the points at their
// converged positions X_n, with the previous boundary polygon as constraints (seed 000 Fig 2a), and then one of
// two rules for which triangles make up the body:
//  - SurfaceMode::alpha (seed 000): every triangle that passes the alpha test (eq 16): a triangle whose
//    circumradius exceeds alpha * l_char is not part of the body. l_char is a constant, or the local l_char^loc
//    of eqs 17-18: the mean over the triangle's corners of each point's average distance to its neighbours in
//    the previous mesh.
//  - SurfaceMode::constrained (seed 001 §3.1: the free surface is kept as it is): the triangles inside the
//    previous boundary polygon, so that a concave surface is never filled; the alpha test only decides where the
//    surface closes or opens. A triangle outside the polygon is added when its edges are all shorter than
//    alpha l_char (not its circumradius: that of a sliver in a closing slit grows as the slit closes) and it fills
//    a void enclosed by the body or joins two surfaces: two of its corners lie on different boundary loops, or are at least kMergeSteps boundary edges
//    and kMergeDetour times their distance apart along one (a fold closing, a falling body reaching another part
//    of the surface; not the two sides of a bend); a triangle inside is removed when it fails the test and none
//    of its edges is on the surface (the body tearing open inside).
// Edges of the previous boundary that cross another (a step that pushed surface points through the surface)
// are left out of the constraints (systems/remesh/boundary_crossings.hpp) and counted; the inside test then
// locates the triangles' centroids in the previous triangles rather than counting constraint crossings.
// The boundary of the new mesh is the set of edges used by one triangle: the outline of a valid triangulation,
// which never crosses itself; it constrains the next remesh.
#pragma once

#include <functional>
#include <vector>

#include "engine/core/types.hpp"
#include "systems/remesh/remesh_types.hpp"

namespace loom {

enum class SurfaceMode { alpha, constrained };

// Two corners of a triangle outside the polygon belong to two surfaces that meet when they are at least this
// many boundary edges apart along one loop and the boundary between them is at least kMergeDetour times longer
// than the gap: a sharp fold (two edges whose angle has closed below about 39 degrees, a front that rolls onto the
// ground beside the body's own base) or a slot that has narrowed to a fifth of its depth (about 10); not an ear of
// a flat or gently curved surface (a right-angled corner has 1.4).
constexpr Index kMergeSteps = 2;
constexpr double kMergeDetour = 3.0;

struct RemeshSettings {
  double alpha = 1.0;
  double l_char = 0.0;        // constant characteristic length (used when local == false)
  bool local = false;         // l_char^loc from `average_distance` (eq 18)
  SurfaceMode surface = SurfaceMode::alpha;
  // The spacing the particle edits keep at a point, where it varies (graded walls); empty: none. A triangle then
  // fails the alpha test only if its circumradius also exceeds alpha times the spacing at its circumcentre: a
  // triangle of fine corners beside a graded wall has an empty circle that reaches into the coarse cells above
  // them, which says nothing of the body opening (the corners' l_char^loc is the fine spacing).
  std::function<double(const Vec2&)> spacing_at = nullptr;
};

struct RemeshResult {
  std::vector<Index> triangles;   // 3 point indices per triangle, counter-clockwise
  std::vector<Edge> boundary;     // edges used by one triangle, oriented as in their triangle
  std::vector<char> merged_face;  // per triangle: 1 if it lies outside the previous boundary (a gap it fills held no material)
  Index rejected = 0;             // triangles removed by the alpha test (alpha mode; constrained: inside ones)
  Index isolated = 0;             // points in no triangle (left out of the solve)
  Index merged = 0;               // constrained: triangles outside the polygon added (two surfaces met)
  Index crossings = 0;            // previous boundary edges left out of the constraints because they cross
  double area = 0.0;              // total area of the kept triangles
};

// What a probe can read of the step's remesh (all bodies together).
struct RemeshStats {
  bool changed = false;
  Index rejected = 0, isolated = 0, merged = 0, crossings = 0;
  Index inserted = 0, removed = 0;  // particles added (long edges, inflow rows) and removed (close pairs, closed inlets)
  double area_change = 0.0;  // area after - area before (3D: volume)
  Index flipped = 0, slivers = 0, capped = 0;  // 3D: flips of the sliver removal, slivers left, flat caps left out
  Index repaired = 0;                          // 3D: flips of the local repair (remesh.repair)
};

// Triangulates `positions` (one per point; coincident points are an error) with the `constraints`
// (edges between point indices: the previous boundary) and keeps the triangles that `settings.surface` says.
// `previous_triangles` (the previous mesh on the same points, at `positions`) is read in constrained mode only,
// `average_distance` only when settings.local (one value per point).
void remesh_points(const std::vector<Vec2>& positions, const std::vector<Edge>& constraints,
                   const std::vector<Index>& previous_triangles, const RemeshSettings& settings,
                   const std::vector<double>& average_distance, RemeshResult& out);

// Alpha mode without a previous mesh.
inline void remesh_points(const std::vector<Vec2>& positions, const std::vector<Edge>& constraints,
                          const RemeshSettings& settings, const std::vector<double>& average_distance, RemeshResult& out) {
  remesh_points(positions, constraints, {}, settings, average_distance, out);
}

// eq 17: for each point, the mean distance to its neighbours along the edges of `triangles` (points in
// no triangle get 0).
void average_neighbour_distance(const std::vector<Vec2>& positions, const std::vector<Index>& triangles,
                                std::vector<double>& average_distance);

// Edges used by exactly one triangle, oriented as in that triangle (counter-clockwise outline).
std::vector<Edge> boundary_of(const std::vector<Index>& triangles);

}  // namespace loom
