// The surface of a tetrahedral mesh as a graph, for the 3D remesh's merge rule (spec 3d-free-surface §3, R3.2 rule 3;
// the 3D counterpart of boundary_loops.hpp): its vertices are the points on faces used by one tetrahedron, its edges
// the sides of those faces. Two points of one surface far apart along it (a fold closing, a front reaching another
// part of the body) or of two surfaces (two bodies, a body and the wall of a void) may join; two neighbours on a
// flat or gently curved surface may not.
#pragma once

#include <array>
#include <vector>

#include "engine/core/types.hpp"

namespace loom {

class SurfaceGraph {
 public:
  // `faces`: outward-oriented triangles (normal (b - a) x (c - a) out of the body) over points 0 .. n_points - 1.
  SurfaceGraph(Index n_points, const std::vector<std::array<Index, 3>>& faces, const std::vector<Vec3>& x);

  bool on_surface(Index v) const { return component_[std::size_t(v)] != kNoIndex; }
  // The connected piece of surface the point lies on, kNoIndex when it lies on none.
  Index component(Index v) const { return component_[std::size_t(v)]; }
  // A component that bounds a void of the body (its outward faces enclose a negative volume): an inner surface.
  bool inner(Index component) const { return inner_[std::size_t(component)] != 0; }
  // The length of the shortest path from a to b along surface edges, searched up to `limit`; infinity beyond it or
  // when b cannot be reached.
  double distance_along(Index a, Index b, double limit) const;

 private:
  const std::vector<Vec3>& x_;
  std::vector<Index> component_;
  std::vector<char> inner_;
  std::vector<Index> first_, neighbour_;  // adjacency along surface edges (ascending neighbours)
};

// Whether two corners of a tetrahedron that lies outside the previous mesh belong to surfaces that meet: on different
// components (or on none), or at least kMergeDetour times their distance apart along the one they share.
constexpr double kMergeDetour3d = 3.0;
bool joins_two_surfaces(const SurfaceGraph& surface, const std::vector<Vec3>& x, const Index (&corners)[4]);

}  // namespace loom
