// Whether a point lies in a set of triangles (their union; the triangles may overlap, as those of a mesh whose
// step folded one part over another do). The free-surface remesh classifies a new triangle by its centroid with
// it when the previous boundary cannot serve as a closed polygon (some of its edges cross).
#pragma once

#include <vector>

#include "engine/core/types.hpp"

namespace loom {

class PointInMesh {
 public:
  // `triangles`: 3 point indices each, either orientation; `x` must outlive the object.
  PointInMesh(const std::vector<Vec2>& x, const std::vector<Index>& triangles);
  // In (or on, to a relative 1e-12) some triangle.
  bool contains(const Vec2& p) const;

 private:
  const std::vector<Vec2>& x_;
  const std::vector<Index>& triangles_;
  Vec2 lo_ = Vec2::Zero();
  double scale_ = 1.0;
  long nx_ = 1, ny_ = 1;
  std::vector<Index> first_, in_cell_;  // triangles of each bucket (counting sort)
};

}  // namespace loom
