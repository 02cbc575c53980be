#include "systems/locate/locate_points.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "engine/core/errors.hpp"
#include "engine/core/parallel.hpp"
#include "engine/mesh/grid_shape.hpp"
#include "engine/mesh/quad9_shape.hpp"

namespace loom {
namespace {

Vec4 barycentric(const Cells& grid, const Nodes<2>& nodes, Index c, const Vec2& x) { return grid_shape_at(grid, nodes, c, x); }

// Accepted as inside when no barycentric coordinate is below -tol (tol: the layout's distance tolerance
// relative to the cell size, so that points on shared or outer edges are not lost to round-off).
double inside_tolerance(const GridLayout& layout, const Cells& grid, Index c) {
  return layout.tolerance / std::sqrt(grid.measure[c]);
}

Index find_structured(const GridLayout& layout, const Cells& grid, const Nodes<2>& nodes, const Vec2& x, Vec4& N) {
  const Vec2 s = (x - layout.origin).cwiseQuotient(layout.spacing);
  const double tol = layout.tolerance / layout.spacing.minCoeff();
  if (!(s.x() >= -tol && s.y() >= -tol && s.x() <= layout.nx + tol && s.y() <= layout.ny + tol)) return kNoIndex;
  const int i = std::clamp(int(std::floor(s.x())), 0, layout.nx - 1);
  const int j = std::clamp(int(std::floor(s.y())), 0, layout.ny - 1);
  const Index k = Index(j) * layout.nx + i;
  if (grid.stride == 4) {  // one quad4 cell per square
    N = barycentric(grid, nodes, k, x);
    return k;
  }
  // The square's two triangles: the one where x is "most inside".
  const Vec4 N0 = barycentric(grid, nodes, 2 * k, x), N1 = barycentric(grid, nodes, 2 * k + 1, x);
  const bool first = N0.head<3>().minCoeff() >= N1.head<3>().minCoeff();
  N = first ? N0 : N1;
  return first ? 2 * k : 2 * k + 1;
}

Index find_in_buckets(const GridLayout& layout, const Cells& grid, const Nodes<2>& nodes, const Vec2& x, Vec4& N) {
  const Vec2 s = (x - layout.lo).cwiseQuotient(layout.bucket_size);
  const double tol = layout.tolerance / layout.bucket_size.minCoeff();
  if (!(s.x() >= -tol && s.y() >= -tol && s.x() <= layout.bx + tol && s.y() <= layout.by + tol)) return kNoIndex;
  const int i = std::clamp(int(std::floor(s.x())), 0, layout.bx - 1);
  const int j = std::clamp(int(std::floor(s.y())), 0, layout.by - 1);
  const std::size_t b = std::size_t(j) * std::size_t(layout.bx) + std::size_t(i);
  Index best = kNoIndex;
  double best_min = -1e300;
  for (Index k = layout.bucket_offsets[b]; k < layout.bucket_offsets[b + 1]; ++k) {
    const Index c = layout.bucket_cells[std::size_t(k)];
    const Vec4 Nc = barycentric(grid, nodes, c, x);
    const double inside = grid_shape_inside(grid.stride, Nc);
    if (inside > best_min) best_min = inside, best = c, N = Nc;
  }
  if (best != kNoIndex && best_min >= -inside_tolerance(layout, grid, best)) return best;
  return kNoIndex;
}

// Visibility walk (triangles): step across the side opposite the most negative barycentric coordinate.
Index walk(const GridLayout& layout, const Cells& grid, const Nodes<2>& nodes, const Vec2& x, Index c, Vec4& N) {
  for (int steps = 0; steps < 64; ++steps) {
    N = barycentric(grid, nodes, c, x);
    Index a;
    const double m = N.head<3>().minCoeff(&a);
    if (m >= -inside_tolerance(layout, grid, c)) return c;
    const Index next = grid.neighbour[3 * c + a];
    if (next == kNoIndex) return kNoIndex;  // left through the boundary (or a concave part): buckets decide
    c = next;
  }
  return kNoIndex;
}

// Graded quad9 rectangle: the cell by a binary search along each axis, then xi by the inverse map.
Index find_quad9(const GridLayout& layout, const Cells& grid, const Nodes<2>& nodes, const Vec2& x, Vec2& xi) {
  const double tol = layout.tolerance;
  if (!layout.moves &&
      !(x.x() >= layout.lo.x() - tol && x.y() >= layout.lo.y() - tol && x.x() <= layout.hi.x() + tol && x.y() <= layout.hi.y() + tol))
    return kNoIndex;
  auto interval = [](const std::vector<double>& lines, double s) {
    const auto it = std::upper_bound(lines.begin() + 1, lines.end() - 1, s);
    return Index(it - lines.begin()) - 1;
  };
  Index i = interval(layout.x_lines, x.x()), j = interval(layout.y_lines, x.y());
  // The lines are the undeformed grid's. A grid that moves with the reset field (method mpm_fem) is off them by a
  // fraction of a cell near the FEM bodies (or by many cells, when the bodies translate): step to the neighbour the
  // reference coordinates point to.
  for (int hop = 0;; ++hop) {
    const Index c = j * layout.nx + i;
    Quad9Coordinates X;
    for (int a = 0; a < 9; ++a) X.row(a) = nodes.X[grid.node(c, a)].transpose();
    if (!quad9_inverse_map(X, x, xi)) return kNoIndex;
    const int di = xi.x() > 1.0 + 1e-9 ? 1 : xi.x() < -1.0 - 1e-9 ? -1 : 0, dj = xi.y() > 1.0 + 1e-9 ? 1 : xi.y() < -1.0 - 1e-9 ? -1 : 0;
    const Index ni = std::clamp<Index>(i + di, 0, layout.nx - 1), nj = std::clamp<Index>(j + dj, 0, layout.ny - 1);
    // At the grid's edge: a moving grid accepts a point within round-off of it (1e-6 of the cell), as a fixed one does.
    if ((ni == i && nj == j) || hop == layout.nx + layout.ny) return !layout.moves || xi.cwiseAbs().maxCoeff() <= 1.0 + 1e-6 ? c : kNoIndex;
    i = ni, j = nj;
  }
}

}  // namespace

Index host_active_cell(const Cells& grid, const Nodes<2>& nodes, const GridActivity& act, Index c, const Vec2& x, Vec4& N) {
  if (act.cell_active[std::size_t(c)]) {
    N = barycentric(grid, nodes, c, x);
    return c;
  }
  // Breadth-first over side neighbours, four rings: covers every cell sharing a corner with c.
  Index visited[128];
  int n_visited = 0, begin = 0;
  visited[n_visited++] = c;
  Index best = kNoIndex;
  double best_min = -1e300;
  for (int ring = 0; ring < 4 && best == kNoIndex; ++ring) {
    const int end = n_visited;
    for (int k = begin; k < end; ++k)
      for (int a = 0; a < grid.sides(); ++a) {
        const Index n = grid.neighbour[grid.sides() * visited[k] + a];
        if (n == kNoIndex || std::find(visited, visited + n_visited, n) != visited + n_visited || n_visited == 128) continue;
        visited[n_visited++] = n;
        if (!act.cell_active[std::size_t(n)]) continue;
        const Vec4 Nn = barycentric(grid, nodes, n, x);
        const double inside = grid_shape_inside(grid.stride, Nn);
        if (inside > best_min) best_min = inside, best = n, N = Nn;
      }
    begin = end;
  }
  return best;
}

Index find_cell(const GridLayout& layout, const Cells& grid, const Nodes<2>& grid_nodes, const Vec2& x, Index hint, Vec4& N) {
  if (layout.structured) return find_structured(layout, grid, grid_nodes, x, N);
  if (hint != kNoIndex) {
    const Index c = walk(layout, grid, grid_nodes, x, hint, N);
    if (c != kNoIndex) return c;
  }
  return find_in_buckets(layout, grid, grid_nodes, x, N);
}

void locate_points(const StepContext& ctx, const GridLayout& layout, const Cells& grid, const Nodes<2>& grid_nodes,
                   const Points<2>& points, PointLocations& loc) {
  const Index n = points.X.size();
  if (loc.size() != n) loc.resize(n);
  // 1. Cell and shape functions of every point (the previous cell is the walk's start).
  std::atomic<Index> outside{0};
  for_each_index(n, [&](Index p) {
    Vec4 N;
    const Index c = grid.type == CellType::quad9 ? find_quad9(layout, grid, grid_nodes, points.position(p), loc.xi[p])
                                                 : find_cell(layout, grid, grid_nodes, points.position(p), loc.cell[p], N);
    loc.cell[p] = c;
    if (c == kNoIndex) return void(outside.fetch_add(1, std::memory_order_relaxed));
    if (grid.type != CellType::quad9) loc.N[p] = N;
  });
  if (outside.load() > 0) {
    Index first = 0;
    while (loc.cell[first] != kNoIndex) ++first;
    const Vec2 x = points.position(first);
    LOOM_CHECK(false, RunError,
               outside.load() << " " << loc.entity << (outside.load() == 1 ? "" : "s") << " left the background grid at step " << ctx.step
                              << ", the first: " << loc.entity << " " << first << " (reference position (" << points.X[first].x() << ", "
                              << points.X[first].y() << ")) is at (" << x.x() << ", " << x.y() << "), outside the grid's ["
                              << layout.lo.x() << ", " << layout.hi.x() << "] x [" << layout.lo.y() << ", " << layout.hi.y()
                              << "]; enlarge [grid]");
  }
  // 2. Group by cell: counting sort, stable in the point index (deterministic).
  loc.cell_offsets.assign(std::size_t(grid.size()) + 1, 0);
  for (Index p = 0; p < n; ++p) ++loc.cell_offsets[std::size_t(loc.cell[p]) + 1];
  for (std::size_t c = 0; c < std::size_t(grid.size()); ++c) loc.cell_offsets[c + 1] += loc.cell_offsets[c];
  loc.by_cell.resize(std::size_t(n));
  std::vector<Index> fill(loc.cell_offsets.begin(), loc.cell_offsets.end() - 1);
  for (Index p = 0; p < n; ++p) loc.by_cell[std::size_t(fill[std::size_t(loc.cell[p])]++)] = p;
}

}  // namespace loom
