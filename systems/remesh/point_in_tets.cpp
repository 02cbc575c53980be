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

PointInTets::PointInTets(const std::vector<Vec3>& x, const std::vector<Index>& tets, const std::vector<std::array<Index, 4>>* neighbours)
    : x_(x), tets_(tets), neighbours_(neighbours) {
  if (!neighbours_) return;
  tet_at_.assign(x.size(), kNoIndex);
  for (std::size_t t = tets.size() / 4; t-- > 0;)
    for (std::size_t k = 0; k < 4; ++k) tet_at_[std::size_t(tets[4 * t + k])] = Index(t);
}

void PointInTets::build_buckets() const {
  const auto& x = x_;
  const auto& tets = tets_;
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
  std::call_once(built_, [this] { build_buckets(); });
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

bool PointInTets::contains_near(const Vec3& p, Index near) const {
  if (neighbours_ && near >= 0 && std::size_t(near) < tet_at_.size() && tet_at_[std::size_t(near)] != kNoIndex &&
      walk(p, tet_at_[std::size_t(near)]) != kNoIndex)
    return true;
  return contains(p);
}

// A visibility walk with exact orientations: leave through a face that has p strictly on its far side. In a
// non-Delaunay mesh it may cycle, hence the bound on the steps; any tetrahedron it stops in holds p, so the answer
// (in or on the union) is the buckets' answer, and an undecided walk defers to them.
Index PointInTets::walk(const Vec3& p, Index start) const {
  constexpr int kMaxSteps = 64;
  const Point q = point(p);
  Index t = start, from = kNoIndex;
  for (int step = 0; step < kMaxSteps; ++step) {
    Point v[4];
    for (int k = 0; k < 4; ++k) v[k] = point(x_[std::size_t(tets_[4 * std::size_t(t) + std::size_t(k)])]);
    const CGAL::Orientation own = CGAL::orientation(v[0], v[1], v[2], v[3]);
    if (own == CGAL::COPLANAR) return kNoIndex;
    Index next = kNoIndex;
    for (int k = 0; k < 4; ++k) {
      const Index across = (*neighbours_)[std::size_t(t)][std::size_t(k)];
      if (across == from && from != kNoIndex) continue;  // p is not behind the face just crossed
      Point w[4] = {v[0], v[1], v[2], v[3]};
      w[k] = q;
      if (CGAL::orientation(w[0], w[1], w[2], w[3]) == -own) {
        next = across;
        if (next < 0) return kNoIndex;  // beyond the surface here: the buckets decide
        break;
      }
    }
    if (next == kNoIndex) return t;
    from = t, t = next;
  }
  return kNoIndex;
}

}  // namespace loom
