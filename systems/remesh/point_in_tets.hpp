// Whether a point lies in a set of tetrahedra (their union), the 3D counterpart of point_in_mesh.hpp: the 3D remesh
// classifies a new tetrahedron by its centroid against the previous mesh at x_n (spec 3d-free-surface §3, R3.2).
// Buckets of a uniform grid over the tetrahedra's bounding boxes (about one tetrahedron per bucket) and CGAL's exact
// orientation predicate: a point on a face or an edge counts as in, whatever the rounding of its coordinates.
#pragma once

#include <array>
#include <mutex>
#include <vector>

#include "engine/core/types.hpp"

namespace loom {

class PointInTets {
 public:
  // `tets`: 4 point indices each, either orientation (degenerate ones never hold a point); `x`, `tets` and
  // `neighbours` must outlive this. With `neighbours` (tet_face_neighbours of `tets`), contains_near walks from a
  // tetrahedron at a given point. The buckets are built (once, by whichever thread asks first) at the first query
  // that needs them; queries may run concurrently.
  PointInTets(const std::vector<Vec3>& x, const std::vector<Index>& tets, const std::vector<std::array<Index, 4>>* neighbours = nullptr);
  // In or on some tetrahedron.
  bool contains(const Vec3& p) const { return find(p) != kNoIndex; }
  // The same answer, found by walking from a tetrahedron at point `near` across faces towards p (a few steps when p
  // lies near `near`); where the walk meets the surface or a flat tetrahedron, or goes on too long, by the buckets.
  bool contains_near(const Vec3& p, Index near) const;
  // The first tetrahedron (lowest index) that holds p, or kNoIndex.
  Index find(const Vec3& p) const;

 private:
  void build_buckets() const;
  // The tetrahedron reached from `start` towards p holding it, kNoIndex when the walk cannot tell.
  Index walk(const Vec3& p, Index start) const;

  const std::vector<Vec3>& x_;
  const std::vector<Index>& tets_;
  const std::vector<std::array<Index, 4>>* neighbours_ = nullptr;
  std::vector<Index> tet_at_;  // per point: a tetrahedron with it as a corner (with neighbours only)
  mutable std::once_flag built_;
  mutable Vec3 lo_ = Vec3::Zero();
  mutable double scale_ = 1.0;
  mutable long n_[3] = {1, 1, 1};
  mutable std::vector<Index> first_, in_cell_;  // tetrahedra of each bucket (counting sort)
};

}  // namespace loom
