// A tetrahedron cut by a plane, for the probes of 3D scenes: the part of its volume on one side (a volume or mass
// downstream of an inlet's disc) and the polygon of the cut (a section's area and extent). The plane is d(x) =
// (x - point) . normal = 0 with a unit normal; a corner with d >= 0 counts as downstream, so that a face lying in the
// plane is cut once, by the cell behind it.
#pragma once

#include <array>

#include "engine/core/types.hpp"

namespace loom {

// The part of tetrahedron (a, b, c, d) where (x - point) . normal >= 0, as a fraction of its volume (0 for a flat one).
double tet_fraction_downstream(const std::array<Vec3, 4>& corners, const Vec3& point, const Vec3& normal);

// The polygon where the plane cuts the tetrahedron: 0, 3 or 4 points, in order around it.
struct TetCut {
  std::array<Vec3, 4> points;
  int n = 0;
  double area() const;
};
TetCut cut_tet(const std::array<Vec3, 4>& corners, const Vec3& point, const Vec3& normal);

}  // namespace loom
