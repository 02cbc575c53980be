#include "engine/mesh/quad9_grid.hpp"

#include <cmath>

#include "engine/core/errors.hpp"
#include "engine/mesh/background_grid.hpp"
#include "engine/mesh/colouring.hpp"

namespace loom {

std::vector<double> graded_lines(double origin, double length, int n, double g, int refinements) {
  // Coarse sizes h_k = h_0 g^k with sum h_k = length.
  const double h0 = g == 1.0 ? length / n : length * (g - 1.0) / (std::pow(g, n) - 1.0);
  const int split = 1 << refinements;
  std::vector<double> lines{origin};
  double x = origin, h = h0;
  for (int k = 0; k < n; ++k, h *= g) {
    for (int s = 1; s < split; ++s) lines.push_back(x + h * s / split);
    x = k + 1 == n ? origin + length : x + h;  // the last edge exactly at the far side
    lines.push_back(x);
  }
  return lines;
}

std::vector<double> quad9_lattice(const std::vector<double>& lines) {
  std::vector<double> s;
  for (std::size_t k = 0; k + 1 < lines.size(); ++k) s.push_back(lines[k]), s.push_back(0.5 * (lines[k] + lines[k + 1]));
  s.push_back(lines.back());
  return s;
}

void build_quad9_grid(const GradedRectangle& r, Formulation formulation, Nodes<2>& nodes, Cells& cells, GridLayout& layout) {
  LOOM_CHECK(r.nx > 0 && r.ny > 0 && r.size.x() > 0.0 && r.size.y() > 0.0 && r.grading.minCoeff() > 0.0 && r.refinements >= 0, InputError,
             "a quad9 grid needs positive divisions, size and grading (got " << r.nx << " x " << r.ny << ")");
  layout = GridLayout{};
  layout.x_lines = graded_lines(r.origin.x(), r.size.x(), r.nx, r.grading.x(), r.refinements);
  layout.y_lines = graded_lines(r.origin.y(), r.size.y(), r.ny, r.grading.y(), r.refinements);
  const int NX = int(layout.x_lines.size()) - 1, NY = int(layout.y_lines.size()) - 1;
  const Index row = 2 * NX + 1;
  const std::vector<double> xs = quad9_lattice(layout.x_lines), ys = quad9_lattice(layout.y_lines);
  nodes.resize(row * Index(2 * NY + 1));
  for (int J = 0; J <= 2 * NY; ++J)
    for (int I = 0; I <= 2 * NX; ++I) nodes.X[Index(J) * row + I] = Vec2(xs[std::size_t(I)], ys[std::size_t(J)]);

  cells = Cells(CellType::quad9, formulation);
  auto& conn = cells.nodes.values();
  conn.reserve(std::size_t(NX) * std::size_t(NY) * 9);
  cells.measure.use();
  for (int j = 0; j < NY; ++j)
    for (int i = 0; i < NX; ++i) {
      const Index b = Index(2 * j) * row + 2 * i;  // lower-left corner
      for (Index n : {b, b + 2, b + 2 * row + 2, b + 2 * row, b + 1, b + row + 2, b + 2 * row + 1, b + row, b + row + 1}) conn.push_back(n);
      cells.measure.values().push_back((layout.x_lines[std::size_t(i) + 1] - layout.x_lines[std::size_t(i)]) *
                              (layout.y_lines[std::size_t(j) + 1] - layout.y_lines[std::size_t(j)]));
    }
  cells.body.assign(Index(NX) * NY, 0);
  colour_cells(cells, nodes.size());
  find_cell_neighbours(cells, nodes.size());

  layout.lo = r.origin, layout.hi = Vec2(layout.x_lines.back(), layout.y_lines.back());
  layout.tolerance = 1e-9 * layout.width();
  layout.nx = NX, layout.ny = NY;
  layout.origin = r.origin;
}

}  // namespace loom
