#include "engine/methods/pfem/domain_transfer.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "engine/core/errors.hpp"
#include "engine/mesh/simplex_geometry.hpp"
#include "engine/methods/model/build_domains.hpp"
#include "engine/methods/pfem/new_triangle_mass.hpp"
#include "systems/map/map_state.hpp"
#include "systems/update/commit_domains.hpp"

namespace loom {
namespace {

// Sorts key[0, n) in place (n <= D + 1); std::sort on a run-time prefix of a std::array draws a false -Warray-bounds
// from GCC 12.
template <std::size_t N>
void sort_prefix(std::array<Index, N>& key, int n) {
  for (int i = 1; i < n; ++i)
    for (int j = i; j > 0 && key[std::size_t(j - 1)] > key[std::size_t(j)]; --j) std::swap(key[std::size_t(j - 1)], key[std::size_t(j)]);
}

// An edge's (3D: a face's) sorted nodes with the last slot kNoIndex, or a whole cell's sorted corners.
template <int D>
typename DomainSnapshot<D>::Key key_of(const Edges<D>& e, Index k) {
  const Index* s = e.stencil.cell_nodes(k);
  typename DomainSnapshot<D>::Key key;
  const int n = e.whole_triangles ? D + 1 : D;
  for (int a = 0; a <= D; ++a) key[std::size_t(a)] = a < n ? s[a] : kNoIndex;
  sort_prefix(key, n);
  return key;
}

template <int D>
typename DomainSnapshot<D>::Key corners_of(const Cells& c, Index t) {
  typename DomainSnapshot<D>::Key key;
  for (int a = 0; a <= D; ++a) key[std::size_t(a)] = c.node(t, a);
  std::sort(key.begin(), key.end());
  return key;
}

// The volume ratio of a domain from its cells' current and reference measures: sum A_n / sum A_0.
template <int D>
double domain_reference_jacobian(const Nodes<D>& nodes, const Cells& c, const Edges<D>& e, Index k) {
  const auto x_n = [&](Index i) { return nodes.position_n(i); };
  double current = 0.0, reference = 0.0;
  for (int s = 0; s < 2; ++s) {
    const Index t = e.triangles[2 * k + s];
    if (t == kNoIndex) continue;
    current += simplex_measure<D>(c.cell_nodes(t), x_n);
    reference += c.measure[t];
  }
  return current / reference;
}

// The mean nodal J over a cell's corners.
template <int D>
double cell_nodal_jacobian(const Nodes<D>& nodes, const Cells& c, Index t) {
  double sum = nodes.J_node[c.node(t, 0)];
  for (int a = 1; a <= D; ++a) sum += nodes.J_node[c.node(t, a)];
  return sum / double(D + 1);
}

}  // namespace

template <int D>
DomainSnapshot<D> snapshot_domains(const std::vector<Edges<D>>& edges, const std::vector<Cells>& cells) {
  DomainSnapshot<D> s;
  for (const Edges<D>& e : edges)
    for (Index k = 0; k < e.size(); ++k) {
      s.domain_of[key_of(e, k)] = Index(s.midpoint.size());
      s.midpoint.push_back(e.midpoint[k]);
      s.be.push_back(e.be_n[k]);
      s.body.push_back(e.stencil.body[k]);
    }
  for (const Cells& c : cells)
    if (integrates_on_domains(c.formulation) && c.measure.used())
      for (Index t = 0; t < c.size(); ++t) s.reference_area[corners_of<D>(c, t)] = c.measure[t];
  return s;
}

template <int D>
void renumber_domain_snapshot(const std::vector<Index>& old_to_new, DomainSnapshot<D>& s) {
  using Key = typename DomainSnapshot<D>::Key;
  auto renumber = [&](Key key, Key& out) {
    for (Index& v : key) {
      if (v == kNoIndex) continue;
      if (v >= Index(old_to_new.size()) || old_to_new[std::size_t(v)] == kNoIndex) return false;
      v = old_to_new[std::size_t(v)];
    }
    // Sorted as key_of and corners_of sort (an edge's last slot stays kNoIndex).
    sort_prefix(key, key[D] == kNoIndex ? D : D + 1);
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

template <int D>
DomainTransferStats transfer_domains(const DomainSnapshot<D>& old, const Nodes<D>& nodes, std::vector<Cells>& cells,
                                     const std::vector<char>& j_projection, std::vector<Edges<D>>& edges, const std::vector<double>* density,
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
      const auto it = old.reference_area.find(corners_of<D>(c, t));
      if (it != old.reference_area.end()) c.measure[t] = it->second;
      else is_new[b][std::size_t(t)] = 1;
    }
  }
  // A_0 = A_n / J_e, J_e the mean nodal J of the corners: every new triangle of a static run (the spec's reading of eqs
  // 42, 48), and in a dynamic run the new material that fills a gap between two surfaces that met (it held no mass).
  auto from_nodal_jacobian = [&](Cells& c, Index t) {
    c.measure[t] = simplex_measure<D>(c.cell_nodes(t), [&](Index i) { return nodes.position_n(i); }) / cell_nodal_jacobian(nodes, c, t);
  };
  auto fills_gap = [&](std::size_t b, Index t) {
    return gap_cells && b < gap_cells->size() && std::size_t(t) < (*gap_cells)[b].size() && (*gap_cells)[b][std::size_t(t)];
  };
  for (std::size_t b = 0; b < cells.size(); ++b)
    for (Index t = 0; !is_new[b].empty() && t < cells[b].size(); ++t)
      if (is_new[b][std::size_t(t)] && (!density || fills_gap(b, t))) {
        from_nodal_jacobian(cells[b], t);
        if (density) stats.new_material_mass += (*density)[std::size_t(cells[b].body[t])] * cells[b].measure[t];
      }
  if (density) share_mass_to_new_triangles(old, nodes, cells, is_new, *density, gap_cells);  // the mass kept
  // Domains: rebuilt, then their history.
  edges.clear();
  build_domains(nodes, cells, j_projection, edges);
  std::vector<Index> copy_from, new_body;
  for (const Edges<D>& e : edges)
    for (Index k = 0; k < e.size(); ++k) {
      const auto it = old.domain_of.find(key_of(e, k));
      copy_from.push_back(it == old.domain_of.end() ? kNoIndex : it->second);
      new_body.push_back(e.stencil.body[k]);
    }
  // Body by body: the nearest old domain of the same body (CPM on the midpoints in B_n).
  std::vector<Mat3> be(copy_from.size());
  const Index n_bodies = new_body.empty() ? 0 : *std::max_element(new_body.begin(), new_body.end()) + 1;
  for (Index b = 0; b < n_bodies; ++b) {
    std::vector<Vec<D>> old_x, new_x;
    std::vector<Mat3> old_be, new_be;
    std::vector<Index> old_index(old.body.size(), kNoIndex), copy, slot;
    for (std::size_t k = 0; k < old.body.size(); ++k)
      if (old.body[k] == b) old_index[k] = Index(old_x.size()), old_x.push_back(old.midpoint[k]), old_be.push_back(old.be[k]);
    std::size_t next_new = 0;
    for (const Edges<D>& e : edges)
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
  for (Edges<D>& e : edges) {
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

template DomainSnapshot<2> snapshot_domains(const std::vector<Edges<2>>&, const std::vector<Cells>&);
template DomainSnapshot<3> snapshot_domains(const std::vector<Edges<3>>&, const std::vector<Cells>&);
template void renumber_domain_snapshot(const std::vector<Index>&, DomainSnapshot<2>&);
template void renumber_domain_snapshot(const std::vector<Index>&, DomainSnapshot<3>&);
template DomainTransferStats transfer_domains(const DomainSnapshot<2>&, const Nodes<2>&, std::vector<Cells>&, const std::vector<char>&,
                                              std::vector<Edges<2>>&, const std::vector<double>*, const std::vector<std::vector<char>>*);
template DomainTransferStats transfer_domains(const DomainSnapshot<3>&, const Nodes<3>&, std::vector<Cells>&, const std::vector<char>&,
                                              std::vector<Edges<3>>&, const std::vector<double>*, const std::vector<std::vector<char>>*);

}  // namespace loom
