#include "systems/remesh/point_in_tets.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>

namespace loom {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;

Point point(const Vec3& x) { return Point(x.x(), x.y(), x.z()); }

}  // namespace

PointInTets::PointInTets(const std::vector<Vec3>& x, const std::vector<Index>& tets) : x_(x), tets_(tets) {
  const std::size_t n = tets.size() / 4;
  if (n == 0) return;
  Vec3 hi = x[std::size_t(tets[0])];
  lo_ = hi;
  for (Index v : tets) lo_ = lo_.cwiseMin(x[std::size_t(v)]), hi = hi.cwiseMax(x[std::size_t(v)]);
  const Vec3 extent = (hi - lo_).cwiseMax(1e-300);
  const double cell = std::cbrt(extent.x() * extent.y() * extent.z() / double(n)) + 1e-300;
  for (int d = 0; d < 3; ++d) n_[d] = std::clamp(long(extent[d] / cell) + 1, 1L, long(n) + 1);
  scale_ = 1.0 / cell;
  auto bucket_range = [&](std::size_t t, long lo[3], long hi_[3]) {
    Vec3 a = x[std::size_t(tets[4 * t])], b = a;
    for (int k = 1; k < 4; ++k) a = a.cwiseMin(x[std::size_t(tets[4 * t + std::size_t(k)])]), b = b.cwiseMax(x[std::size_t(tets[4 * t + std::size_t(k)])]);
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::clamp(long((a[d] - lo_[d]) * scale_), 0L, n_[d] - 1);
      hi_[d] = std::clamp(long((b[d] - lo_[d]) * scale_), 0L, n_[d] - 1);
    }
  };
  auto bucket = [&](long i, long j, long k) { return std::size_t((k * n_[1] + j) * n_[0] + i); };
  first_.assign(std::size_t(n_[0] * n_[1] * n_[2]) + 1, 0);
  long lo[3], up[3];
  for (std::size_t t = 0; t < n; ++t) {
    bucket_range(t, lo, up);
    for (long k = lo[2]; k <= up[2]; ++k)
      for (long j = lo[1]; j <= up[1]; ++j)
        for (long i = lo[0]; i <= up[0]; ++i) ++first_[bucket(i, j, k) + 1];
  }
  for (std::size_t c = 0; c + 1 < first_.size(); ++c) first_[c + 1] += first_[c];
  std::vector<Index> fill(first_.begin(), first_.end() - 1);
  in_cell_.resize(std::size_t(first_.back()));
  for (std::size_t t = 0; t < n; ++t) {
    bucket_range(t, lo, up);
    for (long k = lo[2]; k <= up[2]; ++k)
      for (long j = lo[1]; j <= up[1]; ++j)
        for (long i = lo[0]; i <= up[0]; ++i) in_cell_[std::size_t(fill[bucket(i, j, k)]++)] = Index(t);
  }
}

Index PointInTets::find(const Vec3& p) const {
  if (first_.empty()) return kNoIndex;
  long c[3];
  for (int d = 0; d < 3; ++d) {
    c[d] = long(std::floor((p[d] - lo_[d]) * scale_));
    // A point on the far side of the bounding box lies in the last bucket.
    if (c[d] == n_[d] && p[d] <= lo_[d] + double(n_[d]) / scale_) c[d] = n_[d] - 1;
    if (c[d] < 0 || c[d] >= n_[d]) return kNoIndex;
  }
  const std::size_t b = std::size_t((c[2] * n_[1] + c[1]) * n_[0] + c[0]);
  const Point q = point(p);
  for (Index s = first_[b]; s < first_[b + 1]; ++s) {
    const std::size_t t = std::size_t(in_cell_[std::size_t(s)]);
    Point v[4];
    for (int k = 0; k < 4; ++k) v[k] = point(x_[std::size_t(tets_[4 * t + std::size_t(k)])]);
    const CGAL::Orientation own = CGAL::orientation(v[0], v[1], v[2], v[3]);
    if (own == CGAL::COPLANAR) continue;
    // p is in or on the tetrahedron when replacing any corner by p never reverses its orientation.
    bool in = true;
    for (int k = 0; k < 4 && in; ++k) {
      Point w[4] = {v[0], v[1], v[2], v[3]};
      w[k] = q;
      const CGAL::Orientation o = CGAL::orientation(w[0], w[1], w[2], w[3]);
      in = o == own || o == CGAL::COPLANAR;
    }
    if (in) return Index(t);
  }
  return kNoIndex;
}

}  // namespace loom
