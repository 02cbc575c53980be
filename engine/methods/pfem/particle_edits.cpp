#include "engine/methods/pfem/particle_edits.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <set>

#include "engine/mesh/triangle_geometry.hpp"

namespace loom {
namespace {

using EdgeKey = std::uint64_t;
EdgeKey key_of(Index a, Index b) { return (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b)); }

struct MeshEdge {
  double length;
  Index a, b;
  bool operator<(const MeshEdge& o) const { return length != o.length ? length < o.length : std::make_pair(a, b) < std::make_pair(o.a, o.b); }
};

std::vector<MeshEdge> edges_of(const std::vector<Index>& t, const std::vector<Vec2>& x, const std::vector<char>& dead) {
  std::set<EdgeKey> seen;
  std::vector<MeshEdge> out;
  for (std::size_t k = 0; k < t.size() / 3; ++k) {
    if (!dead.empty() && dead[k]) continue;
    for (int s = 0; s < 3; ++s) {
      const Index a = t[3 * k + std::size_t(s)], b = t[3 * k + std::size_t((s + 1) % 3)];
      if (seen.insert(key_of(a, b)).second) out.push_back({(x[std::size_t(a)] - x[std::size_t(b)]).norm(), std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The length below which an edge is removed and above which it is split, per edge (its midpoint's spacing).
struct EdgeLimits {
  const ParticleEditSettings& settings;
  Index body;
  double h0;
  const std::vector<Vec2>& x;
  bool uniform() const { return settings.graded.empty(); }
  double spacing(const MeshEdge& e) const {
    return uniform() ? h0 : local_spacing(settings, body, h0, 0.5 * (x[std::size_t(e.a)] + x[std::size_t(e.b)]));
  }
};

// Removal on one body's triangles `t` (edited in place; dead triangles flagged).
void plan_removals(const EdgeLimits& limits, const std::vector<Edge>& boundary, const std::vector<char>& fixed, std::vector<Index>& t,
                   std::vector<char>& dead, std::vector<char>& remove, std::vector<Index>& merge_into) {
  const std::vector<Vec2>& x = limits.x;
  std::vector<char> on_surface(x.size(), 0), touched(x.size(), 0);
  std::set<EdgeKey> surface_edge;
  for (const Edge& e : boundary) on_surface[std::size_t(e[0])] = on_surface[std::size_t(e[1])] = 1, surface_edge.insert(key_of(e[0], e[1]));
  std::map<Index, std::vector<std::size_t>> incident;
  for (std::size_t k = 0; k < t.size() / 3; ++k)
    for (int s = 0; s < 3; ++s) incident[t[3 * k + std::size_t(s)]].push_back(k);
  for (const MeshEdge& e : edges_of(t, x, dead)) {
    // Shortest first: with one spacing the first edge long enough ends the search.
    if (!(e.length < limits.settings.remove_below * limits.spacing(e))) {
      if (limits.uniform()) break;
      continue;
    }
    Index keep = e.a, gone = e.b;
    if (touched[std::size_t(keep)] || touched[std::size_t(gone)]) continue;
    const bool fixed_a = fixed[std::size_t(e.a)], fixed_b = fixed[std::size_t(e.b)];
    if (fixed_a && fixed_b) continue;
    if (fixed_a) keep = e.a, gone = e.b;
    else if (fixed_b) keep = e.b, gone = e.a;
    else if (on_surface[std::size_t(e.a)] != on_surface[std::size_t(e.b)]) keep = on_surface[std::size_t(e.a)] ? e.a : e.b, gone = keep == e.a ? e.b : e.a;
    else keep = e.a, gone = e.b;  // the higher index goes
    // A surface particle goes only into a neighbour along the surface (else two surfaces would be pinched).
    if (on_surface[std::size_t(gone)] && !surface_edge.count(key_of(e.a, e.b))) continue;
    // Its triangles, given to `keep`, must stay counter-clockwise.
    bool valid = true;
    for (std::size_t k : incident[gone]) {
      if (dead[k]) continue;
      const Index* c = &t[3 * k];
      if (c[0] == keep || c[1] == keep || c[2] == keep) continue;
      Vec2 p[3];
      for (int s = 0; s < 3; ++s) p[s] = x[std::size_t(c[s] == gone ? keep : c[s])];
      valid = valid && signed_area(p[0], p[1], p[2]) > 0.0;
    }
    if (!valid) continue;
    for (std::size_t k : incident[gone]) {
      if (dead[k]) continue;
      Index* c = &t[3 * k];
      if (c[0] == keep || c[1] == keep || c[2] == keep) {
        dead[k] = 1;
        continue;
      }
      for (int s = 0; s < 3; ++s)
        if (c[s] == gone) c[s] = keep;
    }
    remove[std::size_t(gone)] = 1;
    merge_into[std::size_t(gone)] = keep;
    touched[std::size_t(keep)] = touched[std::size_t(gone)] = 1;
  }
}

}  // namespace

double local_spacing(const ParticleEditSettings& settings, Index b, double h0, const Vec2& x) {
  double h = h0;
  for (const GradedWall& w : settings.graded) {
    if (w.body != kNoIndex && w.body != b) continue;
    const double d = std::max(0.0, (x - w.point).dot(w.normal));
    const double ramp = w.ramp > 0.0 ? w.ramp : h0;
    if (d >= ramp) continue;  // beyond the ramp: exactly h0 (s + (h0 - s) * 1 may round below it)
    h = std::min(h, w.spacing + (h0 - w.spacing) * (d / ramp));
  }
  return h;
}

std::vector<char> fixed_particles(const PfemTopology& topo, const BoundaryConditions<2>& bc) {
  std::vector<char> fixed(std::size_t(topo.n_points), 0);
  auto mark = [&](Index i) {
    if (i >= 0 && i < topo.n_points) fixed[std::size_t(i)] = 1;
  };
  for (const auto& p : bc.prescribed) mark(p.node);
  for (const auto& e : topo.tractions) mark(e.a), mark(e.b);
  for (const InletState& in : topo.inlets)
    for (Index i : in.row) mark(i);
  return fixed;
}

void plan_particle_edits(const ParticleEditSettings& settings, const PfemTopology& topo, const Nodes<2>& nodes,
                         const std::vector<char>& fixed, ParticleSetChange& change) {
  if (!settings.active()) return;
  const Index n_old = topo.n_points;
  std::vector<Vec2> x(static_cast<std::size_t>(n_old));
  for (Index i = 0; i < n_old; ++i) x[std::size_t(i)] = nodes.position_n(i);
  std::vector<char> in_row(static_cast<std::size_t>(n_old), 0);
  for (const InletState& in : topo.inlets)
    for (Index i : in.row) in_row[std::size_t(i)] = 1;
  for (std::size_t b = 0; b < change.triangles.size(); ++b) {
    std::vector<Index>& t = change.triangles[b];
    const EdgeLimits limits{settings, Index(b), topo.spacing[b], x};
    std::vector<char> dead(t.size() / 3, 0);
    const Index removed_before = change.n_removed();
    if (settings.remove_below > 0.0) plan_removals(limits, topo.boundary[b], fixed, t, dead, change.remove, change.merge_into);
    // Insertion: the midpoints of the long edges that remain. Positions of new points extend x for the splits.
    std::map<EdgeKey, Index> mid;
    if (settings.insert_above > 0.0) {
      const std::vector<MeshEdge> edges = edges_of(t, x, dead);
      for (auto e = edges.rbegin(); e != edges.rend(); ++e) {
        if (!(e->length > settings.insert_above * limits.spacing(*e))) {
          if (limits.uniform()) break;  // longest first, as above
          continue;
        }
        if (in_row[std::size_t(e->a)] || in_row[std::size_t(e->b)]) continue;
        mid[key_of(e->a, e->b)] = n_old + Index(change.add.size());
        change.add.push_back({Index(b), e->a, e->b, Vec2::Zero(), Vec2::Zero()});
      }
    }
    if (mid.empty() && change.n_removed() == removed_before) continue;
    change.mark_triangles_changed();
    auto position = [&](Index v) {
      if (v < n_old) return x[std::size_t(v)];
      const NewParticle& p = change.add[std::size_t(v - n_old)];
      return Vec2(0.5 * (x[std::size_t(p.a)] + x[std::size_t(p.b)]));
    };
    auto midpoint = [&](Index a, Index c) {
      const auto it = mid.find(key_of(a, c));
      return it == mid.end() ? kNoIndex : it->second;
    };
    // Split every live triangle along its split edges: 1 -> 2, 2 -> 3 (the shorter diagonal), 3 -> 4 triangles.
    std::vector<Index> out;
    for (std::size_t k = 0; k < t.size() / 3; ++k) {
      if (dead[k]) continue;
      std::array<Index, 3> c{t[3 * k], t[3 * k + 1], t[3 * k + 2]};
      std::array<Index, 3> m{midpoint(c[0], c[1]), midpoint(c[1], c[2]), midpoint(c[2], c[0])};  // m[s] on side (s, s+1)
      const int splits = int(m[0] != kNoIndex) + int(m[1] != kNoIndex) + int(m[2] != kNoIndex);
      if (splits == 0) {
        out.insert(out.end(), c.begin(), c.end());
        continue;
      }
      if (splits == 3) {
        out.insert(out.end(), {c[0], m[0], m[2], m[0], c[1], m[1], m[2], m[1], c[2], m[0], m[1], m[2]});
        continue;
      }
      // Rotate so that side (0, 1) is split and, with two splits, side (2, 0) is the one left whole.
      int r = 0;
      if (splits == 1) {
        while (m[std::size_t(r)] == kNoIndex) ++r;
      } else {
        while (m[std::size_t((r + 2) % 3)] != kNoIndex) ++r;
      }
      std::rotate(c.begin(), c.begin() + r, c.end());
      std::rotate(m.begin(), m.begin() + r, m.end());
      if (splits == 1) {
        out.insert(out.end(), {c[0], m[0], c[2], m[0], c[1], c[2]});
      } else {
        out.insert(out.end(), {m[0], c[1], m[1]});
        if ((position(c[0]) - position(m[1])).norm() <= (position(m[0]) - position(c[2])).norm())
          out.insert(out.end(), {c[0], m[0], m[1], c[0], m[1], c[2]});
        else
          out.insert(out.end(), {c[0], m[0], c[2], m[0], m[1], c[2]});
      }
    }
    t = out;
  }
}

}  // namespace loom
