// The straight simplex of dimension D (a triangle in 2D, a tetrahedron in 3D) read through its corner indices and a
// position lookup: signed measure, centroid and whether a point lies inside, so that code about cells is written once
// for both dimensions. In 2D the arithmetic is that of triangle_geometry.hpp, operation for operation.
#pragma once

#include <optional>

#include "engine/core/types.hpp"
#include "engine/mesh/tet_mesh.hpp"
#include "engine/mesh/triangle_geometry.hpp"

namespace loom {

// Barycentric coordinates of p in the tetrahedron (a, b, c, d), the first from the other three so that they sum to
// one exactly; nullopt for a tetrahedron of zero volume.
inline std::optional<Vec4> barycentric(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& p) {
  const double v = tet_volume(a, b, c, d);
  if (v == 0.0) return std::nullopt;
  const double l1 = tet_volume(a, p, c, d) / v, l2 = tet_volume(a, b, p, d) / v, l3 = tet_volume(a, b, c, p) / v;
  return Vec4(1.0 - l1 - l2 - l3, l1, l2, l3);
}

// `x(i)` gives the position of corner index i (a Vec<D>).
template <int D, class Position>
double simplex_measure(const Index* corner, Position&& x) {
  if constexpr (D == 2) return signed_area(x(corner[0]), x(corner[1]), x(corner[2]));
  else return tet_volume(x(corner[0]), x(corner[1]), x(corner[2]), x(corner[3]));
}

template <int D, class Position>
Vec<D> simplex_centroid(const Index* corner, Position&& x) {
  Vec<D> sum = x(corner[0]);
  for (int a = 1; a <= D; ++a) sum += x(corner[a]);
  return sum / double(D + 1);
}

// Whether p lies in the simplex, its faces included to `tolerance` in barycentric coordinates (false if degenerate).
template <int D, class Position>
bool simplex_contains(const Index* corner, Position&& x, const Vec<D>& p, double tolerance) {
  if constexpr (D == 2) {
    const auto l = barycentric(x(corner[0]), x(corner[1]), x(corner[2]), p);
    return l && l->minCoeff() >= -tolerance;
  } else {
    const auto l = barycentric(x(corner[0]), x(corner[1]), x(corner[2]), x(corner[3]), p);
    return l && l->minCoeff() >= -tolerance;
  }
}

}  // namespace loom
