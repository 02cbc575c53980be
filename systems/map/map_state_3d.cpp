// State transfer on tetrahedra (seed 000 §6: its transfers "directly applicable to 3d"): the 2D map_state with a
// Delaunay_triangulation_3 of the old quadrature points, four barycentric weights and the radius ratio of the
// background tetrahedron. Same contract as the 2D one (map_state.hpp).
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <atomic>

#include "engine/core/errors.hpp"
#include "engine/core/parallel.hpp"
#include "systems/map/deformation_interpolation.hpp"
#include "systems/map/map_state.hpp"

namespace loom {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<Index, Kernel>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase, CGAL::Delaunay_triangulation_cell_base_3<Kernel>, CGAL::Sequential_tag>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;

Kernel::Point_3 point(const Vec3& x) { return Kernel::Point_3(x.x(), x.y(), x.z()); }

constexpr Index kQueryChunk = 64;  // as in 2D: Hilbert-sorted queries, each walking from the previous one

}  // namespace

double radius_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double six_volume = std::abs(u.dot(v.cross(w)));
  if (!(six_volume > 0.0)) return 0.0;
  const double faces = (u.cross(v)).norm() + (v.cross(w)).norm() + (w.cross(u)).norm() + ((c - b).cross(d - b)).norm();  // 2 x area each
  const double r_in = six_volume / faces;  // 3 V / (sum of face areas)
  // Circumcentre relative to a: (|u|^2 v x w + |v|^2 w x u + |w|^2 u x v) / (2 u . (v x w)).
  const Vec3 centre = (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) / (2.0 * u.dot(v.cross(w)));
  return 3.0 * r_in / centre.norm();
}

void map_state(const std::vector<Vec3>& old_positions, const std::vector<Mat3>& old_F, const std::vector<Vec3>& new_positions,
               const std::vector<Index>& copy_from, const MapSettings& settings, std::vector<Mat3>& new_F, MapStats& stats) {
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

  std::vector<std::pair<Kernel::Point_3, Index>> points;
  Vec3 lo = old_positions[0], hi = old_positions[0];
  for (std::size_t i = 0; i < old_positions.size(); ++i) {
    points.emplace_back(point(old_positions[i]), Index(i));
    lo = lo.cwiseMin(old_positions[i]), hi = hi.cwiseMax(old_positions[i]);
  }
  const Delaunay dt(points.begin(), points.end());  // spatially sorted insertion
  const double tol = settings.coincidence * (hi - lo).norm();
  // The 2D limit (r_in / R below 0.005, 1 % of the equilateral triangle's 1/2) in the same measure: 1 % of the
  // regular tetrahedron's 3 r_in / R = 1.
  const double min_ratio = 2.0 * settings.min_radius_ratio;

  std::vector<Kernel::Point_3> query(pending.size());
  for (std::size_t j = 0; j < pending.size(); ++j) query[j] = point(new_positions[std::size_t(pending[j])]);
  std::vector<std::size_t> order(pending.size());
  for (std::size_t j = 0; j < order.size(); ++j) order[j] = j;
  using SortTraits = CGAL::Spatial_sort_traits_adapter_3<Kernel, CGAL::Pointer_property_map<Kernel::Point_3>::type>;
  CGAL::spatial_sort(order.begin(), order.end(), SortTraits(CGAL::make_property_map(query)));

  std::atomic<Index> copied{0}, interpolated{0}, fallback{0};
  const Index n_chunks = (Index(order.size()) + kQueryChunk - 1) / kQueryChunk;
  for_each_index(n_chunks, [&](Index chunk) {
    Delaunay::Cell_handle hint;
    const std::size_t end = std::min(order.size(), std::size_t(chunk + 1) * std::size_t(kQueryChunk));
    for (std::size_t j = std::size_t(chunk) * std::size_t(kQueryChunk); j < end; ++j) {
      const Index k = pending[order[j]];
      const Vec3& x = new_positions[std::size_t(k)];
      const auto& p = query[order[j]];
      auto copy_nearest = [&](std::atomic<Index>& counter) {
        const auto v = dt.nearest_vertex(p, hint);
        hint = v->cell();
        new_F[std::size_t(k)] = old_F[std::size_t(v->info())];
        counter.fetch_add(1, std::memory_order_relaxed);
      };
      if (settings.scheme == MapScheme::cpm) {
        copy_nearest(copied);
        continue;
      }
      const auto cell = dt.locate(p, hint);
      if (cell == nullptr || dt.is_infinite(cell)) {
        copy_nearest(fallback);
        continue;
      }
      hint = cell;
      const Index v[4] = {cell->vertex(0)->info(), cell->vertex(1)->info(), cell->vertex(2)->info(), cell->vertex(3)->info()};
      const Vec3 &a = old_positions[std::size_t(v[0])], &b = old_positions[std::size_t(v[1])], &c = old_positions[std::size_t(v[2])],
                 &d = old_positions[std::size_t(v[3])];
      bool coincides = false;
      for (int m = 0; m < 4 && !coincides; ++m)
        if ((old_positions[std::size_t(v[m])] - x).norm() <= tol) {
          new_F[std::size_t(k)] = old_F[std::size_t(v[m])];
          copied.fetch_add(1, std::memory_order_relaxed);
          coincides = true;
        }
      if (coincides) continue;
      if (radius_ratio(a, b, c, d) < min_ratio) {
        copy_nearest(fallback);
        continue;
      }
      // Barycentric coordinates: the linear shape functions of the background tetrahedron at x.
      const Vec3 u = b - a, s = c - a, t = d - a, q = x - a;
      const double six_volume = u.dot(s.cross(t));
      const double wb = q.dot(s.cross(t)) / six_volume, wc = u.dot(q.cross(t)) / six_volume, wd = u.dot(s.cross(q)) / six_volume;
      const double w[4] = {1.0 - wb - wc - wd, wb, wc, wd};
      const Mat3* const F[4] = {&old_F[std::size_t(v[0])], &old_F[std::size_t(v[1])], &old_F[std::size_t(v[2])], &old_F[std::size_t(v[3])]};
      new_F[std::size_t(k)] = interpolate_deformation<4>(F, w, settings.iso);
      interpolated.fetch_add(1, std::memory_order_relaxed);
    }
  });
  stats.copied = copied.load(), stats.interpolated = interpolated.load(), stats.fallback = fallback.load();
}

}  // namespace loom
