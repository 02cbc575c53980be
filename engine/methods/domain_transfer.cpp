#include "engine/methods/domain_transfer.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "engine/core/errors.hpp"
#include "engine/methods/build_domains.hpp"
#include "engine/mesh/triangle_geometry.hpp"
#include "systems/map/map_state.hpp"
#include "systems/update/commit_domains.hpp"

namespace loom {
namespace {

using Key = DomainSnapshot::Key;

Key key_of(const Edges<2>& e, Index k) {
  const Index* s = e.stencil.cell_nodes(k);
  Key key{s[0], s[1], e.whole_triangles ? s[2] : kNoIndex};
  std::sort(key.begin(), key.begin() + (e.whole_triangles ? 3 : 2));
  return key;
}

Key corners_of(const Cells& c, Index t) {
  Key key{c.node(t, 0), c.node(t, 1), c.node(t, 2)};
  std::sort(key.begin(), key.end());
  return key;
}

// The volume ratio of a domain from its triangles' current and reference areas: sum A_n / sum A_0.
double domain_reference_jacobian(const Nodes<2>& nodes, const Cells& c, const Edges<2>& e, Index k) {
  double current = 0.0, reference = 0.0;
  for (int s = 0; s < 2; ++s) {
    const Index t = e.triangles[2 * k + s];
    if (t == kNoIndex) continue;
    current += signed_area(nodes.position_n(c.node(t, 0)), nodes.position_n(c.node(t, 1)), nodes.position_n(c.node(t, 2)));
    reference += c.measure[t];
  }
  return current / reference;
}

}  // namespace

DomainSnapshot snapshot_domains(const std::vector<Edges<2>>& edges, const std::vector<Cells>& cells) {
  DomainSnapshot s;
  for (const Edges<2>& e : edges)
    for (Index k = 0; k < e.size(); ++k) {
      s.domain_of[key_of(e, k)] = Index(s.midpoint.size());
      s.midpoint.push_back(e.midpoint[k]);
      s.be.push_back(e.be_n[k]);
      s.body.push_back(e.stencil.body[k]);
    }
  for (const Cells& c : cells)
    if (integrates_on_domains(c.formulation) && c.measure.used())
      for (Index t = 0; t < c.size(); ++t) s.reference_area[corners_of(c, t)] = c.measure[t];
  return s;
}

void renumber_domain_snapshot(const std::vector<Index>& old_to_new, DomainSnapshot& s) {
  auto renumber = [&](Key key, Key& out) {
    for (Index& v : key) {
      if (v == kNoIndex) continue;
      if (v >= Index(old_to_new.size()) || old_to_new[std::size_t(v)] == kNoIndex) return false;
      v = old_to_new[std::size_t(v)];
    }
    // Sorted as key_of and corners_of sort (an edge's third slot stays kNoIndex).
    if (key[0] > key[1]) std::swap(key[0], key[1]);
    if (key[2] != kNoIndex) {
      if (key[1] > key[2]) std::swap(key[1], key[2]);
      if (key[0] > key[1]) std::swap(key[0], key[1]);
    }
    out = key;
    return true;
  };
  std::map<Key, Index> domain_of;
  for (const auto& [key, k] : s.domain_of)
    if (Key next; renumber(key, next)) domain_of[next] = k;
  std::map<Key, double> reference_area;
  for (const auto& [key, area] : s.reference_area)
    if (Key next; renumber(key, next)) reference_area[next] = area;
  s.domain_of.swap(domain_of);
  s.reference_area.swap(reference_area);
}

DomainTransferStats transfer_domains(const DomainSnapshot& old, const Nodes<2>& nodes, std::vector<Cells>& cells,
                                     const std::vector<char>& j_projection, std::vector<Edges<2>>& edges, const std::vector<double>* density,
                                     const std::vector<std::vector<char>>* gap_cells) {
  DomainTransferStats stats;
  // Triangles: reference areas. A surviving triangle keeps its own.
  std::vector<std::vector<char>> is_new(cells.size());
  for (std::size_t b = 0; b < cells.size(); ++b) {
    Cells& c = cells[b];
    if (!integrates_on_domains(c.formulation)) continue;
    c.measure.use();
    c.measure.resize(c.size());
    is_new[b].assign(std::size_t(c.size()), 0);
    for (Index t = 0; t < c.size(); ++t) {
      const auto it = old.reference_area.find(corners_of(c, t));
      if (it != old.reference_area.end()) c.measure[t] = it->second;
      else is_new[b][std::size_t(t)] = 1;
    }
  }
  auto area_n = [&](const Cells& c, Index t) {
    return signed_area(nodes.position_n(c.node(t, 0)), nodes.position_n(c.node(t, 1)), nodes.position_n(c.node(t, 2)));
  };
  if (density) {
    // Mass kept: each particle's lumped mass M_a (of the old mesh, carried through any change of the particle set)
    // less what its surviving triangles still give it, D_a = M_a - sum_kept rho A_0 / 3 >= 0, is what its new
    // triangles must give it: a mass per current area r_a = D_a / sum_new A_n / 3 at each corner, and sum over the
    // new triangles of A_n (r_a + r_b + r_c) / 3 = sum_a D_a: the body's mass is unchanged.
    auto fills_gap = [&](std::size_t b, Index t) {
      return gap_cells && b < gap_cells->size() && std::size_t(t) < (*gap_cells)[b].size() && (*gap_cells)[b][std::size_t(t)];
    };
    std::vector<double> kept(std::size_t(nodes.size()), 0.0), fresh_area(std::size_t(nodes.size()), 0.0);
    for (std::size_t b = 0; b < cells.size(); ++b)
      for (Index t = 0; !is_new[b].empty() && t < cells[b].size(); ++t)
        for (int a = 0; a < 3 && !fills_gap(b, t); ++a) {
          const std::size_t i = std::size_t(cells[b].node(t, a));
          if (is_new[b][std::size_t(t)]) fresh_area[i] += area_n(cells[b], t) / 3.0;
          else kept[i] += (*density)[std::size_t(cells[b].body[t])] * cells[b].measure[t] / 3.0;
        }
    std::vector<double> rate(std::size_t(nodes.size()), 0.0);
    for (std::size_t i = 0; i < rate.size(); ++i)
      if (fresh_area[i] > 0.0) rate[i] = std::max(0.0, nodes.lumped_mass[Index(i)] - kept[i]) / fresh_area[i];
    // The new triangles that share edges form patches (an edge flip, an inflow strip, the region of a removed
    // particle); each patch takes its corners' shares, sum A_n (r_a + r_b + r_c) / 3, spread at a uniform density,
    // so that a patch replacing uniform material gets that material's density back (a per-corner share would not).
    std::vector<std::pair<std::size_t, Index>> fresh;  // (block, cell) of the new triangles that take a share
    for (std::size_t b = 0; b < cells.size(); ++b)
      for (Index t = 0; !is_new[b].empty() && t < cells[b].size(); ++t) {
        const Cells& c = cells[b];
        if (!is_new[b][std::size_t(t)]) continue;
        if (fills_gap(b, t)) {
          cells[b].measure[t] = area_n(c, t) / ((nodes.J_node[c.node(t, 0)] + nodes.J_node[c.node(t, 1)] + nodes.J_node[c.node(t, 2)]) / 3.0);
          continue;
        }
        fresh.emplace_back(b, t);
      }
    std::vector<std::size_t> root(fresh.size());
    for (std::size_t k = 0; k < fresh.size(); ++k) root[k] = k;
    auto find = [&](std::size_t k) {
      while (root[k] != k) k = root[k] = root[root[k]];
      return k;
    };
    std::map<std::pair<Index, Index>, std::size_t> by_edge;
    for (std::size_t k = 0; k < fresh.size(); ++k) {
      const Cells& c = cells[fresh[k].first];
      for (int a = 0; a < 3; ++a) {
        const Index u = c.node(fresh[k].second, a), v = c.node(fresh[k].second, (a + 1) % 3);
        const auto [it, first] = by_edge.emplace(std::make_pair(std::min(u, v), std::max(u, v)), k);
        if (!first) root[find(k)] = find(it->second);
      }
    }
    std::vector<double> patch_mass(fresh.size(), 0.0), patch_area(fresh.size(), 0.0);
    for (std::size_t k = 0; k < fresh.size(); ++k) {
      const Cells& c = cells[fresh[k].first];
      const Index t = fresh[k].second;
      const double A = area_n(c, t);
      patch_mass[find(k)] += A * (rate[std::size_t(c.node(t, 0))] + rate[std::size_t(c.node(t, 1))] + rate[std::size_t(c.node(t, 2))]) / 3.0;
      patch_area[find(k)] += A;
    }
    for (std::size_t k = 0; k < fresh.size(); ++k) {
      const Cells& c = cells[fresh[k].first];
      const Index t = fresh[k].second;
      const std::size_t p = find(k);
      cells[fresh[k].first].measure[t] = area_n(c, t) * (patch_mass[p] / patch_area[p]) / (*density)[std::size_t(c.body[t])];
    }
  } else {
    // The volume from the particles' nodal J: A_0 = A_n / J_e (the spec's reading of eqs 42, 48).
    for (std::size_t b = 0; b < cells.size(); ++b)
      for (Index t = 0; !is_new[b].empty() && t < cells[b].size(); ++t)
        if (is_new[b][std::size_t(t)]) {
          const Cells& c = cells[b];
          const double J_e = (nodes.J_node[c.node(t, 0)] + nodes.J_node[c.node(t, 1)] + nodes.J_node[c.node(t, 2)]) / 3.0;
          cells[b].measure[t] = area_n(c, t) / J_e;
        }
  }
  // Domains: rebuilt, then their history.
  edges.clear();
  build_domains(nodes, cells, j_projection, edges);
  std::vector<Index> copy_from, new_body;
  for (const Edges<2>& e : edges)
    for (Index k = 0; k < e.size(); ++k) {
      const auto it = old.domain_of.find(key_of(e, k));
      copy_from.push_back(it == old.domain_of.end() ? kNoIndex : it->second);
      new_body.push_back(e.stencil.body[k]);
    }
  // Body by body: the nearest old domain of the same body (CPM on the midpoints in B_n).
  std::vector<Mat3> be(copy_from.size());
  const Index n_bodies = new_body.empty() ? 0 : *std::max_element(new_body.begin(), new_body.end()) + 1;
  for (Index b = 0; b < n_bodies; ++b) {
    std::vector<Vec2> old_x, new_x;
    std::vector<Mat3> old_be, new_be;
    std::vector<Index> old_index(old.body.size(), kNoIndex), copy, slot;
    for (std::size_t k = 0; k < old.body.size(); ++k)
      if (old.body[k] == b) old_index[k] = Index(old_x.size()), old_x.push_back(old.midpoint[k]), old_be.push_back(old.be[k]);
    std::size_t next_new = 0;
    for (const Edges<2>& e : edges)
      for (Index k = 0; k < e.size(); ++k, ++next_new)
        if (new_body[next_new] == b) {
          new_x.push_back(e.midpoint[k]);
          const Index from = copy_from[next_new];
          copy.push_back(from == kNoIndex ? kNoIndex : old_index[std::size_t(from)]);
          slot.push_back(Index(next_new));
        }
    if (new_x.empty()) continue;
    LOOM_CHECK(!old_x.empty(), RunError, "remesh: body " << b << " has new integration domains but had none to take their history from");
    MapStats map_stats;
    map_state(old_x, old_be, new_x, copy, MapSettings{}, new_be, map_stats);
    for (std::size_t k = 0; k < slot.size(); ++k) be[std::size_t(slot[k])] = new_be[k];
  }
  std::size_t next = 0;
  for (Edges<2>& e : edges) {
    for (Index k = 0; k < e.size(); ++k, ++next) {
      Mat3 b = be[next];
      if (copy_from[next] == kNoIndex) {
        b = with_volume_ratio(b, density ? domain_reference_jacobian(nodes, cells[std::size_t(e.cell_block)], e, k) : domain_nodal_jacobian(nodes, e, k));
        ++stats.projected;
      } else {
        ++stats.kept;
      }
      e.be_n[k] = e.be[k] = b;
    }
  }
  return stats;
}

}  // namespace loom
