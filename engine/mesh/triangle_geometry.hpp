// Where a point lies in a straight triangle: the signed area and the barycentric coordinates of the corners
// (l_a >= 0 for all three inside; the third from the other two so that they sum to one exactly).
#pragma once

#include <optional>

#include "engine/core/types.hpp"

namespace loom {

inline double signed_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  return 0.5 * ((b - a).x() * (c - a).y() - (c - a).x() * (b - a).y());
}

// nullopt for a triangle of zero area.
inline std::optional<Vec3> barycentric(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& p) {
  const double two_area = 2.0 * signed_area(a, b, c);
  if (two_area == 0.0) return std::nullopt;
  const Vec2 q = p - a;
  const double l1 = (q.x() * (c - a).y() - (c - a).x() * q.y()) / two_area, l2 = ((b - a).x() * q.y() - q.x() * (b - a).y()) / two_area;
  return Vec3(1.0 - l1 - l2, l1, l2);
}

}  // namespace loom
