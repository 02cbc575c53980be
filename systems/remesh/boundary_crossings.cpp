#include "systems/remesh/boundary_crossings.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>

namespace loom {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

Kernel::Point_2 point(const Vec2& v) { return {v.x(), v.y()}; }

// A point inside both segments: each segment's ends strictly on opposite sides of the other's line.
bool properly_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const auto pa = point(a), pb = point(b), pc = point(c), pd = point(d);
  const auto o1 = CGAL::orientation(pa, pb, pc), o2 = CGAL::orientation(pa, pb, pd);
  if (o1 == CGAL::COLLINEAR || o2 == CGAL::COLLINEAR || o1 == o2) return false;
  const auto o3 = CGAL::orientation(pc, pd, pa), o4 = CGAL::orientation(pc, pd, pb);
  return o3 != CGAL::COLLINEAR && o4 != CGAL::COLLINEAR && o3 != o4;
}

}  // namespace

std::vector<char> crossing_edges(const std::vector<Vec2>& x, const std::vector<Edge>& edges) {
  std::vector<char> crossing(edges.size(), 0);
  if (edges.size() < 2) return crossing;
  Vec2 lo = x[std::size_t(edges[0][0])], hi = lo;
  double length = 0.0;
  for (const Edge& e : edges) {
    const Vec2 &a = x[std::size_t(e[0])], &b = x[std::size_t(e[1])];
    lo = lo.cwiseMin(a).cwiseMin(b), hi = hi.cwiseMax(a).cwiseMax(b);
    length += (b - a).norm();
  }
  // Cells of about the mean edge length, made coarser until there are at most ~4 cells per edge (a long
  // diagonal outline would otherwise ask for n^2 cells).
  const Vec2 extent = hi - lo;
  double cell = std::max(length / double(edges.size()), 1e-300);
  const double max_cells = 4.0 * double(edges.size()) + 16.0;
  while ((extent.x() / cell + 1.0) * (extent.y() / cell + 1.0) > max_cells) cell *= 2.0;
  const long nx = long(extent.x() / cell) + 1, ny = long(extent.y() / cell) + 1;
  const double sx = double(nx) / std::max(extent.x(), 1e-300), sy = double(ny) / std::max(extent.y(), 1e-300);
  auto cell_of = [&](double v, double origin, double scale, long n) { return std::clamp(long((v - origin) * scale), 0L, n - 1); };
  // Bucket every edge in each cell its bounding box touches (counting sort).
  std::vector<std::array<long, 4>> box(edges.size());
  std::vector<Index> first(std::size_t(nx * ny) + 1, 0);
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const Vec2 &a = x[std::size_t(edges[k][0])], &b = x[std::size_t(edges[k][1])];
    box[k] = {cell_of(std::min(a.x(), b.x()), lo.x(), sx, nx), cell_of(std::max(a.x(), b.x()), lo.x(), sx, nx),
              cell_of(std::min(a.y(), b.y()), lo.y(), sy, ny), cell_of(std::max(a.y(), b.y()), lo.y(), sy, ny)};
    for (long j = box[k][2]; j <= box[k][3]; ++j)
      for (long i = box[k][0]; i <= box[k][1]; ++i) ++first[std::size_t(j * nx + i) + 1];
  }
  for (std::size_t c = 0; c + 1 < first.size(); ++c) first[c + 1] += first[c];
  std::vector<Index> fill(first.begin(), first.end() - 1), in_cell(std::size_t(first.back()));
  for (std::size_t k = 0; k < edges.size(); ++k)
    for (long j = box[k][2]; j <= box[k][3]; ++j)
      for (long i = box[k][0]; i <= box[k][1]; ++i) in_cell[std::size_t(fill[std::size_t(j * nx + i)]++)] = Index(k);
  // Each pair is tested in every cell both touch; a repeat test gives the same answer.
  for (std::size_t c = 0; c + 1 < first.size(); ++c)
    for (Index s = first[c]; s < first[c + 1]; ++s)
      for (Index t = s + 1; t < first[c + 1]; ++t) {
        const Edge &e = edges[std::size_t(in_cell[std::size_t(s)])], &f = edges[std::size_t(in_cell[std::size_t(t)])];
        if (e[0] == f[0] || e[0] == f[1] || e[1] == f[0] || e[1] == f[1]) continue;
        if (properly_cross(x[std::size_t(e[0])], x[std::size_t(e[1])], x[std::size_t(f[0])], x[std::size_t(f[1])]))
          crossing[std::size_t(in_cell[std::size_t(s)])] = crossing[std::size_t(in_cell[std::size_t(t)])] = 1;
      }
  return crossing;
}

}  // namespace loom
