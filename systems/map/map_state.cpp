#include "systems/map/map_state.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <algorithm>
#include <atomic>

#include "engine/core/errors.hpp"
#include "engine/core/parallel.hpp"
#include "systems/map/deformation_interpolation.hpp"

namespace loom {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<Index, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;

Kernel::Point_2 point(const Vec2& x) { return Kernel::Point_2(x.x(), x.y()); }

// Queries in chunks of this many consecutive (Hilbert-sorted) points, each walking from the previous one.
constexpr Index kQueryChunk = 64;

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
  std::vector<Index> pending;
  for (Index k = 0; k < n_new; ++k) {
    if (copy_from[std::size_t(k)] >= 0) {
      new_F[std::size_t(k)] = old_F[std::size_t(copy_from[std::size_t(k)])];
      ++stats.kept;
    } else {
      pending.push_back(k);
    }
  }
  if (pending.empty()) return;
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

  // CGAL's locate and nearest_vertex walk through the triangulation from a start face: from the default
  // one a query costs O(sqrt n), O(n^1.5) for all. So the queries are sorted along a Hilbert curve and
  // each walks from the face of the previous one, in fixed chunks (a chunk starts from the default face):
  // the result of a query does not depend on the thread count.
  std::vector<Kernel::Point_2> query(pending.size());
  for (std::size_t j = 0; j < pending.size(); ++j) query[j] = point(new_positions[std::size_t(pending[j])]);
  std::vector<std::size_t> order(pending.size());
  for (std::size_t j = 0; j < order.size(); ++j) order[j] = j;
  using SortTraits = CGAL::Spatial_sort_traits_adapter_2<Kernel, CGAL::Pointer_property_map<Kernel::Point_2>::type>;
  CGAL::spatial_sort(order.begin(), order.end(), SortTraits(CGAL::make_property_map(query)));

  std::atomic<Index> copied{0}, interpolated{0}, fallback{0};
  const Index n_chunks = (Index(order.size()) + kQueryChunk - 1) / kQueryChunk;
  // Const queries on a built triangulation are safe from several threads.
  for_each_index(n_chunks, [&](Index chunk) {
    Delaunay::Face_handle hint;
    const std::size_t end = std::min(order.size(), std::size_t(chunk + 1) * std::size_t(kQueryChunk));
    for (std::size_t j = std::size_t(chunk) * std::size_t(kQueryChunk); j < end; ++j) {
      const Index k = pending[order[j]];
      const Vec2& x = new_positions[std::size_t(k)];
      const auto& p = query[order[j]];
      auto copy_nearest = [&](std::atomic<Index>& counter) {
        const auto v = dt.nearest_vertex(p, hint);
        hint = v->face();
        new_F[std::size_t(k)] = old_F[std::size_t(v->info())];
        counter.fetch_add(1, std::memory_order_relaxed);
      };
      if (settings.scheme == MapScheme::cpm) {
        copy_nearest(copied);
        continue;
      }
      const auto face = dt.locate(p, hint);
      if (face == nullptr || dt.is_infinite(face)) {
        copy_nearest(fallback);
        continue;
      }
      hint = face;
      const Index v[3] = {face->vertex(0)->info(), face->vertex(1)->info(), face->vertex(2)->info()};
      const Vec2 &a = old_positions[std::size_t(v[0])], &b = old_positions[std::size_t(v[1])], &c = old_positions[std::size_t(v[2])];
      bool coincides = false;
      for (int m = 0; m < 3 && !coincides; ++m)
        if ((old_positions[std::size_t(v[m])] - x).norm() <= tol) {
          new_F[std::size_t(k)] = old_F[std::size_t(v[m])];
          copied.fetch_add(1, std::memory_order_relaxed);
          coincides = true;
        }
      if (coincides) continue;
      if (radius_ratio(a, b, c) < settings.min_radius_ratio) {
        copy_nearest(fallback);
        continue;
      }
      // eq 20: natural coordinates of x in the background triangle (linear shape functions, eq 19).
      const double twice_area = (b - a).x() * (c - a).y() - (c - a).x() * (b - a).y();
      const double wb = ((x - a).x() * (c - a).y() - (c - a).x() * (x - a).y()) / twice_area;
      const double wc = ((b - a).x() * (x - a).y() - (x - a).x() * (b - a).y()) / twice_area;
      const double w[3] = {1.0 - wb - wc, wb, wc};
      const Mat3* const F[3] = {&old_F[std::size_t(v[0])], &old_F[std::size_t(v[1])], &old_F[std::size_t(v[2])]};
      new_F[std::size_t(k)] = interpolate_deformation<3>(F, w, settings.iso);
      interpolated.fetch_add(1, std::memory_order_relaxed);
    }
  });
  stats.copied = copied.load(), stats.interpolated = interpolated.load(), stats.fallback = fallback.load();
}

}  // namespace loom
