#include "engine/mesh/coupled_grid.hpp"

#include <algorithm>
#include <cmath>

#include "engine/core/errors.hpp"
#include "engine/mesh/background_grid.hpp"
#include "engine/mesh/colouring.hpp"

namespace loom {
namespace {

// Index of the lattice coordinate equal to v within tol, or -1.
int find_coordinate(const std::vector<double>& s, double v, double tol) {
  const auto it = std::lower_bound(s.begin(), s.end(), v - tol);
  return it != s.end() && std::abs(*it - v) <= tol ? int(it - s.begin()) : -1;
}

}  // namespace

CoupledMesh build_coupled_grid(const GradedRectangle& grid, const std::vector<FemBlock>& blocks, Formulation formulation, Nodes<2>& nodes,
                               Cells& cells, GridLayout& layout) {
  build_quad9_grid(grid, formulation, nodes, cells, layout);
  CoupledMesh out;
  out.grid_cells = cells.size();
  const Index grid_nodes = nodes.size();
  const std::vector<double> xs = quad9_lattice(layout.x_lines), ys = quad9_lattice(layout.y_lines);
  const Index row = Index(xs.size());
  const double tol = layout.tolerance;
  const Vec2 lo = layout.lo, hi = layout.hi;
  std::vector<std::pair<Vec2, Vec2>> boxes;  // blocks placed so far
  for (const FemBlock& blk : blocks) {
    Nodes<2> bn;
    Cells bc;
    GridLayout bl;
    build_quad9_grid(blk.rectangle, formulation, bn, bc, bl);
    const Vec2 blo = bl.lo, bhi = bl.hi;
    const bool overlaps = blo.x() < hi.x() - tol && bhi.x() > lo.x() + tol && blo.y() < hi.y() - tol && bhi.y() > lo.y() + tol;
    LOOM_CHECK(!overlaps, InputError,
               "FEM body \"" << blk.name << "\" ([" << blo.x() << ", " << bhi.x() << "] x [" << blo.y() << ", " << bhi.y()
                             << "]) overlaps the background grid ([" << lo.x() << ", " << hi.x() << "] x [" << lo.y() << ", " << hi.y()
                             << "]): an FEM body lies outside the grid and shares one of its sides");
    for (const auto& [olo, ohi] : boxes)
      LOOM_CHECK(blo.x() > ohi.x() + tol || bhi.x() < olo.x() - tol || blo.y() > ohi.y() + tol || bhi.y() < olo.y() - tol, InputError,
                 "FEM body \"" << blk.name << "\" touches another FEM body: FEM bodies connect through the grid only");
    boxes.emplace_back(blo, bhi);
    // Its nodes: the grid's where they lie on the grid's boundary, new ones elsewhere.
    std::vector<Index> global(std::size_t(bn.size()));
    int shared = 0;
    for (Index i = 0; i < bn.size(); ++i) {
      const Vec2& x = bn.X[i];
      const bool on_x_side = (std::abs(x.x() - lo.x()) <= tol || std::abs(x.x() - hi.x()) <= tol) && x.y() >= lo.y() - tol && x.y() <= hi.y() + tol;
      const bool on_y_side = (std::abs(x.y() - lo.y()) <= tol || std::abs(x.y() - hi.y()) <= tol) && x.x() >= lo.x() - tol && x.x() <= hi.x() + tol;
      if (!on_x_side && !on_y_side) {
        global[std::size_t(i)] = nodes.size();
        nodes.resize(nodes.size() + 1);
        nodes.X[nodes.size() - 1] = x;
        continue;
      }
      const int I = find_coordinate(xs, x.x(), tol), J = find_coordinate(ys, x.y(), tol);
      LOOM_CHECK(I >= 0 && J >= 0, InputError,
                 "FEM body \"" << blk.name << "\" does not conform to the background grid: its node (" << x.x() << ", " << x.y()
                               << ") lies on the grid's side but is not a grid node (the body's cells along the common side must be the "
                                  "grid's: the same divisions and grading there, refined the same number of times)");
      global[std::size_t(i)] = Index(J) * row + I;
      ++shared;
    }
    LOOM_CHECK(shared >= 3, InputError,
               "FEM body \"" << blk.name << "\" ([" << blo.x() << ", " << bhi.x() << "] x [" << blo.y() << ", " << bhi.y()
                             << "]) does not share a cell side with the background grid ([" << lo.x() << ", " << hi.x() << "] x [" << lo.y()
                             << ", " << hi.y() << "])");
    // A side on the grid's side must take three consecutive grid nodes: a block with half the grid's divisions has all
    // its nodes on grid nodes and would leave every other grid node hanging.
    for (Index c = 0; c < bc.size(); ++c)
      for (int sd = 0; sd < 4; ++sd) {
        const Index ends[3] = {global[std::size_t(bc.node(c, sd))], global[std::size_t(bc.node(c, 4 + sd))], global[std::size_t(bc.node(c, (sd + 1) % 4))]};
        if (ends[0] >= grid_nodes || ends[1] >= grid_nodes || ends[2] >= grid_nodes) continue;
        for (int k = 0; k < 2; ++k) {
          const Index a = ends[k], e = ends[k + 1];
          const Index di = std::abs(a % row - e % row), dj = std::abs(a / row - e / row);
          LOOM_CHECK(di + dj == 1, InputError,
                     "FEM body \"" << blk.name << "\" does not conform to the background grid: its cell side from (" << nodes.X[a].x() << ", "
                                   << nodes.X[a].y() << ") to (" << nodes.X[e].x() << ", " << nodes.X[e].y()
                                   << ") spans grid nodes it does not hold (the body's cells along the common side must be the grid's: the "
                                      "same divisions and grading there, refined the same number of times)");
        }
      }
    auto& conn = cells.nodes.values();
    for (Index c = 0; c < bc.size(); ++c) {
      for (int a = 0; a < 9; ++a) conn.push_back(global[std::size_t(bc.node(c, a))]);
      cells.measure.values().push_back(bc.measure[c]);
      cells.body.values().push_back(blk.body);
    }
  }
  colour_cells(cells, nodes.size());
  find_cell_neighbours(cells, nodes.size());
  out.fem_node.assign(std::size_t(nodes.size()), 0);
  out.interface_node.assign(std::size_t(nodes.size()), 0);
  for (Index c = out.grid_cells; c < cells.size(); ++c)
    for (int a = 0; a < 9; ++a) out.fem_node[std::size_t(cells.node(c, a))] = 1;
  for (Index i = 0; i < grid_nodes; ++i) out.interface_node[std::size_t(i)] = out.fem_node[std::size_t(i)];
  return out;
}

}  // namespace loom
