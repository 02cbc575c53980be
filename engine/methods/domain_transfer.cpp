#include "engine/methods/domain_transfer.hpp"

#include <algorithm>
#include <cmath>

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
  std::vector<Vec2> new_mid;
  std::vector<Index> copy_from;
  for (const Edges<2>& e : edges)
    for (Index k = 0; k < e.size(); ++k) {
      new_mid.push_back(e.midpoint[k]);
      const auto it = old.domain_of.find(key_of(e, k));
      copy_from.push_back(it == old.domain_of.end() ? kNoIndex : it->second);
    }
  std::vector<Mat3> be;
  MapStats map_stats;
  map_state(old.midpoint, old.be, new_mid, copy_from, MapSettings{}, be, map_stats);
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
