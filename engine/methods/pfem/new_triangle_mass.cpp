#include "engine/methods/pfem/new_triangle_mass.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "engine/mesh/simplex_geometry.hpp"

namespace loom {
namespace {

template <int D>
typename DomainSnapshot<D>::Key corners_of(const Cells& c, Index t) {
  typename DomainSnapshot<D>::Key key;
  for (int a = 0; a <= D; ++a) key[std::size_t(a)] = c.node(t, a);
  std::sort(key.begin(), key.end());
  return key;
}

// A new triangle that takes a share: (block, cell).
struct Fresh {
  std::size_t block;
  Index cell;
};

// Patches: the fresh triangles joined by shared edges (3D: tetrahedra by shared faces; union-find); returns each
// one's root.
template <int D>
std::vector<std::size_t> patches_of(const std::vector<Fresh>& fresh, const std::vector<Cells>& cells) {
  std::vector<std::size_t> root(fresh.size());
  for (std::size_t k = 0; k < fresh.size(); ++k) root[k] = k;
  auto find = [&](std::size_t k) {
    while (root[k] != k) k = root[k] = root[root[k]];
    return k;
  };
  std::map<std::array<Index, D>, std::size_t> by_facet;
  for (std::size_t k = 0; k < fresh.size(); ++k) {
    const auto corners = corners_of<D>(cells[fresh[k].block], fresh[k].cell);
    for (int skip = 0; skip <= D; ++skip) {  // the facet opposite corner `skip`, sorted
      std::array<Index, D> facet;
      for (int a = 0, f = 0; a <= D; ++a)
        if (a != skip) facet[std::size_t(f++)] = corners[std::size_t(a)];
      const auto [it, first] = by_facet.emplace(facet, k);
      if (!first) root[find(k)] = find(it->second);
    }
  }
  for (std::size_t k = 0; k < fresh.size(); ++k) root[k] = find(k);
  return root;
}

}  // namespace

template <int D>
void share_mass_to_new_triangles(const DomainSnapshot<D>& old, const Nodes<D>& nodes, std::vector<Cells>& cells,
                                 const std::vector<std::vector<char>>& is_new, const std::vector<double>& density,
                                 const std::vector<std::vector<char>>* gap_cells) {
  auto fills_gap = [&](std::size_t b, Index t) {
    return gap_cells && b < gap_cells->size() && std::size_t(t) < (*gap_cells)[b].size() && (*gap_cells)[b][std::size_t(t)];
  };
  auto rho = [&](const Cells& c, Index t) { return density[std::size_t(c.body[t])]; };
  const auto x_n = [&](Index i) { return nodes.position_n(i); };
  const auto X = [&](Index i) { return Vec<D>(nodes.X[i]); };
  auto area_n = [&](const Cells& c, Index t) { return simplex_measure<D>(c.cell_nodes(t), x_n); };
  auto area_0 = [&](const Cells& c, Index t) { return simplex_measure<D>(c.cell_nodes(t), X); };
  // A corner's share of a cell, and the sum over the corners of a nodal value.
  constexpr double kCorners = D + 1;
  auto corner_sum = [&](const Cells& c, Index t, auto&& value) {
    double sum = value(c.node(t, 0));
    for (int a = 1; a <= D; ++a) sum += value(c.node(t, a));
    return sum;
  };
  const std::size_t n_nodes = std::size_t(nodes.size());

  // The triangles that take a share, the ones kept (their mass at each corner), and the new mesh's corner sets.
  std::vector<Fresh> fresh, kept_cells;
  std::vector<std::vector<std::size_t>> fresh_at(n_nodes), kept_at(n_nodes);  // the fresh (kept) triangles around each node
  std::vector<double> kept(n_nodes, 0.0), fresh_area(n_nodes, 0.0);
  std::set<typename DomainSnapshot<D>::Key> present;
  for (std::size_t b = 0; b < cells.size(); ++b)
    for (Index t = 0; !is_new[b].empty() && t < cells[b].size(); ++t) {
      const Cells& c = cells[b];
      present.insert(corners_of<D>(c, t));
      if (fills_gap(b, t)) continue;
      for (int a = 0; a <= D; ++a) {
        const std::size_t i = std::size_t(c.node(t, a));
        if (is_new[b][std::size_t(t)]) fresh_area[i] += area_n(c, t) / kCorners, fresh_at[i].push_back(fresh.size());
        else kept[i] += rho(c, t) * c.measure[t] / kCorners, kept_at[i].push_back(kept_cells.size());
      }
      if (is_new[b][std::size_t(t)]) fresh.push_back({b, t});
      else kept_cells.push_back({b, t});
    }

  // 1. Removed triangles matched to the fresh triangle that holds their centroid.
  std::vector<double> matched(fresh.size(), 0.0), matched_at(n_nodes, 0.0);
  for (const auto& [key, A0] : old.reference_area) {
    if (present.count(key) || key[D] >= Index(n_nodes)) continue;
    const Vec<D> centroid = simplex_centroid<D>(key.data(), x_n);
    for (Index corner : key) {
      bool found = false;
      for (std::size_t k : fresh_at[std::size_t(corner)]) {
        const Cells& c = cells[fresh[k].block];
        const Index t = fresh[k].cell;
        if (!simplex_contains<D>(c.cell_nodes(t), x_n, centroid, 1e-9)) continue;
        const double mass = rho(c, t) * A0;
        matched[k] += mass;
        for (Index v : key) matched_at[std::size_t(v)] += mass / kCorners;
        found = true;
        break;
      }
      if (found) break;
    }
  }

  // 2. What each particle lost besides: D_a = M_a - kept - matched >= 0, at a rate per unit of its new area. A
  //    particle with no fresh triangle around it (a removed triangle whose neighbours all survived) gives D_a to the
  //    kept triangles around it instead, in proportion to their areas: they hold a little more material.
  std::vector<double> rate(n_nodes, 0.0), extra(kept_cells.size(), 0.0);
  for (std::size_t i = 0; i < n_nodes; ++i) {
    const double lost = std::max(0.0, nodes.lumped_mass[Index(i)] - kept[i] - matched_at[i]);
    if (fresh_area[i] > 0.0) {
      rate[i] = lost / fresh_area[i];
    } else if (lost > 1e-12 * nodes.lumped_mass[Index(i)] && !kept_at[i].empty()) {  // not round-off
      double around = 0.0;
      for (std::size_t k : kept_at[i]) around += area_n(cells[kept_cells[k].block], kept_cells[k].cell);
      for (std::size_t k : kept_at[i]) extra[k] += lost * area_n(cells[kept_cells[k].block], kept_cells[k].cell) / around;
    }
  }
  for (std::size_t k = 0; k < kept_cells.size(); ++k)
    if (extra[k] > 0.0) {
      Cells& c = cells[kept_cells[k].block];
      c.measure[kept_cells[k].cell] += extra[k] / rho(c, kept_cells[k].cell);
    }

  // 3. Each patch's mass, spread over its triangles.
  const std::vector<std::size_t> patch = patches_of<D>(fresh, cells);
  std::vector<double> mass(fresh.size(), 0.0), shared(fresh.size(), 0.0), area(fresh.size(), 0.0), reference(fresh.size(), 0.0);
  std::vector<char> tiles(fresh.size(), 1);
  for (std::size_t k = 0; k < fresh.size(); ++k) {
    const Cells& c = cells[fresh[k].block];
    const Index t = fresh[k].cell;
    const double A = area_n(c, t), A_ref = area_0(c, t);
    const std::size_t p = patch[k];
    const double share = A * corner_sum(c, t, [&](Index i) { return rate[std::size_t(i)]; }) / kCorners;
    mass[p] += matched[k] + share, shared[p] += share;
    area[p] += A, reference[p] += rho(c, t) * A_ref;
    if (!(A_ref > 0.0)) tiles[p] = 0;
  }
  for (std::size_t k = 0; k < fresh.size(); ++k) {
    if (patch[k] != k) continue;
    tiles[k] = tiles[k] && shared[k] <= 1e-12 * mass[k] && std::abs(reference[k] - mass[k]) <= 1e-9 * mass[k];
  }
  // A patch that nothing gave mass to (a sliver the remesh added on the surface, all its corners' old cells kept) takes
  // the particles' volume, A_n / J_e, and that mass from the kept cells around its corners, in proportion to theirs.
  std::vector<double> taken(kept_cells.size(), 0.0);
  for (std::size_t k = 0; k < fresh.size(); ++k) {
    Cells& c = cells[fresh[k].block];
    const Index t = fresh[k].cell;
    const std::size_t p = patch[k];
    if (!(mass[p] > 0.0 && area[p] > 0.0)) {
      c.measure[t] = area_n(c, t) / (corner_sum(c, t, [&](Index i) { return nodes.J_node[i]; }) / kCorners);
      double around = 0.0;
      for (int a = 0; a <= D; ++a)
        for (std::size_t j : kept_at[std::size_t(c.node(t, a))]) around += cells[kept_cells[j].block].measure[kept_cells[j].cell];
      for (int a = 0; a <= D && around > 0.0; ++a)
        for (std::size_t j : kept_at[std::size_t(c.node(t, a))])
          taken[j] += c.measure[t] * cells[kept_cells[j].block].measure[kept_cells[j].cell] / around;
      continue;
    }
    c.measure[t] = tiles[p] ? area_0(c, t) * (mass[p] / reference[p]) : area_n(c, t) * (mass[p] / area[p]) / rho(c, t);
  }
  for (std::size_t j = 0; j < kept_cells.size(); ++j)  // same density: volumes move
    if (taken[j] > 0.0) cells[kept_cells[j].block].measure[kept_cells[j].cell] -= taken[j];
}

template void share_mass_to_new_triangles(const DomainSnapshot<2>&, const Nodes<2>&, std::vector<Cells>&, const std::vector<std::vector<char>>&,
                                          const std::vector<double>&, const std::vector<std::vector<char>>*);
template void share_mass_to_new_triangles(const DomainSnapshot<3>&, const Nodes<3>&, std::vector<Cells>&, const std::vector<std::vector<char>>&,
                                          const std::vector<double>&, const std::vector<std::vector<char>>*);

}  // namespace loom
