#include "systems/remesh/surface_graph.hpp"

#include <algorithm>
#include <functional>
#include <limits>
#include <map>
#include <queue>

#include <Eigen/Geometry>  // cross

namespace loom {

SurfaceGraph::SurfaceGraph(Index n_points, const std::vector<std::array<Index, 3>>& faces, const std::vector<Vec3>& x) : x_(x) {
  const std::size_t n = std::size_t(n_points);
  // Neighbours along face sides (counting sort, then sorted and unique per point).
  first_.assign(n + 1, 0);
  for (const auto& f : faces)
    for (int s = 0; s < 3; ++s) ++first_[std::size_t(f[std::size_t(s)]) + 1], ++first_[std::size_t(f[std::size_t((s + 1) % 3)]) + 1];
  for (std::size_t i = 0; i < n; ++i) first_[i + 1] += first_[i];
  std::vector<Index> all(std::size_t(first_[n]));
  {
    std::vector<Index> cursor(first_.begin(), first_.end() - 1);
    for (const auto& f : faces)
      for (int s = 0; s < 3; ++s) {
        const Index a = f[std::size_t(s)], b = f[std::size_t((s + 1) % 3)];
        all[std::size_t(cursor[std::size_t(a)]++)] = b, all[std::size_t(cursor[std::size_t(b)]++)] = a;
      }
  }
  std::vector<Index> compact_first(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    auto begin = all.begin() + first_[i], end = all.begin() + first_[i + 1];
    std::sort(begin, end);
    end = std::unique(begin, end);
    compact_first[i + 1] = compact_first[i] + Index(end - begin);
    neighbour_.insert(neighbour_.end(), begin, end);
  }
  first_.swap(compact_first);

  // Components by flood fill in ascending point order, so that their numbering is reproducible.
  component_.assign(n, kNoIndex);
  Index count = 0;
  for (std::size_t s = 0; s < n; ++s) {
    if (component_[s] != kNoIndex || first_[s] == first_[s + 1]) continue;
    std::vector<Index> stack{Index(s)};
    component_[s] = count;
    while (!stack.empty()) {
      const Index v = stack.back();
      stack.pop_back();
      for (Index k = first_[std::size_t(v)]; k < first_[std::size_t(v) + 1]; ++k)
        if (const Index w = neighbour_[std::size_t(k)]; component_[std::size_t(w)] == kNoIndex) component_[std::size_t(w)] = count, stack.push_back(w);
    }
    ++count;
  }
  // The volume a component's outward faces enclose (divergence theorem): negative for the wall of a void.
  std::vector<double> volume(std::size_t(count), 0.0);
  for (const auto& f : faces) {
    const Vec3 &a = x[std::size_t(f[0])], &b = x[std::size_t(f[1])], &c = x[std::size_t(f[2])];
    volume[std::size_t(component_[std::size_t(f[0])])] += a.dot(b.cross(c)) / 6.0;
  }
  inner_.resize(volume.size());
  for (std::size_t c = 0; c < volume.size(); ++c) inner_[c] = volume[c] < 0.0 ? 1 : 0;
}

double SurfaceGraph::distance_along(Index a, Index b, double limit) const {
  constexpr double kFar = std::numeric_limits<double>::infinity();
  if (a == b) return 0.0;
  // Bounded Dijkstra; the few points within `limit` of a are kept in a map (a surface of 10^5 points is searched
  // locally, not allocated per query).
  std::map<Index, double> best{{a, 0.0}};
  using Item = std::pair<double, Index>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  queue.push({0.0, a});
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (v == b) return d;
    if (d > best[v]) continue;
    for (Index k = first_[std::size_t(v)]; k < first_[std::size_t(v) + 1]; ++k) {
      const Index w = neighbour_[std::size_t(k)];
      const double next = d + (x_[std::size_t(w)] - x_[std::size_t(v)]).norm();
      if (next > limit) continue;
      const auto it = best.find(w);
      if (it != best.end() && it->second <= next) continue;
      best[w] = next;
      queue.push({next, w});
    }
  }
  return kFar;
}

bool joins_two_surfaces(const SurfaceGraph& surface, const std::vector<Vec3>& x, const Index (&corners)[4]) {
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      const Index a = corners[i], b = corners[j];
      if (!surface.on_surface(a) || !surface.on_surface(b) || surface.component(a) != surface.component(b)) return true;
      const double gap = (x[std::size_t(a)] - x[std::size_t(b)]).norm();
      if (surface.distance_along(a, b, kMergeDetour3d * gap) >= kMergeDetour3d * gap) return true;
    }
  return false;
}

}  // namespace loom
