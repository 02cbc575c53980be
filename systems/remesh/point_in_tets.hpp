// Whether a point lies in a set of tetrahedra (their union), the 3D counterpart of point_in_mesh.hpp: the 3D remesh
// classifies a new tetrahedron by its centroid against the previous mesh at x_n (spec 3d-free-surface §3, R3.2).
// Buckets of a uniform grid over the tetrahedra's bounding boxes (about one tetrahedron per bucket) and CGAL's exact
// orientation predicate: a point on a face or an edge counts as in, whatever the rounding of its coordinates.
#pragma once

#include <vector>

#include "engine/core/types.hpp"

namespace loom {

class PointInTets {
 public:
  // `tets`: 4 point indices each, either orientation (degenerate ones never hold a point); `x` must outlive this.
  PointInTets(const std::vector<Vec3>& x, const std::vector<Index>& tets);
  // In or on some tetrahedron.
  bool contains(const Vec3& p) const { return find(p) != kNoIndex; }
  // The first tetrahedron (lowest index) that holds p, or kNoIndex.
  Index find(const Vec3& p) const;

 private:
  const std::vector<Vec3>& x_;
  const std::vector<Index>& tets_;
  Vec3 lo_ = Vec3::Zero();
  double scale_ = 1.0;
  long n_[3] = {1, 1, 1};
  std::vector<Index> first_, in_cell_;  // tetrahedra of each bucket (counting sort)
};

}  // namespace loom
