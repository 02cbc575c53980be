// How points are found in an MPM background grid (the locate system): a rectangle of nx x ny squares,
// square k = j nx + i cut into the cells 2k and 2k + 1, is searched by arithmetic; a graded rectangle of
// quad9 cells by a binary search along each axis; any other
// triangulation by walking from the point's previous cell through the cells' neighbours, starting from a
// bucket index of the cells when there is no previous cell or the walk fails. Lengths in L.
#pragma once

#include <vector>

#include "engine/core/types.hpp"

namespace loom {

struct GridLayout {
  bool structured = false;
  Vec2 origin = Vec2::Zero();   // structured: lower-left corner
  Vec2 spacing = Vec2::Ones();  // structured: square size
  int nx = 0, ny = 0;           // structured: squares along x and y

  // Graded rectangles of quad9 cells: the cell edges along x (nx + 1 values) and y (ny + 1), ascending;
  // cell k = j nx + i spans [x_lines[i], x_lines[i+1]] x [y_lines[j], y_lines[j+1]] (binary search).
  std::vector<double> x_lines, y_lines;
  // Method mpm_fem: the grid's nodes move with the reset field (seed 004 eq 8), so the lines only guess the
  // cell, and a point off the undeformed rectangle may still be inside the moved grid.
  bool moves = false;

  Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();  // bounding box of the grid
  double tolerance = 0.0;  // distance outside a cell still accepted as inside it (round-off on shared edges)

  // Bucket index (unstructured grids): bucket (i, j) covers lo + [i, i+1) x [j, j+1) bucket_size and lists
  // the cells whose bounding box meets it.
  int bx = 0, by = 0;
  Vec2 bucket_size = Vec2::Ones();
  std::vector<Index> bucket_offsets;  // bx * by + 1
  std::vector<Index> bucket_cells;

  double width() const { return (hi - lo).maxCoeff(); }
};

}  // namespace loom
