// Linear triangle: shape functions N = (1 - xi - eta, xi, eta) on the reference triangle; gradients are
// constant over the cell. Corners counter-clockwise.
#pragma once

#include <Eigen/Core>

#include "engine/core/types.hpp"

namespace loom {

using Tri3Gradients = Eigen::Matrix<double, 3, 2>;  // row A: dN^A/dx

// Gradients and signed area of the triangle (x0, x1, x2); area <= 0 means degenerate or inverted.
inline double tri3_gradients(const Vec2& x0, const Vec2& x1, const Vec2& x2, Tri3Gradients& dN) {
  const double two_area = (x1.x() - x0.x()) * (x2.y() - x0.y()) - (x2.x() - x0.x()) * (x1.y() - x0.y());
  const double inv = 1.0 / two_area;
  dN << (x1.y() - x2.y()) * inv, (x2.x() - x1.x()) * inv,
        (x2.y() - x0.y()) * inv, (x0.x() - x2.x()) * inv,
        (x0.y() - x1.y()) * inv, (x1.x() - x0.x()) * inv;
  return 0.5 * two_area;
}

// Three-point rule exact for quadratics: points at the edge midpoints' inner neighbours (2/3, 1/6, 1/6),
// weights 1/3 of the area. Barycentric coordinates of point q: kTri3Rule3[q].
inline constexpr double kTri3Rule3[3][3] = {{2.0 / 3, 1.0 / 6, 1.0 / 6}, {1.0 / 6, 2.0 / 3, 1.0 / 6}, {1.0 / 6, 1.0 / 6, 2.0 / 3}};

}  // namespace loom
