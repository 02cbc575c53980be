// The PFEM remesh stage on tetrahedra (methods pfem and es_pfem, scene.dimension = 3; spec 3d-free-surface §3-§5): the
// 2D stage of pfem_remesh.cpp with particle insertion (particle_insertion_3d.hpp) and inflow (inlet_flow_3d.hpp), without
// removal. Before each step the particles at
// X_n are remeshed (systems/remesh/remesh_3d.hpp: the previous mesh plays the role of 2D's boundary constraints),
// tet10 mid-nodes are dropped and re-created on the straight edges with averaged nodal columns, the quadrature
// history is copied for surviving cells and mapped (CPM / BTM-ISO0/1/2 on a Delaunay_triangulation_3 of the old
// points) for new ones, es_pfem's face domains are rebuilt with their b^e kept or projected and the new tetrahedra's
// reference volumes shared out (domain_transfer.hpp), and the dofs, sparsity and scatters are rebuilt where the
// connectivity changed.
#include <algorithm>
#include <map>

#include "engine/core/errors.hpp"
#include "engine/mesh/colouring.hpp"
#include "engine/mesh/tet_adjacency.hpp"
#include "engine/methods/model/build_boundary_conditions.hpp"
#include "engine/methods/model/build_solid_3d.hpp"
#include "engine/methods/pfem/domain_transfer.hpp"
#include "engine/methods/pfem/inlet_flow_3d.hpp"
#include "engine/methods/pfem/particle_insertion_3d.hpp"
#include "engine/methods/pfem/pfem_remesh.hpp"
#include "engine/methods/pfem/point_history_transfer.hpp"
#include "systems/assemble/compute_geometry.hpp"
#include "systems/assemble/elements/tet10.hpp"
#include "systems/assemble/elements/tet4.hpp"
#include "systems/update/lumped_mass.hpp"

