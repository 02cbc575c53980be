#include "engine/mesh/mid_nodes.hpp"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

namespace loom {
namespace {

// Corners first, then one mid-node per side (shared), then the centre if asked for.
template <int Corners>
std::vector<Index> add_side_nodes(std::vector<Vec2>& X, const std::vector<Index>& linear, bool centre) {
  const std::size_t n_cells = linear.size() / Corners;
  std::unordered_map<std::uint64_t, Index> mid_of_edge;
  mid_of_edge.reserve(n_cells * 2);
  std::vector<Index> quadratic;
  quadratic.reserve(n_cells * (2 * Corners + (centre ? 1 : 0)));
  for (std::size_t c = 0; c < n_cells; ++c) {
    const Index* v = linear.data() + Corners * c;
    Index mids[Corners];
    for (int s = 0; s < Corners; ++s) {
      const Index a = v[s], b = v[(s + 1) % Corners];
      const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
      auto [it, inserted] = mid_of_edge.emplace(key, Index(X.size()));
      if (inserted) X.push_back(0.5 * (X[std::size_t(a)] + X[std::size_t(b)]));
      mids[s] = it->second;
    }
    quadratic.insert(quadratic.end(), v, v + Corners);
    quadratic.insert(quadratic.end(), mids, mids + Corners);
  }
  if (!centre) return quadratic;
  std::vector<Index> with_centres;
  with_centres.reserve(n_cells * (2 * Corners + 1));
  for (std::size_t c = 0; c < n_cells; ++c) {
    const Index* v = quadratic.data() + 2 * Corners * c;
    with_centres.insert(with_centres.end(), v, v + 2 * Corners);
    Vec2 mean = Vec2::Zero();
    for (int a = 0; a < Corners; ++a) mean += X[std::size_t(v[a])];
    with_centres.push_back(Index(X.size()));
    X.push_back(mean / Corners);
  }
  return with_centres;
}

}  // namespace

std::vector<Index> add_mid_nodes(std::vector<Vec2>& X, const std::vector<Index>& tri3) { return add_side_nodes<3>(X, tri3, false); }

std::vector<Index> add_quad9_nodes(std::vector<Vec2>& X, const std::vector<Index>& quad4) { return add_side_nodes<4>(X, quad4, true); }

}  // namespace loom
