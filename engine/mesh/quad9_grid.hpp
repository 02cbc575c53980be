// Graded rectangles of quad9 cells (seed 004 §2.2, §6): a coarse block of nx x ny cells whose widths and
// heights grow geometrically (grading g: each cell g times the one before it, left to right and bottom to
// top), refined `refinements` times by midpoint refinement (every cell into four, so the grading is kept
// and every coarse cell is split into 2^J x 2^J equal cells). Cell k = j NX + i, nodes in the order of
// engine/mesh/quad9_shape.hpp; the lattice of (2 NX + 1) x (2 NY + 1) nodes is numbered row by row.
#pragma once

#include <vector>

#include "engine/core/types.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_layout.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

struct GradedRectangle {
  Vec2 origin = Vec2::Zero();
  Vec2 size = Vec2::Ones();
  int nx = 1, ny = 1;          // coarse cells
  Vec2 grading = Vec2::Ones();  // ratio of successive coarse cell sizes along x and y
  int refinements = 0;          // J
};

// Cell edges of one axis: n coarse cells of total length `length` from `origin` with ratio g, each split
// into 2^J equal parts.
std::vector<double> graded_lines(double origin, double length, int n, double g, int refinements);

// Node coordinates along one axis of a quad9 lattice: the cell edges and the mid-points between them (2 n + 1).
std::vector<double> quad9_lattice(const std::vector<double>& lines);

// Throws InputError for an empty rectangle.
void build_quad9_grid(const GradedRectangle& spec, Formulation formulation, Nodes<2>& nodes, Cells& cells, GridLayout& layout);

}  // namespace loom
