// Shape functions of MPM background-grid cells at a point x (seed 003 §3): the linear triangle (tri3,
// barycentric coordinates, constant gradients stored on the cells) and the bilinear quadrilateral (quad4)
// of a rectangle grid, whose cells are axis-aligned rectangles with corners counter-clockwise from the
// lower left. With xi = (x - x_0) / h_x and eta = (y - y_0) / h_y,
//   N = [(1 - xi)(1 - eta), xi (1 - eta), xi eta, (1 - xi) eta],
//   dN/dx = [-(1 - eta), 1 - eta, eta, -eta] / h_x,   dN/dy = [-(1 - xi), -xi, xi, 1 - xi] / h_y,
// and xi = N_1 + N_2, eta = N_2 + N_3, so the gradients follow from N and the cell. Outside the cell the
// same formulas extend N (bi)linearly: the values still sum to one and reproduce linear fields.
// A Vec4 holds N for either cell; a triangle's fourth entry is 0. In 3D (D = 3) the cells are linear
// tetrahedra (tet4): N are the barycentric coordinates (tet_shape_at), their gradients constant and stored.
#pragma once

#include <Eigen/Core>
#include <algorithm>

#include "engine/core/types.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

template <int NC, int D = 2>
using CornerGradients = Eigen::Matrix<double, NC, D>;  // one row per corner: dN_a/dx, dN_a/dy (, dN_a/dz)

inline Vec4 grid_shape_at(const Cells& grid, const Nodes<2>& nodes, Index c, const Vec2& x) {
  const Vec2& x0 = nodes.X[grid.node(c, 0)];
  Vec4 N;
  if (grid.stride == 4) {
    const Vec2 h = nodes.X[grid.node(c, 2)] - x0;
    const double xi = (x.x() - x0.x()) / h.x(), eta = (x.y() - x0.y()) / h.y();
    N << (1.0 - xi) * (1.0 - eta), xi * (1.0 - eta), xi * eta, (1.0 - xi) * eta;
    return N;
  }
  const Mat32& g = grid.gradient[c];
  const Vec2 d = x - x0;
  N[1] = g.row(1).dot(d);
  N[2] = g.row(2).dot(d);
  N[0] = 1.0 - N[1] - N[2];
  N[3] = 0.0;
  return N;
}

// How far inside the cell a point with shape values N is: the smallest value for a triangle, the
// smallest of xi, 1 - xi, eta, 1 - eta for a quadrilateral (negative outside; the cell's corners are 0).
inline double grid_shape_inside(int corners, const Vec4& N) {
  if (corners == 3) return N.head<3>().minCoeff();
  const double xi = N[1] + N[2], eta = N[2] + N[3];
  return std::min(std::min(xi, 1.0 - xi), std::min(eta, 1.0 - eta));
}

template <int NC, int D>
CornerGradients<NC, D> grid_shape_gradients(const Cells& grid, const Nodes<D>& nodes, Index c, const Vec4& N) {
  if constexpr (D == 3) {
    static_assert(NC == 4, "3D grids are tet4");
    return grid.gradient_3d[c];
  } else if constexpr (NC == 3) {
    return grid.gradient[c];
  } else {
    const Vec2 h = nodes.X[grid.node(c, 2)] - nodes.X[grid.node(c, 0)];
    const double xi = N[1] + N[2], eta = N[2] + N[3];
    CornerGradients<4> g;
    g << -(1.0 - eta) / h.x(), -(1.0 - xi) / h.y(),  //
        (1.0 - eta) / h.x(), -xi / h.y(),            //
        eta / h.x(), xi / h.y(),                     //
        -eta / h.x(), (1.0 - xi) / h.y();
    return g;
  }
}

}  // namespace loom
