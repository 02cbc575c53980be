#include "engine/methods/domain_transfer.hpp"

#include <algorithm>
#include <cmath>

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

DomainTransferStats transfer_domains(const DomainSnapshot& old, const Nodes<2>& nodes, std::vector<Cells>& cells,
                                     const std::vector<char>& j_projection, std::vector<Edges<2>>& edges) {
  DomainTransferStats stats;
  // Triangles: reference areas.
  for (Cells& c : cells) {
    if (!integrates_on_domains(c.formulation)) continue;
    c.measure.use();
    c.measure.resize(c.size());
    for (Index t = 0; t < c.size(); ++t) {
      const auto it = old.reference_area.find(corners_of(c, t));
      if (it != old.reference_area.end()) {
        c.measure[t] = it->second;
        continue;
      }
      const double J_e = (nodes.J_node[c.node(t, 0)] + nodes.J_node[c.node(t, 1)] + nodes.J_node[c.node(t, 2)]) / 3.0;
      c.measure[t] = signed_area(nodes.position_n(c.node(t, 0)), nodes.position_n(c.node(t, 1)), nodes.position_n(c.node(t, 2))) / J_e;
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
        b = with_volume_ratio(b, domain_nodal_jacobian(nodes, e, k));
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
