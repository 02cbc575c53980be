#include "engine/methods/pfem/pfem_remesh.hpp"
#include "engine/methods/pfem/point_history_transfer.hpp"

#include <algorithm>
#include <map>
#include <optional>

#include "engine/core/errors.hpp"
#include "engine/mesh/colouring.hpp"
#include "engine/methods/model/build_boundary_conditions.hpp"
#include "engine/methods/pfem/domain_transfer.hpp"
#include "engine/methods/pfem/inlet_flow.hpp"
#include "engine/methods/pfem/particle_edits.hpp"
#include "systems/assemble/compute_geometry.hpp"
#include "systems/assemble/elements/tri3.hpp"
#include "systems/assemble/elements/tri6.hpp"
#include "systems/update/lumped_mass.hpp"

namespace loom {
namespace {

using Triple = std::array<Index, 3>;

Triple sorted(Index a, Index b, Index c) {
  Triple t{a, b, c};
  std::sort(t.begin(), t.end());
  return t;
}

double corner_area(const Nodes<2>& nodes, const std::vector<Index>& triangles) {
  double area = 0.0;
  for (std::size_t t = 0; t < triangles.size(); t += 3) {
    const Vec2 a = nodes.position_n(triangles[t]), b = nodes.position_n(triangles[t + 1]), c = nodes.position_n(triangles[t + 2]);
    area += 0.5 * ((b - a).x() * (c - a).y() - (c - a).x() * (b - a).y());
  }
  return area;
}

// Position in B_n of point q of cell c (3-point rules: point q sits nearest corner q).
Vec2 quad_point_position(const Nodes<2>& nodes, const Cells& cells, int per_cell, Index c, int q) {
  const Index* n = cells.cell_nodes(c);
  if (per_cell == 1) return (nodes.position_n(n[0]) + nodes.position_n(n[1]) + nodes.position_n(n[2])) / 3.0;
  const double* l = kTri3Rule3[q];
  if (cells.stride == 3) return l[0] * nodes.position_n(n[0]) + l[1] * nodes.position_n(n[1]) + l[2] * nodes.position_n(n[2]);
  const Tri6Values N = tri6_values(l[0], l[1], l[2]);
  Vec2 x = Vec2::Zero();
  for (int a = 0; a < 6; ++a) x += N[a] * nodes.position_n(n[a]);
  return x;
}

// Every nodal column of node `to` set to the mean of nodes a and b (a re-created mid-node).
void set_midpoint(Nodes<2>& nodes, Index to, Index a, Index b) {
  nodes.for_each_column([&](const char*, auto& col) {
    if (col.used()) col[to] = 0.5 * (col[a] + col[b]);
  });
}

// What the state transfer needs of the old mesh: its quadrature points (positions in B_n and F_n, the first
// point of each cell) and its integration domains' history. Taken before the particle set changes, since that
// renumbers the nodes and drops the mid-nodes.
struct OldMesh {
  std::vector<Vec2> x;
  std::vector<Mat3> F;
  std::vector<Mat3> be;                      // hencky_perzyna's b^e_n (I at points without history)
  std::vector<Formulation> with_history;     // the blocks that carry it
  std::map<std::pair<Index, Index>, Index> first_point;  // (block, cell) -> index of its first point in x
  DomainSnapshot<2> domains;
};

OldMesh snapshot_old_mesh(const FemModel& m) {
  OldMesh old;
  for (std::size_t k = 0; k < m.cells.size(); ++k) {
    const QuadPoints<2>& q = m.quad[k];
    for (Index c = 0; c < m.cells[k].size(); ++c) {
      old.first_point[{Index(k), c}] = Index(old.x.size());
      for (int p = 0; p < q.per_cell; ++p) {
        old.x.push_back(quad_point_position(m.nodes, m.cells[k], q.per_cell, c, p));
        old.F.push_back(q.F_n[c * q.per_cell + p]);
        old.be.push_back(q.be_n.used() ? q.be_n[c * q.per_cell + p] : Mat3::Identity());
      }
    }
  }
  old.with_history = formulations_with_history(m.cells, m.quad);
  old.domains = snapshot_domains(m.edges, m.cells);  // es_pfem: the domains' history
  return old;
}

// Inserts, removes and adds inflow particles as planned; the old mesh is snapshot first and its domain keys
// renumbered. Returns whether the particle set changed.
bool change_particles(const PfemSettings& settings, double t_n, PfemTopology& topo, FemModel& m, std::optional<OldMesh>& old,
                      RemeshReport& report) {
  if (!settings.edits.active() && m.scene.inlets.empty()) return false;
  ParticleSetChange change(topo);
  plan_particle_edits(settings.edits, topo, m.nodes, fixed_particles(topo, m.bc), change);
  plan_inflow(m.scene.inlets, t_n, m.nodes, topo, change);
  if (change.empty()) return false;
  old = snapshot_old_mesh(m);
  const std::vector<Index> old_to_new = apply_particle_change(change, topo, m);
  renumber_domain_snapshot(old_to_new, old->domains);
  report.inserted = Index(change.add.size());
  report.removed = change.n_removed();
  return true;
}

}  // namespace

PfemSettings pfem_settings_of(const SceneSpec& scene) {
  PfemSettings s;
  const PfemSpec& p = scene.pfem;
  s.remesh.alpha = p.alpha, s.remesh.l_char = p.lchar, s.remesh.local = p.local;
  s.remesh_3d.alpha = p.alpha, s.remesh_3d.l_char = p.lchar, s.remesh_3d.local = p.local;
  s.remesh_3d.keep_delaunay = p.keep_delaunay, s.remesh_3d.repair = p.repair, s.remesh_3d.flip_quality = p.flip_quality;
  s.map.scheme = p.btm ? MapScheme::btm : MapScheme::cpm;
  s.map.iso = p.iso == 0 ? IsoMode::iso0 : p.iso == 1 ? IsoMode::iso1 : IsoMode::iso2;
  s.every = p.every;
  s.remesh.surface = p.constrained_surface ? SurfaceMode::constrained : SurfaceMode::alpha;
  s.edits = {p.insert_above, p.remove_below, {}};
  for (const WallSpec& w : scene.walls)
    if (w.spacing > 0.0)
      for (const auto& [point, normal] : w.planes)
        s.edits.graded.push_back({Vec2(point.head<2>()), Vec2(normal.head<2>()), w.spacing, w.body, w.spacing_ramp});
  return s;
}

PfemTopology initial_topology(const FemModel& m) {
  PfemTopology topo;
  const std::size_t n_bodies = m.scene.bodies.size();
  topo.points_of_body.resize(n_bodies);
  topo.triangles.resize(n_bodies);
  topo.boundary.resize(n_bodies);
  // Corners are the nodes used as a cell's first three nodes; build_mesh numbers them first.
  std::vector<char> corner(std::size_t(m.nodes.size()), 0);
  for (const Cells& cb : m.cells)
    for (Index c = 0; c < cb.size(); ++c) {
      for (int a = 0; a < 3; ++a) corner[std::size_t(cb.node(c, a))] = 1;
      for (int a = 0; a < 3; ++a) topo.triangles[std::size_t(cb.body[c])].push_back(cb.node(c, a));
    }
  topo.n_points = Index(std::count(corner.begin(), corner.end(), 1));
  for (Index i = 0; i < topo.n_points; ++i) {
    LOOM_ASSERT(corner[std::size_t(i)], "corner nodes must come first");
    topo.points_of_body[std::size_t(m.node_body[std::size_t(i)])].push_back(i);
  }
  for (std::size_t b = 0; b < n_bodies; ++b) topo.boundary[b] = boundary_of(topo.triangles[b]);
  // h0 of particle insertion and removal: remesh.spacing, or the mean edge length of the body's initial mesh.
  topo.spacing.assign(n_bodies, m.scene.pfem.spacing);
  for (std::size_t b = 0; b < n_bodies && m.scene.pfem.spacing <= 0.0; ++b) {
    double sum = 0.0;
    const auto& t = topo.triangles[b];
    for (std::size_t k = 0; k < t.size(); k += 3)
      for (int e = 0; e < 3; ++e) sum += (m.nodes.X[t[k + std::size_t(e)]] - m.nodes.X[t[k + std::size_t((e + 1) % 3)]]).norm();
    topo.spacing[b] = t.empty() ? 0.0 : sum / double(t.size());  // interior edges counted twice, boundary edges once
  }
  topo.inlets.assign(m.scene.inlets.size(), InletState{});
  // Loads on the particles: linear edge functions, since mid-nodes do not persist (a quadratic edge's
  // mid-node load would vanish with it).
  topo.tractions = m.bc.traction_edges;
  for (auto& e : topo.tractions) e.mid = kNoIndex;
  return topo;
}

RemeshReport remesh_model(const PfemSettings& settings, double t_n, PfemTopology& topo, FemModel& m, Timers& timers) {
  RemeshReport report;
  const std::size_t n_bodies = m.scene.bodies.size();
  for (std::size_t b = 0; b < n_bodies; ++b) report.area_before += corner_area(m.nodes, topo.triangles[b]);

  // 0. Particles inserted, removed or poured in, with the previous mesh edited to match.
  ScopedTimer edit(timers, "remesh/change_particles");
  std::optional<OldMesh> old;
  const bool particles_changed = change_particles(settings, t_n, topo, m, old, report);
  edit.stop();
  ScopedTimer triangulate(timers, "remesh/triangulate");

  // 1. New corner triangles of every body (local to the body's particles, then global).
  std::vector<std::vector<Index>> triangles(n_bodies);
  std::vector<std::vector<char>> gap(n_bodies);  // per triangle: it fills a gap outside the previous boundary
  for (std::size_t b = 0; b < n_bodies; ++b) {
    const auto& pts = topo.points_of_body[b];
    std::map<Index, Index> local;
    std::vector<Vec2> x(pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) local[pts[k]] = Index(k), x[k] = m.nodes.position_n(pts[k]);
    auto to_local = [&](Index g) { return local.at(g); };
    std::vector<Index> old_local;
    for (Index g : topo.triangles[b]) old_local.push_back(to_local(g));
    std::vector<Edge> constraints;
    for (const Edge& e : topo.boundary[b]) constraints.push_back({to_local(e[0]), to_local(e[1])});
    std::vector<double> d_avg;
    if (settings.remesh.local) average_neighbour_distance(x, old_local, d_avg);  // eq 17 on the previous mesh
    RemeshSettings remesh = settings.remesh;
    const auto grades_body = [b](const GradedWall& w) { return w.body == kNoIndex || w.body == Index(b); };
    if (std::any_of(settings.edits.graded.begin(), settings.edits.graded.end(), grades_body)) {  // else as ungraded
      const double h0 = topo.spacing[b];
      remesh.spacing_at = [&settings, b, h0](const Vec2& p) { return local_spacing(settings.edits, Index(b), h0, p); };
    }
    RemeshResult r;
    remesh_points(x, constraints, old_local, remesh, d_avg, r);
    // Nothing to solve on, and halving the step cannot bring the triangles back: stop at once.
    LOOM_CHECK(!r.triangles.empty() || pts.empty(), RunError,
               "remesh: the alpha shape (remesh.alpha = " << settings.remesh.alpha << ", l_char "
                   << (settings.remesh.local ? std::string("local") : std::to_string(settings.remesh.l_char))
                   << ") removed every triangle of body \"" << m.scene.bodies[b].name
                   << "\": raise remesh.alpha (triangles whose circumradius exceeds alpha * l_char are removed)");
    for (Index v : r.triangles) triangles[b].push_back(pts[std::size_t(v)]);
    gap[b] = r.merged_face;
    report.rejected += r.rejected, report.isolated += r.isolated, report.triangles += r.triangles.size() / 3;
    report.merged += r.merged, report.crossings += r.crossings;
    report.area_after += r.area;
  }

  // 2. Did the connectivity change?
  std::map<Triple, std::pair<Index, Index>> old_cell;  // corner set -> (block, cell)
  for (std::size_t k = 0; k < m.cells.size(); ++k)
    for (Index c = 0; c < m.cells[k].size(); ++c) {
      const Index* n = m.cells[k].cell_nodes(c);
      old_cell[sorted(n[0], n[1], n[2])] = {Index(k), c};
    }
  report.changed = particles_changed;
  for (std::size_t b = 0; b < n_bodies && !report.changed; ++b) {
    if (triangles[b].size() != topo.triangles[b].size()) report.changed = true;
    for (std::size_t t = 0; t < triangles[b].size() && !report.changed; t += 3)
      if (!old_cell.count(sorted(triangles[b][t], triangles[b][t + 1], triangles[b][t + 2]))) report.changed = true;
  }
  triangulate.stop();
  bool quadratic = false;
  for (const Cells& cb : m.cells) quadratic = quadratic || cb.type == CellType::tri6;
  if (!report.changed && !quadratic) return report;  // nothing to transfer, nothing to rebuild
  ScopedTimer rebuild(timers, "remesh/rebuild_cells");

  // 3. Old quadrature points: positions in B_n and histories (already taken if the particle set changed).
  if (!old) old = snapshot_old_mesh(m);
  const std::vector<Vec2>& old_x = old->x;
  const std::vector<Mat3>& old_F = old->F;
  const auto& first_point = old->first_point;
  const DomainSnapshot<2>& old_domains = old->domains;
  std::vector<Cells> old_cells;
  if (!report.changed) {
    for (std::size_t b = 0; b < n_bodies; ++b) triangles[b] = topo.triangles[b], gap[b].assign(triangles[b].size() / 3, 0);  // keep the cell order
  }
  old_cells.swap(m.cells);

  // 4. New cells; mid-nodes dropped and re-created at straight midpoints with interpolated data.
  m.nodes.resize(topo.n_points);
  m.node_body.resize(std::size_t(topo.n_points));
  std::vector<std::vector<char>> gap_cells(n_bodies);  // per cell block (at most one per body)
  std::map<std::pair<Index, Index>, Index> mid_of;
  for (std::size_t b = 0; b < n_bodies; ++b) {
    const Formulation element = m.scene.bodies[b].element;
    const CellType type = cell_type_of(element);
    Cells* block = nullptr;
    for (auto& c : m.cells)
      if (c.formulation == element) block = &c;
    if (!block) {
      m.cells.emplace_back(type, element);
      block = &m.cells.back();
    }
    std::vector<char>& block_gap = gap_cells[std::size_t(block - m.cells.data())];
    block_gap.insert(block_gap.end(), gap[b].begin(), gap[b].end());
    for (std::size_t t = 0; t < triangles[b].size(); t += 3) {
      const Index v[3] = {triangles[b][t], triangles[b][t + 1], triangles[b][t + 2]};
      block->nodes.values().insert(block->nodes.values().end(), v, v + 3);
      if (type == CellType::tri6)
        for (int s = 0; s < 3; ++s) {
          const Index a = v[s], c = v[(s + 1) % 3];
          const auto key = std::make_pair(std::min(a, c), std::max(a, c));
          auto [it, inserted] = mid_of.emplace(key, m.nodes.size());
          if (inserted) {
            m.nodes.resize(m.nodes.size() + 1);
            set_midpoint(m.nodes, it->second, a, c);
            m.node_body.push_back(Index(b));
          }
          block->nodes.values().push_back(it->second);
        }
      block->body.values().push_back(Index(b));
    }
  }
  for (auto& c : m.cells) colour_cells(c, m.nodes.size());
  allocate_quad_points(m.cells, m.quad);
  use_history_columns(old->with_history, m.cells, m.quad);
  LOOM_CHECK(compute_geometry(m.nodes, m.cells, m.quad) == 0, RunError, "remesh: the new mesh has inverted cells");

  rebuild.stop();
  ScopedTimer transfer(timers, "remesh/map");
  // 5. Transfer of the history: cells that kept their corners copy point by point (the points of 3-point
  //    rules follow their corner), the others are mapped (CPM / BTM).
  std::vector<Vec2> new_x;
  std::vector<Index> copy_from;
  for (std::size_t k = 0; k < m.cells.size(); ++k) {
    const Cells& cb = m.cells[k];
    const int per_cell = m.quad[k].per_cell;
    for (Index c = 0; c < cb.size(); ++c) {
      const Index* n = cb.cell_nodes(c);
      auto it = old_cell.find(sorted(n[0], n[1], n[2]));
      for (int p = 0; p < per_cell; ++p) {
        new_x.push_back(quad_point_position(m.nodes, cb, per_cell, c, p));
        Index from = kNoIndex;
        if (it != old_cell.end() && old_cells[std::size_t(it->second.first)].formulation == cb.formulation) {
          const Cells& oc = old_cells[std::size_t(it->second.first)];
          int q = 0;  // the old point that sits at the same corner
          if (per_cell == 3)
            while (oc.node(it->second.second, q) != n[p]) ++q;
          from = first_point.at(it->second) + q;
        }
        copy_from.push_back(from);
      }
    }
  }
  std::vector<Mat3> new_F;
  map_state(old_x, old_F, new_x, copy_from, settings.map, new_F, report.map);
  std::size_t next = 0;
  for (auto& q : m.quad)
    for (Index p = 0; p < q.size(); ++p) q.F_n[p] = q.F[p] = new_F[next++];
  transfer_point_history(old_x, old->be, new_x, copy_from, settings.map, isochoric_plastic_flow(m.scene), m.quad);
  if (!m.edges.empty()) {
    // Dynamic runs carry each particle's mass in lumped_mass: the new triangles share it out (mass conserved).
    std::vector<double> density;
    for (const BodyMaterial& b : m.materials) density.push_back(b.density);
    gap_cells.resize(m.cells.size());
    report.new_material_mass =
        transfer_domains(old_domains, m.nodes, m.cells, m.j_projection, m.edges, m.nodes.lumped_mass.used() ? &density : nullptr, &gap_cells).new_material_mass;
  }
  if (m.nodes.lumped_mass.used()) compute_lumped_mass(m.cells, m.quad, m.materials, m.nodes);

  transfer.stop();
  ScopedTimer numbering(timers, "remesh/rebuild_system");
  rebuild_system(m, topo, report.changed);
  for (std::size_t b = 0; b < n_bodies; ++b) {
    topo.triangles[b] = triangles[b];
    topo.boundary[b] = boundary_of(triangles[b]);
  }
  return report;
}

void rebuild_system(FemModel& m, const PfemTopology& topo, bool connectivity_changed) {
  // Boundary conditions, dofs, sparsity and scatter on the new mesh (the symbolic factorization is
  // redone because the pattern version changes).
  const int per_node = m.system.dofs.per_node;
  m.bc = build_boundary_conditions(m.scene, m.nodes, m.cells, m.node_body, m.regions, per_node, /*tie_mid_nodes=*/true, &topo.tractions);
  add_inlet_rows(m.scene.inlets, topo, m.bc);
  std::vector<DofKind> kinds = dof_kinds(m.bc, m.cells, m.nodes.size(), per_node);
  std::vector<char> in_cell(std::size_t(m.nodes.size()), 0);
  for (const Cells& cb : m.cells)
    for (Index v : cb.nodes) in_cell[std::size_t(v)] = 1;
  for (Index i = 0; i < m.nodes.size(); ++i)
    if (!in_cell[std::size_t(i)])  // an isolated particle carries no equation
      for (int d = 0; d < per_node; ++d) kinds[std::size_t(i * per_node + d)] = DofKind::absent;
  if (connectivity_changed || m.system.dofs.n_dofs() != Index(kinds.size()) || m.system.dofs.kind != kinds) {
    m.system.dofs.build(per_node, std::move(kinds), m.bc.ties);
    std::vector<const Cells*> blocks;
    for (const auto& c : m.cells) blocks.push_back(&c);
    for (const auto& e : m.edges) blocks.push_back(&e.stencil);
    build_pattern(blocks, m.system.dofs, m.system.pattern);
  }
  m.system.scatter.resize(m.cells.size());
  for (std::size_t k = 0; k < m.cells.size(); ++k) build_scatter(m.cells[k], m.system.dofs, m.system.pattern, m.system.scatter[k]);
  m.system.domain_scatter.resize(m.edges.size());
  for (std::size_t e = 0; e < m.edges.size(); ++e) build_scatter(m.edges[e].stencil, m.system.dofs, m.system.pattern, m.system.domain_scatter[e]);
  m.system.resize_vectors();
}

}  // namespace loom
