#include "systems/map/map_state.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <atomic>

#include "engine/core/errors.hpp"
#include "engine/core/parallel.hpp"

namespace loom {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<Index, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;

Kernel::Point_2 point(const Vec2& x) { return Kernel::Point_2(x.x(), x.y()); }

}  // namespace

double radius_ratio(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double ab = (b - a).norm(), bc = (c - b).norm(), ca = (a - c).norm();
  const double area = 0.5 * std::abs((b - a).x() * (c - a).y() - (c - a).x() * (b - a).y());
  if (!(area > 0.0)) return 0.0;
  const double r_in = 2.0 * area / (ab + bc + ca);
  const double r_circ = ab * bc * ca / (4.0 * area);
  return r_in / r_circ;
}

void map_state(const std::vector<Vec2>& old_positions, const std::vector<Mat3>& old_F,
               const std::vector<Vec2>& new_positions, const std::vector<Index>& copy_from, const MapSettings& settings,
               std::vector<Mat3>& new_F, MapStats& stats) {
  const Index n_new = Index(new_positions.size());
  new_F.resize(std::size_t(n_new));
  stats = MapStats{};
  std::vector<Index> todo;
  for (Index k = 0; k < n_new; ++k) {
    if (copy_from[std::size_t(k)] >= 0) {
      new_F[std::size_t(k)] = old_F[std::size_t(copy_from[std::size_t(k)])];
      ++stats.kept;
    } else {
      todo.push_back(k);
    }
  }
  if (todo.empty()) return;
  LOOM_CHECK(!old_positions.empty(), RunError, "map: no old quadrature points to transfer the state from");

  // Background triangulation of the old points (Fig 3).
  std::vector<std::pair<Kernel::Point_2, Index>> points;
  Vec2 lo = old_positions[0], hi = old_positions[0];
  for (std::size_t i = 0; i < old_positions.size(); ++i) {
    points.emplace_back(point(old_positions[i]), Index(i));
    lo = lo.cwiseMin(old_positions[i]), hi = hi.cwiseMax(old_positions[i]);
  }
  const Delaunay dt(points.begin(), points.end());
  const double tol = settings.coincidence * (hi - lo).norm();

  std::atomic<Index> copied{0}, interpolated{0}, fallback{0};
  // Const queries on a built triangulation are safe from several threads.
  for_each_index(Index(todo.size()), [&](Index j) {
    const Index k = todo[std::size_t(j)];
    const Vec2& x = new_positions[std::size_t(k)];
    const auto p = point(x);
    auto copy_nearest = [&](std::atomic<Index>& counter) {
      new_F[std::size_t(k)] = old_F[std::size_t(dt.nearest_vertex(p)->info())];
      counter.fetch_add(1, std::memory_order_relaxed);
    };
    if (settings.scheme == MapScheme::cpm) return copy_nearest(copied);
    const auto face = dt.locate(p);
    if (face == nullptr || dt.is_infinite(face)) return copy_nearest(fallback);
    const Index v[3] = {face->vertex(0)->info(), face->vertex(1)->info(), face->vertex(2)->info()};
    const Vec2 &a = old_positions[std::size_t(v[0])], &b = old_positions[std::size_t(v[1])], &c = old_positions[std::size_t(v[2])];
    for (int m = 0; m < 3; ++m)
      if ((old_positions[std::size_t(v[m])] - x).norm() <= tol) {
        new_F[std::size_t(k)] = old_F[std::size_t(v[m])];
        copied.fetch_add(1, std::memory_order_relaxed);
        return;
      }
    if (radius_ratio(a, b, c) < settings.min_radius_ratio) return copy_nearest(fallback);
    // eq 20: natural coordinates of x in the background triangle (linear shape functions, eq 19).
    const double twice_area = (b - a).x() * (c - a).y() - (c - a).x() * (b - a).y();
    const double wb = ((x - a).x() * (c - a).y() - (c - a).x() * (x - a).y()) / twice_area;
    const double wc = ((b - a).x() * (x - a).y() - (x - a).x() * (b - a).y()) / twice_area;
    const double w[3] = {1.0 - wb - wc, wb, wc};
    const Mat3* const F[3] = {&old_F[std::size_t(v[0])], &old_F[std::size_t(v[1])], &old_F[std::size_t(v[2])]};
    new_F[std::size_t(k)] = interpolate_deformation<3>(F, w, settings.iso);
    interpolated.fetch_add(1, std::memory_order_relaxed);
  });
  stats.copied = copied.load(), stats.interpolated = interpolated.load(), stats.fallback = fallback.load();
}

}  // namespace loom
