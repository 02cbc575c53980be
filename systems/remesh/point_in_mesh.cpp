#include "systems/remesh/point_in_mesh.hpp"

#include <algorithm>
#include <cmath>

namespace loom {
namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

PointInMesh::PointInMesh(const std::vector<Vec2>& x, const std::vector<Index>& triangles) : x_(x), triangles_(triangles) {
  const std::size_t n = triangles.size() / 3;
  if (n == 0) return;
  Vec2 hi = x[std::size_t(triangles[0])];
  lo_ = hi;
  for (Index v : triangles) lo_ = lo_.cwiseMin(x[std::size_t(v)]), hi = hi.cwiseMax(x[std::size_t(v)]);
  // About one triangle per bucket.
  const Vec2 extent = (hi - lo_).cwiseMax(1e-300);
  const double cell = std::sqrt(extent.x() * extent.y() / double(n)) + 1e-300;
  nx_ = std::clamp(long(extent.x() / cell) + 1, 1L, long(n) + 1);
  ny_ = std::clamp(long(extent.y() / cell) + 1, 1L, long(n) + 1);
  scale_ = 1.0 / cell;
  auto bucket_range = [&](std::size_t t, long r[4]) {
    Vec2 a = x[std::size_t(triangles[3 * t])], b = a;
    for (int k = 1; k < 3; ++k) a = a.cwiseMin(x[std::size_t(triangles[3 * t + std::size_t(k)])]), b = b.cwiseMax(x[std::size_t(triangles[3 * t + std::size_t(k)])]);
    r[0] = std::clamp(long((a.x() - lo_.x()) * scale_), 0L, nx_ - 1), r[1] = std::clamp(long((b.x() - lo_.x()) * scale_), 0L, nx_ - 1);
    r[2] = std::clamp(long((a.y() - lo_.y()) * scale_), 0L, ny_ - 1), r[3] = std::clamp(long((b.y() - lo_.y()) * scale_), 0L, ny_ - 1);
  };
  first_.assign(std::size_t(nx_ * ny_) + 1, 0);
  long r[4];
  for (std::size_t t = 0; t < n; ++t) {
    bucket_range(t, r);
    for (long j = r[2]; j <= r[3]; ++j)
      for (long i = r[0]; i <= r[1]; ++i) ++first_[std::size_t(j * nx_ + i) + 1];
  }
  for (std::size_t c = 0; c + 1 < first_.size(); ++c) first_[c + 1] += first_[c];
  std::vector<Index> fill(first_.begin(), first_.end() - 1);
  in_cell_.resize(std::size_t(first_.back()));
  for (std::size_t t = 0; t < n; ++t) {
    bucket_range(t, r);
    for (long j = r[2]; j <= r[3]; ++j)
      for (long i = r[0]; i <= r[1]; ++i) in_cell_[std::size_t(fill[std::size_t(j * nx_ + i)]++)] = Index(t);
  }
}

bool PointInMesh::contains(const Vec2& p) const {
  if (first_.empty()) return false;
  const long i = long(std::floor((p.x() - lo_.x()) * scale_)), j = long(std::floor((p.y() - lo_.y()) * scale_));
  if (i < 0 || j < 0 || i >= nx_ || j >= ny_) return false;
  const std::size_t c = std::size_t(j * nx_ + i);
  for (Index s = first_[c]; s < first_[c + 1]; ++s) {
    const std::size_t t = std::size_t(in_cell_[std::size_t(s)]);
    const Vec2 &a = x_[std::size_t(triangles_[3 * t])], &b = x_[std::size_t(triangles_[3 * t + 1])], &d = x_[std::size_t(triangles_[3 * t + 2])];
    const double area = cross(b - a, d - a);
    if (area == 0.0) continue;
    // Barycentric coordinates, each >= -tol (either orientation).
    const double l1 = cross(d - b, p - b) / area, l2 = cross(a - d, p - d) / area, l3 = cross(b - a, p - a) / area;
    if (l1 >= -1e-12 && l2 >= -1e-12 && l3 >= -1e-12) return true;
  }
  return false;
}

}  // namespace loom
