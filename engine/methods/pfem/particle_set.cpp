#include "engine/methods/pfem/particle_set.hpp"

#include <algorithm>

#include "engine/core/errors.hpp"
#include "engine/mesh/triangle_geometry.hpp"
#include "systems/remesh/remesh.hpp"

namespace loom {

Index ParticleSetChange::n_removed() const { return Index(std::count(remove.begin(), remove.end(), 1)); }

std::vector<Index> apply_particle_change(const ParticleSetChange& change, PfemTopology& topo, FemModel& m) {
  const Index n_old = topo.n_points, n_added = Index(change.add.size());
  // 1. Numbering: kept particles in order, then the new ones.
  std::vector<Index> old_to_new(std::size_t(n_old), kNoIndex);
  Index next = 0;
  for (Index i = 0; i < n_old; ++i)
    if (!change.remove[std::size_t(i)]) old_to_new[std::size_t(i)] = next++;
  const Index n_kept = next, n_new = n_kept + n_added;
  auto extended = [&](Index v) { return v < n_old ? old_to_new[std::size_t(v)] : n_kept + (v - n_old); };

  // Mass of removed particles to the particle each merges into (read before the compaction below overwrites it).
  const bool masses = m.nodes.lumped_mass.used();
  std::vector<double> merged_mass(std::size_t(n_kept), 0.0);
  if (masses)
    for (Index i = 0; i < n_old; ++i)
      if (change.remove[std::size_t(i)] && change.merge_into[std::size_t(i)] != kNoIndex)
        merged_mass[std::size_t(old_to_new[std::size_t(change.merge_into[std::size_t(i)])])] += m.nodes.lumped_mass[i];

  // 2. Nodal columns: kept particles moved down (in place: new <= old), mid-nodes dropped, new particles appended.
  m.nodes.for_each_column([&](const char*, auto& col) {
    if (!col.used()) return;
    for (Index i = 0; i < n_old; ++i)
      if (old_to_new[std::size_t(i)] != kNoIndex && old_to_new[std::size_t(i)] != i) col[old_to_new[std::size_t(i)]] = col[i];
  });
  // Interpolation reads the old particles, which are now at their new indices (a midpoint's ends are never removed).
  std::vector<Index> body(static_cast<std::size_t>(n_new));
  for (Index i = 0; i < n_old; ++i)
    if (old_to_new[std::size_t(i)] != kNoIndex) body[std::size_t(old_to_new[std::size_t(i)])] = m.node_body[std::size_t(i)];
  m.nodes.resize(n_kept);
  m.nodes.resize(n_new);  // fresh entries: zero, phi and J one
  for (Index k = 0; k < n_added; ++k) {
    const NewParticle& p = change.add[std::size_t(k)];
    const Index to = n_kept + k;
    body[std::size_t(to)] = p.body;
    if (p.a == kNoIndex) {
      m.nodes.X[to] = p.x;
      if (m.nodes.v.used()) m.nodes.v[to] = m.nodes.v_n[to] = p.v;
      continue;
    }
    const Index a = extended(p.a), b = extended(p.b);
    LOOM_ASSERT(a != kNoIndex && b != kNoIndex, "a midpoint's ends stay");
    m.nodes.for_each_column([&](const char*, auto& col) {
      if (col.used()) col[to] = 0.5 * (col[a] + col[b]);
    });
    // Contact with a stick wall: the midpoint is held where both ends are, at the mean of their anchors.
    if (m.nodes.in_contact.used()) {
      const bool both = m.nodes.in_contact[a] != 0.0 && m.nodes.in_contact[b] != 0.0;
      m.nodes.in_contact[to] = both ? 1.0 : 0.0;
      if (!both) m.nodes.contact_point[to] = Vec2::Zero();
    }
  }
  m.node_body = body;
  if (masses) {
    for (Index i = 0; i < n_kept; ++i) m.nodes.lumped_mass[i] += merged_mass[std::size_t(i)];
    for (Index i = n_kept; i < n_new; ++i) m.nodes.lumped_mass[i] = 0.0;
    for (std::size_t t = 0; t + 2 < change.fresh_triangles.size(); t += 3) {
      const Index c[3] = {extended(change.fresh_triangles[t]), extended(change.fresh_triangles[t + 1]), extended(change.fresh_triangles[t + 2])};
      const double share = m.materials[std::size_t(body[std::size_t(c[0])])].density *
                           std::abs(signed_area(m.nodes.position_n(c[0]), m.nodes.position_n(c[1]), m.nodes.position_n(c[2]))) / 3.0;
      for (Index v : c) m.nodes.lumped_mass[v] += share;
    }
  }

  // 3. Everything else that holds particle indices.
  topo.n_points = n_new;
  for (std::size_t b = 0; b < topo.triangles.size(); ++b) {
    topo.triangles[b].clear();
    for (Index v : change.triangles[b]) {
      const Index w = extended(v);
      LOOM_ASSERT(w != kNoIndex, "no triangle holds a removed particle");
      topo.triangles[b].push_back(w);
    }
    topo.boundary[b] = boundary_of(topo.triangles[b]);
    topo.points_of_body[b].clear();
  }
  for (Index i = 0; i < n_new; ++i) topo.points_of_body[std::size_t(body[std::size_t(i)])].push_back(i);
  std::vector<TractionEdge<2>> tractions;
  for (TractionEdge<2> e : topo.tractions) {
    e.a = extended(e.a), e.b = extended(e.b);
    if (e.a != kNoIndex && e.b != kNoIndex) tractions.push_back(e);
  }
  topo.tractions = tractions;
  for (std::size_t k = 0; k < topo.inlets.size(); ++k) {
    std::vector<Index> row;
    for (Index v : change.inlet_row_set[k] ? change.inlet_rows[k] : topo.inlets[k].row)
      if (extended(v) != kNoIndex) row.push_back(extended(v));
    topo.inlets[k].row = row;
  }
  for (auto& regions : m.regions)
    for (MeshRegion& r : regions) {
      std::vector<Index> corners;
      for (Index v : r.corners)
        if (v < n_old && old_to_new[std::size_t(v)] != kNoIndex) corners.push_back(old_to_new[std::size_t(v)]);
      r.corners = corners;
      std::vector<std::array<Index, 2>> edges;
      for (auto e : r.edges) {
        if (e[0] >= n_old || e[1] >= n_old) continue;
        e = {old_to_new[std::size_t(e[0])], old_to_new[std::size_t(e[1])]};
        if (e[0] != kNoIndex && e[1] != kNoIndex) edges.push_back({std::min(e[0], e[1]), std::max(e[0], e[1])});
      }
      r.edges = edges;
    }
  for (Cells& cb : m.cells) {
    const int corners = corners_of_stride(cb.stride);
    for (Index c = 0; c < cb.size(); ++c)
      for (int a = 0; a < cb.stride; ++a) {
        Index& v = cb.nodes[c * cb.stride + a];
        v = a < corners && v < n_old ? old_to_new[std::size_t(v)] : kNoIndex;
      }
  }
  return old_to_new;
}

}  // namespace loom
