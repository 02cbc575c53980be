#include "systems/remesh/boundary_loops.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>

namespace loom {

BoundaryLoops boundary_loops(Index n_points, const std::vector<Edge>& boundary, const std::vector<Vec2>* x) {
  BoundaryLoops out;
  out.loop.assign(std::size_t(n_points), kNoIndex);
  out.position.assign(std::size_t(n_points), kNoIndex);
  out.arc.assign(std::size_t(n_points), 0.0);
  // Outgoing edges per point (counting sort): a pinch point has two.
  std::vector<Index> first(std::size_t(n_points) + 1, 0), out_edge(boundary.size());
  for (const Edge& e : boundary) ++first[std::size_t(e[0]) + 1];
  for (std::size_t i = 0; i < std::size_t(n_points); ++i) first[i + 1] += first[i];
  std::vector<Index> fill(first.begin(), first.end() - 1);
  for (std::size_t k = 0; k < boundary.size(); ++k) out_edge[std::size_t(fill[std::size_t(boundary[k][0])]++)] = Index(k);
  std::vector<char> used(boundary.size(), 0);
  for (std::size_t start = 0; start < boundary.size(); ++start) {
    if (used[start]) continue;
    const Index id = Index(out.length.size());
    Index steps = 0;
    double along = 0.0;
    for (Index k = Index(start); k != kNoIndex && !used[std::size_t(k)];) {
      used[std::size_t(k)] = 1;
      const Index a = boundary[std::size_t(k)][0], b = boundary[std::size_t(k)][1];
      if (out.loop[std::size_t(a)] == kNoIndex) out.loop[std::size_t(a)] = id, out.position[std::size_t(a)] = steps, out.arc[std::size_t(a)] = along;
      ++steps;
      if (x) along += ((*x)[std::size_t(b)] - (*x)[std::size_t(a)]).norm();
      Index next = kNoIndex;  // an unused edge leaving b
      for (Index s = first[std::size_t(b)]; s < first[std::size_t(b) + 1] && next == kNoIndex; ++s)
        if (!used[std::size_t(out_edge[std::size_t(s)])]) next = out_edge[std::size_t(s)];
      k = next;
    }
    out.length.push_back(steps);
    out.perimeter.push_back(along);
  }
  return out;
}

Index steps_along(const BoundaryLoops& loops, Index a, Index b) {
  const Index la = loops.loop[std::size_t(a)], lb = loops.loop[std::size_t(b)];
  if (la == kNoIndex || la != lb) return kNoIndex;
  const Index d = std::abs(loops.position[std::size_t(a)] - loops.position[std::size_t(b)]);
  return std::min(d, loops.length[std::size_t(la)] - d);
}

double length_along(const BoundaryLoops& loops, Index a, Index b) {
  const Index la = loops.loop[std::size_t(a)], lb = loops.loop[std::size_t(b)];
  if (la == kNoIndex || la != lb) return std::numeric_limits<double>::infinity();
  const double d = std::abs(loops.arc[std::size_t(a)] - loops.arc[std::size_t(b)]);
  return std::min(d, loops.perimeter[std::size_t(la)] - d);
}

}  // namespace loom
