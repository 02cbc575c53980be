#include "engine/mesh/boundary_edges.hpp"

#include <algorithm>
#include <cstdint>

#include "engine/store/cells.hpp"

namespace loom {

std::vector<BoundaryEdge> boundary_edges(const std::vector<Index>& connectivity, int stride) {
  struct Half {
    std::uint64_t key;  // sorted node pair, packed
    Index a, b, cell;
    int side;
  };
  const Index n_cells = Index(connectivity.size() / std::size_t(stride));
  const int corners = corners_of_stride(stride);
  std::vector<Half> halves;
  halves.reserve(std::size_t(n_cells) * std::size_t(corners));
  for (Index c = 0; c < n_cells; ++c)
    for (int s = 0; s < corners; ++s) {
      const Index a = connectivity[std::size_t(c) * stride + s];
      const Index b = connectivity[std::size_t(c) * stride + (s + 1) % corners];
      const auto lo = std::uint64_t(std::min(a, b)), hi = std::uint64_t(std::max(a, b));
      halves.push_back({(lo << 32) | hi, a, b, c, s});
    }
  std::sort(halves.begin(), halves.end(), [](const Half& x, const Half& y) {
    return x.key != y.key ? x.key < y.key : x.cell < y.cell;
  });
  std::vector<BoundaryEdge> edges;
  for (std::size_t i = 0; i < halves.size();) {
    std::size_t j = i + 1;
    while (j < halves.size() && halves[j].key == halves[i].key) ++j;
    if (j - i == 1) edges.push_back({halves[i].a, halves[i].b, halves[i].cell, halves[i].side});
    i = j;
  }
  // Deterministic order: by owning cell, then side.
  std::sort(edges.begin(), edges.end(),
            [](const BoundaryEdge& x, const BoundaryEdge& y) { return x.cell != y.cell ? x.cell < y.cell : x.side < y.side; });
  return edges;
}

}  // namespace loom