namespace loom {
namespace {

using Quad = std::array<Index, 4>;

Quad sorted_quad(const Index* v) {
  Quad q{v[0], v[1], v[2], v[3]};
  std::sort(q.begin(), q.end());
  return q;
}

double corner_volume(const Nodes<3>& nodes, const std::vector<Index>& tets) {
  double v = 0.0;
  for (std::size_t t = 0; t + 3 < tets.size(); t += 4)
    v += tet_volume(nodes.position_n(tets[t]), nodes.position_n(tets[t + 1]), nodes.position_n(tets[t + 2]), nodes.position_n(tets[t + 3]));
  return v;
}

// Position in B_n of point q of cell c: the centroid (one point), or the four-point rule's point q, which sits
// nearest corner q (tet10: through its quadratic map).
Vec3 quad_point_position(const Nodes<3>& nodes, const Cells& cells, int per_cell, Index c, int q) {
  const Index* n = cells.cell_nodes(c);
  if (per_cell == 1) return (nodes.position_n(n[0]) + nodes.position_n(n[1]) + nodes.position_n(n[2]) + nodes.position_n(n[3])) / 4.0;
  const double* l = kTet4Rule4[q];
  Vec3 x = Vec3::Zero();
  if (cells.stride == 4) {
    for (int a = 0; a < 4; ++a) x += l[a] * nodes.position_n(n[a]);
  } else {
    const Tet10Values N = tet10_values(l);
    for (int a = 0; a < 10; ++a) x += N[a] * nodes.position_n(n[a]);
  }
  return x;
}

// Every nodal column of node `to` set to the mean of nodes a and b (a re-created mid-node).
void set_midpoint(Nodes<3>& nodes, Index to, Index a, Index b) {
  nodes.for_each_column([&](const char*, auto& col) {
    if (col.used()) col[to] = 0.5 * (col[a] + col[b]);
  });
}

// The old mesh's quadrature points (positions in B_n, F_n) and where each cell's first point is.
struct OldPoints {
  std::vector<Vec3> x;
  std::vector<Mat3> F;
  std::vector<Mat3> be;                   // hencky_perzyna's b^e_n (I at points without history)
  std::vector<Formulation> with_history;  // the blocks that carry it
  std::map<Quad, std::pair<Index, Index>> cell_of;  // sorted corners -> (block, cell)
  std::map<std::pair<Index, Index>, Index> first_point;
  DomainSnapshot<3> domains;  // es_pfem: the domains' history
};

OldPoints snapshot(const FemModelT<3>& m) {
  OldPoints old;
  old.domains = snapshot_domains(m.edges, m.cells);
  for (std::size_t k = 0; k < m.cells.size(); ++k) {
    const QuadPoints<3>& q = m.quad[k];
    for (Index c = 0; c < m.cells[k].size(); ++c) {
      old.cell_of[sorted_quad(m.cells[k].cell_nodes(c))] = {Index(k), c};
      old.first_point[{Index(k), c}] = Index(old.x.size());
      for (int p = 0; p < q.per_cell; ++p) {
        old.x.push_back(quad_point_position(m.nodes, m.cells[k], q.per_cell, c, p));
        old.F.push_back(q.F_n[c * q.per_cell + p]);
        old.be.push_back(q.be_n.used() ? q.be_n[c * q.per_cell + p] : Mat3::Identity());
      }
    }
  }
  old.with_history = formulations_with_history(m.cells, m.quad);
  return old;
}

// The new cell blocks (m.cells empty) from the bodies' corner tetrahedra; tet10 mid-nodes re-created after the particles.
// `merged` (per body, per tetrahedron: it fills a gap outside the previous mesh) is gathered per block into gap_cells.
void rebuild_cells(const std::vector<std::vector<Index>>& tets, const std::vector<std::vector<char>>& merged, Index n_points, FemModelT<3>& m,
                   std::vector<std::vector<char>>& gap_cells) {
  m.nodes.resize(n_points);
  m.node_body.resize(std::size_t(n_points));
  std::map<std::pair<Index, Index>, Index> mid_of;
  for (std::size_t b = 0; b < tets.size(); ++b) {
    const Formulation element = m.scene.bodies[b].element;
    const CellType type = element == Formulation::tri6 ? CellType::tet10 : CellType::tet4;
    Cells* block = nullptr;
    for (auto& c : m.cells)
      if (c.formulation == element) block = &c;
    if (!block) {
      m.cells.emplace_back(type, element);
      block = &m.cells.back();
    }
    std::vector<char>& block_gap = gap_cells[std::size_t(block - m.cells.data())];
    block_gap.insert(block_gap.end(), merged[b].begin(), merged[b].end());
    for (std::size_t t = 0; t + 3 < tets[b].size(); t += 4) {
      const Index* v = &tets[b][t];
      block->nodes.values().insert(block->nodes.values().end(), v, v + 4);
      if (type == CellType::tet10)
        for (const auto& e : kTet10Edges) {
          const Index a = v[e[0]], c = v[e[1]];
          auto [it, inserted] = mid_of.emplace(std::make_pair(std::min(a, c), std::max(a, c)), m.nodes.size());
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
}

// New points of surviving cells copy the old point at the same corner; the others are mapped.
void transfer_history(const PfemSettings& settings, const OldPoints& old, const std::vector<Cells>& old_cells, FemModelT<3>& m,
                      MapStats& stats) {
  std::vector<Vec3> new_x;
  std::vector<Index> copy_from;
  for (std::size_t k = 0; k < m.cells.size(); ++k) {
    const Cells& cb = m.cells[k];
    const int per_cell = m.quad[k].per_cell;
    for (Index c = 0; c < cb.size(); ++c) {
      const Index* n = cb.cell_nodes(c);
      const auto it = old.cell_of.find(sorted_quad(n));
      for (int p = 0; p < per_cell; ++p) {
        new_x.push_back(quad_point_position(m.nodes, cb, per_cell, c, p));
        Index from = kNoIndex;
        if (it != old.cell_of.end() && old_cells[std::size_t(it->second.first)].formulation == cb.formulation) {
          const Cells& oc = old_cells[std::size_t(it->second.first)];
          int q = 0;  // the old point at the same corner
          if (per_cell == 4)
            while (oc.node(it->second.second, q) != n[p]) ++q;
          from = old.first_point.at(it->second) + q;
        }
        copy_from.push_back(from);
      }
    }
  }
  std::vector<Mat3> new_F;
  map_state(old.x, old.F, new_x, copy_from, settings.map, new_F, stats);
  std::size_t next = 0;
  for (auto& q : m.quad)
    for (Index p = 0; p < q.size(); ++p) q.F_n[p] = q.F[p] = new_F[next++];
  transfer_point_history(old.x, old.be, new_x, copy_from, settings.map, isochoric_plastic_flow(m.scene), m.quad);
}

}  // namespace

PfemTopology3d initial_topology(const FemModelT<3>& m) {
  PfemTopology3d topo;
  const std::size_t n_bodies = m.scene.bodies.size();
  topo.points_of_body.resize(n_bodies);
  topo.tets.resize(n_bodies);
  topo.surface.resize(n_bodies);
  topo.neighbours.resize(n_bodies);
  std::vector<char> corner(std::size_t(m.nodes.size()), 0);
  for (const Cells& cb : m.cells)
    for (Index c = 0; c < cb.size(); ++c)
      for (int a = 0; a < 4; ++a) {
        corner[std::size_t(cb.node(c, a))] = 1;
        topo.tets[std::size_t(cb.body[c])].push_back(cb.node(c, a));
      }
  topo.n_points = Index(std::count(corner.begin(), corner.end(), 1));
  for (Index i = 0; i < topo.n_points; ++i) {
    LOOM_ASSERT(corner[std::size_t(i)], "corner nodes must come first");
    topo.points_of_body[std::size_t(m.node_body[std::size_t(i)])].push_back(i);
  }
  for (std::size_t b = 0; b < n_bodies; ++b) {
    topo.neighbours[b] = tet_face_neighbours(topo.tets[b]);
    for (const BoundaryFace& f : boundary_faces(topo.tets[b], topo.neighbours[b])) topo.surface[b].push_back(f.nodes);
  }
  // Dead loads on the particles: linear face functions (mid-nodes do not persist).
  topo.tractions = m.bc.traction_faces;
  for (auto& f : topo.tractions) f.nodes[3] = f.nodes[4] = f.nodes[5] = kNoIndex;
  topo.spacing = initial_spacing_3d(topo, m.nodes);
  topo.inlets.assign(m.scene.inlets.size(), InletState{});
  return topo;
}

RemeshReport remesh_model(const PfemSettings& settings, double t_n, PfemTopology3d& topo, FemModelT<3>& m, Timers& timers) {
  RemeshReport report;
  const std::size_t n_bodies = m.scene.bodies.size();
  for (std::size_t b = 0; b < n_bodies; ++b) report.area_before += corner_volume(m.nodes, topo.tets[b]);

  // 0. Particles inserted where the previous mesh's edges grew long (its cells split with them).
  if (settings.edits.insert_above > 0.0) {
    ScopedTimer edit(timers, "remesh/change_particles");
    report.inserted = insert_particles_3d(settings.edits.insert_above, topo, m);
  }
  // ... and new layers poured in at the inlets (their cells added to the previous mesh).
  bool released = false;
  if (!m.scene.inlets.empty()) {
    ScopedTimer pour(timers, "remesh/change_particles");
    report.inserted += pour_inlets_3d(m.scene.inlets, t_n, topo, m, released);
  }

  // 1. Every body's new tetrahedra, from its particles at X_n and its previous mesh.
  ScopedTimer triangulate(timers, "remesh/triangulate");
  std::vector<std::vector<Index>> tets(n_bodies);
  std::vector<std::vector<std::array<Index, 3>>> surface(n_bodies);
  std::vector<std::vector<std::array<Index, 4>>> neighbours(n_bodies);
  std::vector<std::vector<char>> merged(n_bodies);  // per tetrahedron: it fills a gap outside the previous mesh
  bool kept_all = true;
  for (std::size_t b = 0; b < n_bodies; ++b) {
    const auto& pts = topo.points_of_body[b];
    std::vector<Index> local(std::size_t(topo.n_points), kNoIndex);
    std::vector<Vec3> x(pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) local[std::size_t(pts[k])] = Index(k), x[k] = m.nodes.position_n(pts[k]);
    std::vector<Index> previous;
    for (Index g : topo.tets[b]) previous.push_back(local[std::size_t(g)]);
    std::vector<double> h;
    if (settings.remesh_3d.local) average_neighbour_distance_3d(x, previous, h);
    Remesh3dResult r;
    remesh_points_3d(x, previous, settings.remesh_3d, h, r, &topo.neighbours[b]);
    LOOM_CHECK(!r.tets.empty() || pts.empty(), RunError,
               "remesh: the alpha test (remesh.alpha = " << settings.remesh_3d.alpha << ") removed every tetrahedron of body \"" << m.scene.bodies[b].name
                                                         << "\": raise remesh.alpha, or remesh.lchar if it is set (cells whose circumradius exceeds alpha * l_char are removed)");
    for (Index v : r.tets) tets[b].push_back(pts[std::size_t(v)]);
    for (const auto& f : r.surface) surface[b].push_back({pts[std::size_t(f[0])], pts[std::size_t(f[1])], pts[std::size_t(f[2])]});
    neighbours[b] = std::move(r.neighbours);
    merged[b] = std::move(r.merged_cell);
    merged[b].resize(r.tets.size() / 4, 0);
    kept_all = kept_all && r.kept_previous;
    report.rejected += r.rejected, report.isolated += r.isolated, report.merged += r.merged, report.triangles += Index(r.tets.size() / 4);
    report.flipped += r.flipped, report.slivers += r.slivers, report.capped += r.capped, report.repaired += r.repaired;
    report.area_after += r.volume;
  }
  // 2. Did the connectivity change?
  report.changed = !kept_all || report.inserted > 0;
  if (report.changed) {
    std::vector<Quad> before, after;
    for (std::size_t b = 0; b < n_bodies; ++b) {
      for (std::size_t t = 0; t + 3 < topo.tets[b].size(); t += 4) before.push_back(sorted_quad(&topo.tets[b][t]));
      for (std::size_t t = 0; t + 3 < tets[b].size(); t += 4) after.push_back(sorted_quad(&tets[b][t]));
    }
    std::sort(before.begin(), before.end()), std::sort(after.begin(), after.end());
    report.changed = before != after || report.inserted > 0;
    if (!report.changed) {  // the same cells: keep their order
      tets = topo.tets, surface = topo.surface, neighbours = topo.neighbours;
      for (std::size_t b = 0; b < n_bodies; ++b) merged[b].assign(tets[b].size() / 4, 0);
    }
  }
  triangulate.stop();
  bool quadratic = false;
  for (const Cells& cb : m.cells) quadratic = quadratic || cb.type == CellType::tet10;
  if (!report.changed && !quadratic) {  // nothing to transfer, nothing to rebuild but a released layer's conditions
    if (released) rebuild_system(m, topo, false);
    return report;
  }

  // 3. New cells (tet10: mid-nodes dropped and re-created at the straight midpoints), their geometry and history.
  ScopedTimer rebuild(timers, "remesh/rebuild_cells");
  const OldPoints old = snapshot(m);
  std::vector<Cells> old_cells;
  old_cells.swap(m.cells);
  std::vector<std::vector<char>> gap_cells(n_bodies);  // per cell block (at most one per body)
  rebuild_cells(tets, merged, topo.n_points, m, gap_cells);
  gap_cells.resize(m.cells.size());
  allocate_quad_points(m.cells, m.quad);
  use_history_columns(old.with_history, m.cells, m.quad);
  LOOM_CHECK(compute_geometry(m.nodes, m.cells, m.quad) == 0, RunError, "remesh: the new mesh has inverted cells");
  rebuild.stop();
  ScopedTimer transfer(timers, "remesh/map");
  transfer_history(settings, old, old_cells, m, report.map);
  if (!m.edges.empty()) {
    // Dynamic runs carry each particle's mass in lumped_mass: the new tetrahedra share it out (mass conserved).
    std::vector<double> density;
    for (const BodyMaterial& b : m.materials) density.push_back(b.density);
    report.new_material_mass =
        transfer_domains(old.domains, m.nodes, m.cells, m.j_projection, m.edges, m.nodes.lumped_mass.used() ? &density : nullptr, &gap_cells).new_material_mass;
  }
  if (m.nodes.lumped_mass.used()) compute_lumped_mass(m.cells, m.quad, m.materials, m.nodes);
  transfer.stop();
  ScopedTimer numbering(timers, "remesh/rebuild_system");
  rebuild_system(m, topo, report.changed);
  topo.tets = std::move(tets);
  topo.surface = std::move(surface);
  topo.neighbours = std::move(neighbours);
  return report;
}

void rebuild_system(FemModelT<3>& m, const PfemTopology3d& topo, bool connectivity_changed) {
  const int per_node = m.system.dofs.per_node;
  m.bc = build_boundary_conditions_3d(m.scene, m.nodes, m.cells, m.node_body, m.regions, per_node, /*tie_mid_nodes=*/true, &topo.tractions);
  add_inlet_layers(m.scene.inlets, topo, m.bc);
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
