#include "systems/locate/locate_points.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <ostream>

#include "engine/core/errors.hpp"
#include "engine/core/parallel.hpp"
#include "engine/mesh/grid_shape.hpp"
#include "engine/mesh/quad9_shape.hpp"
#include "engine/mesh/tet_background_grid.hpp"

namespace loom {
namespace {

// Shape functions of cell c at x: tri3 barycentric or quad4 bilinear (2D), tet4 barycentric (3D).
template <int D>
Vec4 barycentric(const Cells& grid, const Nodes<D>& nodes, Index c, const Vec<D>& x) {
  if constexpr (D == 2) return grid_shape_at(grid, nodes, c, x);
  else return tet_shape_at(grid, nodes, c, x);
}

// How far inside the cell a point with shape values N is (negative outside): grid_shape_inside in 2D, the
// smallest barycentric coordinate of a tetrahedron.
template <int D>
double shape_inside(const Cells& grid, const Vec4& N) {
  if constexpr (D == 2) return grid_shape_inside(grid.stride, N);
  else return N.minCoeff();
}

// Accepted as inside when no barycentric coordinate is below -tol (tol: the layout's distance tolerance
// relative to the cell size h = measure^(1/D), so that points on shared or outer sides are not lost to round-off).
template <int D>
double inside_tolerance(const GridLayoutT<D>& layout, const Cells& grid, Index c) {
  if constexpr (D == 2) return layout.tolerance / std::sqrt(grid.measure[c]);
  else return layout.tolerance / std::cbrt(grid.measure[c]);
}

// The lattice box holding x, for a lattice of n[a] boxes of size `size` along each axis from `corner`: s = x
// in box units, the box (clamped, so that points within tolerance of the outer sides count) in `box`, and
// false when x is farther out than the layout's tolerance.
template <int D>
bool lattice_box(const GridLayoutT<D>& layout, const Vec<D>& corner, const Vec<D>& size, const int (&n)[3], const Vec<D>& x,
                 Vec<D>& s, int (&box)[3]) {
  s = (x - corner).cwiseQuotient(size);
  const double tol = layout.tolerance / size.minCoeff();
  for (int a = 0; a < D; ++a)
    if (!(s[a] >= -tol && s[a] <= n[a] + tol)) return false;
  box[2] = 0;
  for (int a = 0; a < D; ++a) box[a] = std::clamp(int(std::floor(s[a])), 0, n[a] - 1);
  return true;
}

Index find_structured(const GridLayoutT<2>& layout, const Cells& grid, const Nodes<2>& nodes, const Vec2& x, Vec4& N) {
  Vec2 s;
  int square[3];
  if (!lattice_box(layout, layout.origin, layout.spacing, {layout.nx, layout.ny, 1}, x, s, square)) return kNoIndex;
  const Index k = Index(square[1]) * layout.nx + square[0];
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

// Box of Kuhn cubes (generate_box): cube k = (kz ny + j) nx + i holds the tetrahedra 6k + p, p the index of
// the path 000 -> e_a -> e_a + e_b -> 111 in generate_box's kPaths {012, 021, 102, 120, 201, 210}, that is
// p = 2 a + (b > c). The path's tetrahedron holds the points whose coordinates in the cube order as
// xi_a >= xi_b >= xi_c.
Index find_structured(const GridLayoutT<3>& layout, const Cells& grid, const Nodes<3>& nodes, const Vec3& x, Vec4& N) {
  Vec3 s;
  int cube[3];
  if (!lattice_box(layout, layout.origin, layout.spacing, {layout.nx, layout.ny, layout.nz}, x, s, cube)) return kNoIndex;
  const Vec3 xi = s - Vec3(cube[0], cube[1], cube[2]);
  int a = 0, b = 1, c = 2;  // sorted so that xi[a] >= xi[b] >= xi[c]
  if (xi[b] > xi[a]) std::swap(a, b);
  if (xi[c] > xi[b]) std::swap(b, c);
  if (xi[b] > xi[a]) std::swap(a, b);
  const Index cell = 6 * ((Index(cube[2]) * layout.ny + cube[1]) * layout.nx + cube[0]) + 2 * a + (b > c ? 1 : 0);
  N = barycentric(grid, nodes, cell, x);
  // On a face shared with another tetrahedron (of this cube or the next), xi and the corners' coordinates
  // round differently: of the two cells, the one where x is "most inside".
  Index m;
  if (N.minCoeff(&m) >= 0.0) return cell;
  const Index across = grid.neighbour[4 * cell + m];
  if (across == kNoIndex) return cell;
  const Vec4 Na = barycentric(grid, nodes, across, x);
  if (Na.minCoeff() <= N.minCoeff()) return cell;
  N = Na;
  return across;
}

template <int D>
Index find_in_buckets(const GridLayoutT<D>& layout, const Cells& grid, const Nodes<D>& nodes, const Vec<D>& x, Vec4& N) {
  Vec<D> s;
  int bucket[3];
  if (!lattice_box(layout, layout.lo, layout.bucket_size, {layout.bx, layout.by, D == 3 ? layout.bz : 1}, x, s, bucket)) return kNoIndex;
  const std::size_t b =
      (std::size_t(bucket[2]) * std::size_t(layout.by) + std::size_t(bucket[1])) * std::size_t(layout.bx) + std::size_t(bucket[0]);
  Index best = kNoIndex;
  double best_min = -1e300;
  for (Index k = layout.bucket_offsets[b]; k < layout.bucket_offsets[b + 1]; ++k) {
    const Index c = layout.bucket_cells[std::size_t(k)];
    const Vec4 Nc = barycentric(grid, nodes, c, x);
    const double inside = shape_inside<D>(grid, Nc);
    if (inside > best_min) best_min = inside, best = c, N = Nc;
  }
  if (best != kNoIndex && best_min >= -inside_tolerance(layout, grid, best)) return best;
  return kNoIndex;
}

// Visibility walk (triangles, tetrahedra): step across the side (face) opposite the most negative barycentric
// coordinate.
template <int D>
Index walk(const GridLayoutT<D>& layout, const Cells& grid, const Nodes<D>& nodes, const Vec<D>& x, Index c, Vec4& N) {
  for (int steps = 0; steps < 64; ++steps) {
    N = barycentric(grid, nodes, c, x);
    Index a;
    const double m = N.template head<D + 1>().minCoeff(&a);
    if (m >= -inside_tolerance(layout, grid, c)) return c;
    const Index next = grid.neighbour[(D + 1) * c + a];
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

// The bounding box "[lo_x, hi_x] x [lo_y, hi_y][ x [lo_z, hi_z]]" in messages.
template <int D>
struct BoundingBox {
  const GridLayoutT<D>& layout;
};
template <int D>
std::ostream& operator<<(std::ostream& os, const BoundingBox<D>& b) {
  for (int a = 0; a < D; ++a) os << (a ? " x [" : "[") << b.layout.lo[a] << ", " << b.layout.hi[a] << "]";
  return os;
}

}  // namespace

template <int D>
Index host_active_cell(const Cells& grid, const Nodes<D>& nodes, const GridActivity& act, Index c, const std::type_identity_t<Vec<D>>& x,
                       Vec4& N) {
  if (act.cell_active[std::size_t(c)]) {
    N = barycentric(grid, nodes, c, x);
    return c;
  }
  // Breadth-first over side (face) neighbours: the rings that cover every cell sharing a corner with c on the
  // generated grids (2D: up to eight triangles around a corner, four rings; 3D: the 24 Kuhn tetrahedra around
  // a corner, six rings), within a bounded scratch list.
  constexpr int kRings = D == 2 ? 4 : 6, kMaxVisited = D == 2 ? 128 : 512;
  Index visited[kMaxVisited];
  int n_visited = 0, begin = 0;
  visited[n_visited++] = c;
  Index best = kNoIndex;
  double best_min = -1e300;
  for (int ring = 0; ring < kRings && best == kNoIndex; ++ring) {
    const int end = n_visited;
    for (int k = begin; k < end; ++k)
      for (int a = 0; a < grid.sides(); ++a) {
        const Index n = grid.neighbour[grid.sides() * visited[k] + a];
        if (n == kNoIndex || std::find(visited, visited + n_visited, n) != visited + n_visited || n_visited == kMaxVisited) continue;
        visited[n_visited++] = n;
        if (!act.cell_active[std::size_t(n)]) continue;
        const Vec4 Nn = barycentric(grid, nodes, n, x);
        const double inside = shape_inside<D>(grid, Nn);
        if (inside > best_min) best_min = inside, best = n, N = Nn;
      }
    begin = end;
  }
  return best;
}

template <int D>
Index find_cell(const GridLayoutT<D>& layout, const Cells& grid, const Nodes<D>& grid_nodes, const std::type_identity_t<Vec<D>>& x,
                Index hint, Vec4& N) {
  if (layout.structured) return find_structured(layout, grid, grid_nodes, x, N);
  if (hint != kNoIndex) {
    const Index c = walk(layout, grid, grid_nodes, x, hint, N);
    if (c != kNoIndex) return c;
  }
  return find_in_buckets(layout, grid, grid_nodes, x, N);
}

template <int D>
void locate_points(const StepContext& ctx, const GridLayoutT<D>& layout, const Cells& grid, const Nodes<D>& grid_nodes,
                   const Points<D>& points, PointLocations& loc) {
  const Index n = points.X.size();
  if (loc.size() != n) loc.resize(n);
  // 1. Cell and shape functions of every point (the previous cell is the walk's start).
  std::atomic<Index> outside{0};
  for_each_index(n, [&](Index p) {
    Vec4 N;
    Index c;
    if constexpr (D == 2)
      c = grid.type == CellType::quad9 ? find_quad9(layout, grid, grid_nodes, points.position(p), loc.xi[p])
                                       : find_cell(layout, grid, grid_nodes, points.position(p), loc.cell[p], N);
    else
      c = find_cell(layout, grid, grid_nodes, points.position(p), loc.cell[p], N);
    loc.cell[p] = c;
    if (c == kNoIndex) return void(outside.fetch_add(1, std::memory_order_relaxed));
    if (grid.type != CellType::quad9) loc.N[p] = N;
  });
  if (outside.load() > 0) {
    Index first = 0;
    while (loc.cell[first] != kNoIndex) ++first;
    const Vec<D> x = points.position(first);
    LOOM_CHECK(false, RunError,
               outside.load() << " " << loc.entity << (outside.load() == 1 ? "" : "s") << " left the background grid at step " << ctx.step
                              << ", the first: " << loc.entity << " " << first << " (reference position "
                              << Coordinates<D>{points.X[first]} << ") is at " << Coordinates<D>{x} << ", outside the grid's "
                              << BoundingBox<D>{layout} << "; enlarge [grid]");
  }
  // 2. Group by cell: counting sort, stable in the point index (deterministic).
  loc.cell_offsets.assign(std::size_t(grid.size()) + 1, 0);
  for (Index p = 0; p < n; ++p) ++loc.cell_offsets[std::size_t(loc.cell[p]) + 1];
  for (std::size_t c = 0; c < std::size_t(grid.size()); ++c) loc.cell_offsets[c + 1] += loc.cell_offsets[c];
  loc.by_cell.resize(std::size_t(n));
  std::vector<Index> fill(loc.cell_offsets.begin(), loc.cell_offsets.end() - 1);
  for (Index p = 0; p < n; ++p) loc.by_cell[std::size_t(fill[std::size_t(loc.cell[p])]++)] = p;
}

// Instantiations: 2D (tri3, quad4, quad9 grids) and 3D (tet4 grids).
#define LOOM_LOCATE_INSTANTIATE(D)                                                                                            \
  template void locate_points<D>(const StepContext&, const GridLayoutT<D>&, const Cells&, const Nodes<D>&, const Points<D>&,  \
                                 PointLocations&);                                                                            \
  template Index host_active_cell<D>(const Cells&, const Nodes<D>&, const GridActivity&, Index, const Vec<D>&, Vec4&);        \
  template Index find_cell<D>(const GridLayoutT<D>&, const Cells&, const Nodes<D>&, const Vec<D>&, Index, Vec4&);
LOOM_LOCATE_INSTANTIATE(2)
LOOM_LOCATE_INSTANTIATE(3)
#undef LOOM_LOCATE_INSTANTIATE

}  // namespace loom
