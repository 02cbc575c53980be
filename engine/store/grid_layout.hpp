// How points are found in an MPM background grid (the locate system). In 2D: a rectangle of nx x ny squares,
// square k = j nx + i cut into the cells 2k and 2k + 1, is searched by arithmetic; a graded rectangle of
// quad9 cells by a binary search along each axis. In 3D: a box of nx x ny x nz cubes, cube
// k = (kz ny + j) nx + i cut into the six Kuhn tetrahedra 6k .. 6k + 5 (engine/mesh/tet_generators.hpp),
// by arithmetic. Any other triangulation or tetrahedralisation by walking from the point's previous cell
// through the cells' neighbours, starting from a bucket index of the cells when there is no previous cell
// or the walk fails. Lengths in L.
#pragma once

#include <vector>

#include "engine/core/types.hpp"

namespace loom {

template <int D>
struct GridLayoutT {
  static_assert(D == 2 || D == 3);
  using V = Vec<D>;

  bool structured = false;
  V origin = V::Zero();   // structured: lower-left (-front) corner
  V spacing = V::Ones();  // structured: square (cube) size along each axis
  int nx = 0, ny = 0;     // structured: squares (cubes) along x and y
  int nz = 0;             // structured 3D: cubes along z (0 in 2D)

  // 2D only. Graded rectangles of quad9 cells: the cell edges along x (nx + 1 values) and y (ny + 1),
  // ascending; cell k = j nx + i spans [x_lines[i], x_lines[i+1]] x [y_lines[j], y_lines[j+1]] (binary search).
  std::vector<double> x_lines, y_lines;
  // 2D only. Method mpm_fem: the grid's nodes move with the reset field (seed 004 eq 8), so the lines only
  // guess the cell, and a point off the undeformed rectangle may still be inside the moved grid.
  bool moves = false;

  V lo = V::Zero(), hi = V::Zero();  // bounding box of the grid
  double tolerance = 0.0;  // distance outside a cell still accepted as inside it (round-off on shared sides)

  // Bucket index (unstructured grids): bucket (i, j[, k]) covers lo + [i, i+1) x [j, j+1) [x [k, k+1)]
  // bucket_size, number b = (k by + j) bx + i, and lists the cells whose bounding box meets it.
  int bx = 0, by = 0;
  int bz = 0;  // 3D only (0 in 2D)
  V bucket_size = V::Ones();
  std::vector<Index> bucket_offsets;  // bx * by [* bz] + 1
  std::vector<Index> bucket_cells;

  double width() const { return (hi - lo).maxCoeff(); }
};

using GridLayout = GridLayoutT<2>;

}  // namespace loom
