#include "engine/mesh/mid_nodes.hpp"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

namespace loom {

std::vector<Index> add_mid_nodes(std::vector<Vec2>& X, const std::vector<Index>& tri3) {
  const std::size_t n_cells = tri3.size() / 3;
  std::unordered_map<std::uint64_t, Index> mid_of_edge;
  mid_of_edge.reserve(n_cells * 2);
  std::vector<Index> tri6;
  tri6.reserve(n_cells * 6);
  for (std::size_t c = 0; c < n_cells; ++c) {
    const Index* v = tri3.data() + 3 * c;
    Index mids[3];
    for (int s = 0; s < 3; ++s) {
      const Index a = v[s], b = v[(s + 1) % 3];
      const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
      auto [it, inserted] = mid_of_edge.emplace(key, Index(X.size()));
      if (inserted) X.push_back(0.5 * (X[std::size_t(a)] + X[std::size_t(b)]));
      mids[s] = it->second;
    }
    tri6.insert(tri6.end(), {v[0], v[1], v[2], mids[0], mids[1], mids[2]});
  }
  return tri6;
}

}  // namespace loom
