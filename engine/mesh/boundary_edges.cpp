#include "engine/mesh/boundary_edges.hpp"

#include <algorithm>

#include "engine/store/cells.hpp"

namespace loom {

std::vector<BoundaryEdge> boundary_edges(const std::vector<Index>& connectivity, int stride) {
  const Index n_cells = Index(connectivity.size() / std::size_t(stride));
  const int corners = corners_of_stride(stride);
  auto corner = [&](Index c, int s) { return connectivity[std::size_t(c) * std::size_t(stride) + std::size_t(s % corners)]; };
  Index n_nodes = 0;
  for (Index c = 0; c < n_cells; ++c)
    for (int s = 0; s < corners; ++s) n_nodes = std::max(n_nodes, corner(c, s) + 1);
  // Every half-edge's higher node, bucketed by its lower node (a counting sort: linear, where sorting all
  // half-edges cost a quarter of a remesh, docs/pfem_performance.md); an edge is on the boundary if its
  // bucket holds it once.
  std::vector<Index> first(std::size_t(n_nodes) + 1, 0);
  for (Index c = 0; c < n_cells; ++c)
    for (int s = 0; s < corners; ++s) ++first[std::size_t(std::min(corner(c, s), corner(c, s + 1))) + 1];
  for (Index i = 0; i < n_nodes; ++i) first[std::size_t(i) + 1] += first[std::size_t(i)];
  std::vector<Index> higher(std::size_t(first.back()));
  {
    std::vector<Index> cursor(first.begin(), first.end() - 1);
    for (Index c = 0; c < n_cells; ++c)
      for (int s = 0; s < corners; ++s) {
        const Index a = corner(c, s), b = corner(c, s + 1);
        higher[std::size_t(cursor[std::size_t(std::min(a, b))]++)] = std::max(a, b);
      }
  }
  // Visited by cell, then side: the edges come out in that (deterministic) order.
  std::vector<BoundaryEdge> edges;
  for (Index c = 0; c < n_cells; ++c)
    for (int s = 0; s < corners; ++s) {
      const Index a = corner(c, s), b = corner(c, s + 1), lo = std::min(a, b), hi = std::max(a, b);
      const auto begin = higher.begin() + first[std::size_t(lo)], end = higher.begin() + first[std::size_t(lo) + 1];
      if (std::count(begin, end, hi) == 1) edges.push_back({a, b, c, s});
    }
  return edges;
}

}  // namespace loom
