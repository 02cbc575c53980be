// The bucket index of an unstructured MPM background grid (engine/store/grid_layout.hpp), for triangles
// (D = 2) and tetrahedra (D = 3): a lattice of about one cell per bucket over the grid's bounding box,
// each bucket listing (ascending) the cells whose bounding box, widened by the layout's tolerance, meets it.
// A template in a header so that the 2D and 3D grid builders share one definition.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "engine/store/cells.hpp"
#include "engine/store/grid_layout.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

// Needs layout.lo, hi and tolerance; fills bx, by (bz), bucket_size, bucket_offsets and bucket_cells.
// The cells are simplices: their first D + 1 nodes are the corners.
template <int D>
void build_buckets(const Nodes<D>& nodes, const Cells& cells, GridLayoutT<D>& layout) {
  const Vec<D> extent = (layout.hi - layout.lo).cwiseMax(1e-300);
  double volume = extent[0];
  for (int a = 1; a < D; ++a) volume *= extent[a];
  const double per_cell = volume / std::max<Index>(cells.size(), 1);
  // The edge of a bucket holding one cell on average: the D-th root of the volume per cell.
  const double per_bucket = D == 2 ? std::sqrt(per_cell) : std::cbrt(per_cell);
  int* counts[3] = {&layout.bx, &layout.by, &layout.bz};
  int n[3] = {1, 1, 1};  // buckets along each axis (the third is 1 in 2D)
  for (int a = 0; a < D; ++a) {
    n[a] = *counts[a] = std::clamp(int(std::ceil(extent[a] / per_bucket)), 1, 4096);
    layout.bucket_size[a] = extent[a] / n[a];
  }
  // Bucket ranges [first, last] along each axis of cell c's widened bounding box (the third [0, 0] in 2D).
  auto range = [&](Index c, int (&first)[3], int (&last)[3]) {
    Vec<D> lo = nodes.X[cells.node(c, 0)], hi = lo;
    for (int a = 1; a < D + 1; ++a) lo = lo.cwiseMin(nodes.X[cells.node(c, a)]), hi = hi.cwiseMax(nodes.X[cells.node(c, a)]);
    lo.array() -= layout.tolerance, hi.array() += layout.tolerance;
    first[2] = last[2] = 0;
    for (int a = 0; a < D; ++a) {
      first[a] = std::clamp(int(std::floor((lo[a] - layout.lo[a]) / layout.bucket_size[a])), 0, n[a] - 1);
      last[a] = std::clamp(int(std::floor((hi[a] - layout.lo[a]) / layout.bucket_size[a])), 0, n[a] - 1);
    }
  };
  // Two passes over the cells (count, then fill): a compressed row per bucket, cells ascending.
  layout.bucket_offsets.assign(std::size_t(n[0]) * std::size_t(n[1]) * std::size_t(n[2]) + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<Index> fill(layout.bucket_offsets.begin(), layout.bucket_offsets.end() - 1);
    for (Index c = 0; c < cells.size(); ++c) {
      int first[3], last[3];
      range(c, first, last);
      for (int k = first[2]; k <= last[2]; ++k)
        for (int j = first[1]; j <= last[1]; ++j)
          for (int i = first[0]; i <= last[0]; ++i) {
            const std::size_t b = (std::size_t(k) * std::size_t(n[1]) + std::size_t(j)) * std::size_t(n[0]) + std::size_t(i);
            if (pass == 0) ++layout.bucket_offsets[b + 1];
            else layout.bucket_cells[std::size_t(fill[b]++)] = c;
          }
    }
    if (pass == 0) {
      for (std::size_t b = 0; b + 1 < layout.bucket_offsets.size(); ++b) layout.bucket_offsets[b + 1] += layout.bucket_offsets[b];
      layout.bucket_cells.assign(std::size_t(layout.bucket_offsets.back()), kNoIndex);
    }
  }
}

}  // namespace loom
