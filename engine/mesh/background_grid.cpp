#include "engine/mesh/background_grid.hpp"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

#include "engine/core/errors.hpp"
#include "engine/mesh/cell_buckets.hpp"
#include "engine/mesh/colouring.hpp"

namespace loom {

void find_cell_neighbours(Cells& cells, Index n_nodes) {
  const int sides = cells.sides();
  cells.neighbour.use();
  cells.neighbour.resize_strided(cells.size(), sides, kNoIndex);
  std::unordered_map<std::uint64_t, std::pair<Index, int>> open;  // side key -> (cell, side)
  open.reserve(std::size_t(cells.size()) * 2);
  auto key = [n_nodes](Index a, Index b) { return std::uint64_t(std::min(a, b)) * std::uint64_t(n_nodes) + std::uint64_t(std::max(a, b)); };
  for (Index c = 0; c < cells.size(); ++c)
    for (int a = 0; a < sides; ++a) {
      const auto [i, j] = cells.side_corners(c, a);
      const std::uint64_t k = key(i, j);
      auto it = open.find(k);
      if (it == open.end()) {
        open.emplace(k, std::make_pair(c, a));
        continue;
      }
      cells.neighbour[sides * c + a] = it->second.first;
      cells.neighbour[sides * it->second.first + it->second.second] = c;
      open.erase(it);
    }
}

void build_quad_grid(const RectangleSpec& r, Formulation formulation, Nodes<2>& nodes, Cells& cells, GridLayout& layout) {
  LOOM_CHECK(r.nx > 0 && r.ny > 0 && r.size.x() > 0.0 && r.size.y() > 0.0, InputError,
             "a quad4 grid needs positive divisions and size (got " << r.nx << " x " << r.ny << ")");
  const Vec2 h(r.size.x() / r.nx, r.size.y() / r.ny);
  nodes.resize(Index(r.nx + 1) * Index(r.ny + 1));
  for (int j = 0; j <= r.ny; ++j)
    for (int i = 0; i <= r.nx; ++i) nodes.X[Index(j) * (r.nx + 1) + i] = r.origin + Vec2(i * h.x(), j * h.y());
  cells = Cells(CellType::quad4, formulation);
  auto& conn = cells.nodes.values();
  conn.reserve(std::size_t(r.nx) * std::size_t(r.ny) * 4);
  for (int j = 0; j < r.ny; ++j)  // cell k = j nx + i, as the structured locate computes it
    for (int i = 0; i < r.nx; ++i) {
      const Index n0 = Index(j) * (r.nx + 1) + i;
      for (Index n : {n0, n0 + 1, n0 + r.nx + 2, n0 + r.nx + 1}) conn.push_back(n);
    }
  cells.body.assign(Index(r.nx) * r.ny, 0);
  colour_cells(cells, nodes.size());
  find_cell_neighbours(cells, nodes.size());
  cells.measure.use();
  cells.measure.resize(cells.size(), h.x() * h.y());

  layout = GridLayout{};
  layout.lo = r.origin, layout.hi = r.origin + r.size;
  layout.tolerance = 1e-9 * layout.width();
  layout.structured = true;
  layout.origin = r.origin;
  layout.nx = r.nx, layout.ny = r.ny;
  layout.spacing = h;
}

void build_background_grid(const MeshData& mesh, const RectangleSpec* rectangle, Formulation formulation, Nodes<2>& nodes,
                           Cells& cells, GridLayout& layout) {
  // 1. Nodes and cells.
  nodes.resize(Index(mesh.X.size()));
  for (Index i = 0; i < nodes.size(); ++i) nodes.X[i] = mesh.X[std::size_t(i)];
  cells = Cells(CellType::tri3, formulation);
  cells.nodes.values() = mesh.triangles;
  cells.body.assign(mesh.n_triangles(), 0);
  colour_cells(cells, nodes.size());
  find_cell_neighbours(cells, nodes.size());

  // 2. Geometry: area and constant gradients of the linear shape functions.
  cells.measure.use();
  cells.gradient.use();
  cells.measure.resize(cells.size(), 0.0);
  cells.gradient.resize(cells.size(), Mat32::Zero());
  for (Index c = 0; c < cells.size(); ++c) {
    const Vec2 &x0 = nodes.X[cells.node(c, 0)], &x1 = nodes.X[cells.node(c, 1)], &x2 = nodes.X[cells.node(c, 2)];
    const double two_area = (x1 - x0).x() * (x2 - x0).y() - (x2 - x0).x() * (x1 - x0).y();
    LOOM_CHECK(two_area > 0.0, InputError, "grid cell " << c << " is degenerate or clockwise (area " << 0.5 * two_area << ")");
    Mat32 g;
    g << x1.y() - x2.y(), x2.x() - x1.x(), x2.y() - x0.y(), x0.x() - x2.x(), x0.y() - x1.y(), x1.x() - x0.x();
    cells.gradient[c] = g / two_area;
    cells.measure[c] = 0.5 * two_area;
  }

  // 3. Layout.
  layout = GridLayout{};
  layout.lo = layout.hi = nodes.X[0];
  for (Index i = 0; i < nodes.size(); ++i) layout.lo = layout.lo.cwiseMin(nodes.X[i]), layout.hi = layout.hi.cwiseMax(nodes.X[i]);
  layout.tolerance = 1e-9 * layout.width();
  if (rectangle && rectangle->pattern != GridPattern::shifted) {
    layout.structured = true;
    layout.origin = rectangle->origin;
    layout.nx = rectangle->nx, layout.ny = rectangle->ny;
    layout.spacing = Vec2(rectangle->size.x() / rectangle->nx, rectangle->size.y() / rectangle->ny);
#ifndef NDEBUG
    // The generator numbers the two cells of square k = j nx + i as 2k and 2k + 1.
    for (Index c = 0; c < cells.size(); ++c) {
      const Vec2 centre = (nodes.X[cells.node(c, 0)] + nodes.X[cells.node(c, 1)] + nodes.X[cells.node(c, 2)]) / 3.0;
      const Index k = c / 2;
      const Vec2 square((k % layout.nx + 0.5) * layout.spacing.x(), (k / layout.nx + 0.5) * layout.spacing.y());
      LOOM_ASSERT(((centre - layout.origin - square).cwiseQuotient(layout.spacing)).cwiseAbs().maxCoeff() < 0.5,
                  "cell " << c << " is not in square " << k);
    }
#endif
  } else {
    build_buckets(nodes, cells, layout);
  }
}

}  // namespace loom
