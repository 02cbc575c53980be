#include "engine/methods/pfem/new_triangle_mass.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "engine/mesh/triangle_geometry.hpp"

namespace loom {
namespace {

using Key = DomainSnapshot::Key;

Key corners_of(const Cells& c, Index t) {
  Key key{c.node(t, 0), c.node(t, 1), c.node(t, 2)};
  std::sort(key.begin(), key.end());
  return key;
}

// A new triangle that takes a share: (block, cell).
struct Fresh {
  std::size_t block;
  Index cell;
};

// Patches: the fresh triangles joined by shared edges (union-find); returns each one's root.
std::vector<std::size_t> patches_of(const std::vector<Fresh>& fresh, const std::vector<Cells>& cells) {
  std::vector<std::size_t> root(fresh.size());
  for (std::size_t k = 0; k < fresh.size(); ++k) root[k] = k;
  auto find = [&](std::size_t k) {
    while (root[k] != k) k = root[k] = root[root[k]];
    return k;
  };
  std::map<std::pair<Index, Index>, std::size_t> by_edge;
  for (std::size_t k = 0; k < fresh.size(); ++k) {
    const Cells& c = cells[fresh[k].block];
    for (int a = 0; a < 3; ++a) {
      const Index u = c.node(fresh[k].cell, a), v = c.node(fresh[k].cell, (a + 1) % 3);
      const auto [it, first] = by_edge.emplace(std::make_pair(std::min(u, v), std::max(u, v)), k);
      if (!first) root[find(k)] = find(it->second);
    }
  }
  for (std::size_t k = 0; k < fresh.size(); ++k) root[k] = find(k);
  return root;
}

}  // namespace

void share_mass_to_new_triangles(const DomainSnapshot& old, const Nodes<2>& nodes, std::vector<Cells>& cells,
                                 const std::vector<std::vector<char>>& is_new, const std::vector<double>& density,
                                 const std::vector<std::vector<char>>* gap_cells) {
  auto fills_gap = [&](std::size_t b, Index t) {
    return gap_cells && b < gap_cells->size() && std::size_t(t) < (*gap_cells)[b].size() && (*gap_cells)[b][std::size_t(t)];
  };
  auto rho = [&](const Cells& c, Index t) { return density[std::size_t(c.body[t])]; };
  auto area_n = [&](const Cells& c, Index t) {
    return signed_area(nodes.position_n(c.node(t, 0)), nodes.position_n(c.node(t, 1)), nodes.position_n(c.node(t, 2)));
  };
  auto area_0 = [&](const Cells& c, Index t) { return signed_area(nodes.X[c.node(t, 0)], nodes.X[c.node(t, 1)], nodes.X[c.node(t, 2)]); };
  const std::size_t n_nodes = std::size_t(nodes.size());

  // The triangles that take a share, the ones kept (their mass at each corner), and the new mesh's corner sets.
  std::vector<Fresh> fresh;
  std::vector<std::vector<std::size_t>> fresh_at(n_nodes);  // the fresh triangles around each node
  std::vector<double> kept(n_nodes, 0.0), fresh_area(n_nodes, 0.0);
  std::set<Key> present;
  for (std::size_t b = 0; b < cells.size(); ++b)
    for (Index t = 0; !is_new[b].empty() && t < cells[b].size(); ++t) {
      const Cells& c = cells[b];
      present.insert(corners_of(c, t));
      if (fills_gap(b, t)) continue;
      for (int a = 0; a < 3; ++a) {
        const std::size_t i = std::size_t(c.node(t, a));
        if (is_new[b][std::size_t(t)]) fresh_area[i] += area_n(c, t) / 3.0, fresh_at[i].push_back(fresh.size());
        else kept[i] += rho(c, t) * c.measure[t] / 3.0;
      }
      if (is_new[b][std::size_t(t)]) fresh.push_back({b, t});
    }

  // 1. Removed triangles matched to the fresh triangle that holds their centroid.
  std::vector<double> matched(fresh.size(), 0.0), matched_at(n_nodes, 0.0);
  for (const auto& [key, A0] : old.reference_area) {
    if (present.count(key) || key[2] >= Index(n_nodes)) continue;
    const Vec2 centroid = (nodes.position_n(key[0]) + nodes.position_n(key[1]) + nodes.position_n(key[2])) / 3.0;
    for (Index corner : key) {
      bool found = false;
      for (std::size_t k : fresh_at[std::size_t(corner)]) {
        const Cells& c = cells[fresh[k].block];
        const Index t = fresh[k].cell;
        const auto l = barycentric(nodes.position_n(c.node(t, 0)), nodes.position_n(c.node(t, 1)), nodes.position_n(c.node(t, 2)), centroid);
        if (!l || l->minCoeff() < -1e-9) continue;
        const double mass = rho(c, t) * A0;
        matched[k] += mass;
        for (Index v : key) matched_at[std::size_t(v)] += mass / 3.0;
        found = true;
        break;
      }
      if (found) break;
    }
  }

  // 2. What each particle lost besides: D_a = M_a - kept - matched >= 0, at a rate per unit of its new area.
  std::vector<double> rate(n_nodes, 0.0);
  for (std::size_t i = 0; i < n_nodes; ++i)
    if (fresh_area[i] > 0.0) rate[i] = std::max(0.0, nodes.lumped_mass[Index(i)] - kept[i] - matched_at[i]) / fresh_area[i];

  // 3. Each patch's mass, spread over its triangles.
  const std::vector<std::size_t> patch = patches_of(fresh, cells);
  std::vector<double> mass(fresh.size(), 0.0), shared(fresh.size(), 0.0), area(fresh.size(), 0.0), reference(fresh.size(), 0.0);
  std::vector<char> tiles(fresh.size(), 1);
  for (std::size_t k = 0; k < fresh.size(); ++k) {
    const Cells& c = cells[fresh[k].block];
    const Index t = fresh[k].cell;
    const double A = area_n(c, t), A_ref = area_0(c, t);
    const std::size_t p = patch[k];
    const double share = A * (rate[std::size_t(c.node(t, 0))] + rate[std::size_t(c.node(t, 1))] + rate[std::size_t(c.node(t, 2))]) / 3.0;
    mass[p] += matched[k] + share, shared[p] += share;
    area[p] += A, reference[p] += rho(c, t) * A_ref;
    if (!(A_ref > 0.0)) tiles[p] = 0;
  }
  for (std::size_t k = 0; k < fresh.size(); ++k) {
    if (patch[k] != k) continue;
    tiles[k] = tiles[k] && shared[k] <= 1e-12 * mass[k] && std::abs(reference[k] - mass[k]) <= 1e-9 * mass[k];
  }
  for (std::size_t k = 0; k < fresh.size(); ++k) {
    Cells& c = cells[fresh[k].block];
    const Index t = fresh[k].cell;
    const std::size_t p = patch[k];
    if (!(mass[p] > 0.0 && area[p] > 0.0)) {  // a patch that nothing gave mass to: the particles' volume, A_n / J_e
      const double J_e = (nodes.J_node[c.node(t, 0)] + nodes.J_node[c.node(t, 1)] + nodes.J_node[c.node(t, 2)]) / 3.0;
      c.measure[t] = area_n(c, t) / J_e;
      continue;
    }
    c.measure[t] = tiles[p] ? area_0(c, t) * (mass[p] / reference[p]) : area_n(c, t) * (mass[p] / area[p]) / rho(c, t);
  }
}

}  // namespace loom
