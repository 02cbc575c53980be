// Shape values and gradients of a located point in its grid cell, for the cell types whose kernels are
// templated on the node count NEN: quad4 (from the stored corner values N, engine/mesh/grid_shape.hpp) and
// quad9 (from the stored reference coordinates xi, engine/mesh/quad9_shape.hpp). Gradients are with respect
// to the grid's coordinates X (the grid at the step's start).
#pragma once

#include "engine/mesh/grid_shape.hpp"
#include "engine/mesh/quad9_shape.hpp"
#include "engine/store/point_locations.hpp"

namespace loom {

template <int NEN>
struct PointShape {
  Eigen::Matrix<double, NEN, 1> N;
  Eigen::Matrix<double, NEN, 2> dN;
};

inline Quad9Coordinates quad9_cell_coordinates(const Cells& grid, const Nodes<2>& nodes, Index c) {
  Quad9Coordinates X;
  for (int a = 0; a < 9; ++a) X.row(a) = nodes.X[grid.node(c, a)].transpose();
  return X;
}

template <int NEN>
PointShape<NEN> point_shape(const Cells& grid, const Nodes<2>& nodes, Index c, const PointLocations& loc, Index p) {
  PointShape<NEN> s;
  if constexpr (NEN == 9) {
    s.N = quad9_shape(loc.xi[p]);
    s.dN = quad9_gradients(quad9_cell_coordinates(grid, nodes, c), loc.xi[p]);
  } else {
    s.N = loc.N[p].template head<NEN>();
    s.dN = grid_shape_gradients<NEN>(grid, nodes, c, loc.N[p]);
  }
  return s;
}

// Quadrature of a whole cell: calls f(dN, weight) at the points of the 3 x 3 Gauss rule (quad9) or the
// 2 x 2 rule (quad4), weight = Gauss weight x det J.
template <int NEN, class F>
void for_each_cell_gauss_point(const Cells& grid, const Nodes<2>& nodes, Index c, F&& f) {
  if constexpr (NEN == 9) {
    const Quad9Coordinates X = quad9_cell_coordinates(grid, nodes, c);
    const Quad9Gauss& rule = quad9_gauss();
    for (std::size_t q = 0; q < 9; ++q) {
      double det = 0.0;
      const Eigen::Matrix<double, 9, 2> dN = quad9_gradients(X, rule.xi[q], &det);
      f(dN, rule.weight[q] * det);
    }
  } else {
    static_assert(NEN == 4, "quad4 or quad9");
    const double g = 0.5 / std::sqrt(3.0);
    for (double eta : {0.5 - g, 0.5 + g})
      for (double xi : {0.5 - g, 0.5 + g}) {
        const Vec4 N((1.0 - xi) * (1.0 - eta), xi * (1.0 - eta), xi * eta, (1.0 - xi) * eta);
        f(grid_shape_gradients<4>(grid, nodes, c, N), 0.25 * grid.measure[c]);
      }
  }
}

}  // namespace loom
