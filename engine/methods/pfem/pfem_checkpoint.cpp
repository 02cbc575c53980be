#include "engine/methods/pfem/pfem_checkpoint.hpp"

#include <string>

#include "engine/core/errors.hpp"
#include "engine/mesh/tet_adjacency.hpp"
#include "systems/remesh/remesh.hpp"
#include "systems/remesh/remesh_3d.hpp"

namespace loom {
namespace {

// The particles of each body from the restored node_body.
template <class Topology, class Model>
void restore_particles(const CheckpointReader& r, Topology& topology, Model& m, bool particles_change) {
  const Index n_points = r.value<Index>("topology/n_points");
  if (!particles_change) r.expect_size("particles", std::size_t(n_points), std::size_t(topology.n_points));
  topology.n_points = n_points;
  r.expect(topology.n_points <= m.nodes.size(), "has more particles than nodes");
  topology.points_of_body.assign(topology.points_of_body.size(), {});
  for (Index i = 0; i < topology.n_points; ++i) {
    const Index b = m.node_body[std::size_t(i)];
    r.expect(b >= 0 && b < Index(topology.points_of_body.size()), "has particles of bodies the scene does not have");
    topology.points_of_body[std::size_t(b)].push_back(i);
  }
}

void write_inlets(CheckpointWriter& w, const std::vector<InletState>& inlets) {
  for (std::size_t k = 0; k < inlets.size(); ++k) {
    const std::string key = "topology/inlet/" + std::to_string(k);
    w.vector(key + "/row", inlets[k].row);
    w.value(key + "/state", char(int(inlets[k].started) + 2 * int(inlets[k].closed)));
  }
}

void restore_inlets(const CheckpointReader& r, std::vector<InletState>& inlets, Index n_points) {
  for (std::size_t k = 0; k < inlets.size(); ++k) {
    const std::string key = "topology/inlet/" + std::to_string(k);
    r.vector(key + "/row", inlets[k].row);
    const char state = r.value<char>(key + "/state");
    inlets[k].started = state & 1, inlets[k].closed = (state & 2) != 0;
    for (Index v : inlets[k].row) r.expect(v >= 0 && v < n_points, "has inlet rows on nodes that are not particles");
  }
}

}  // namespace

void write_topology(CheckpointWriter& w, const PfemTopology& topology, const FemModel& m) {
  for (std::size_t b = 0; b < topology.triangles.size(); ++b) w.vector("topology/triangles/" + std::to_string(b), topology.triangles[b]);
  // A particle set that changes (insertion, removal, inflow): its size, the inlets' rows and what renumbering
  // touched (dead-load edges, mesh-file regions).
  w.value("topology/n_points", topology.n_points);
  write_inlets(w, topology.inlets);
  std::vector<Index> traction_ends;
  for (const auto& e : topology.tractions) traction_ends.insert(traction_ends.end(), {e.a, e.b});
  w.vector("topology/traction_ends", traction_ends);
  for (std::size_t b = 0; b < m.regions.size(); ++b)
    for (std::size_t r = 0; r < m.regions[b].size(); ++r) {
      const std::string key = "regions/" + std::to_string(b) + "/" + std::to_string(r);
      w.vector(key + "/corners", m.regions[b][r].corners);
      std::vector<Index> ends;
      for (const auto& e : m.regions[b][r].edges) ends.insert(ends.end(), {e[0], e[1]});
      w.vector(key + "/edges", ends);
    }
}

void restore_topology(const CheckpointReader& r, PfemTopology& topology, FemModel& m, bool particles_change) {
  restore_particles(r, topology, m, particles_change);
  restore_inlets(r, topology.inlets, topology.n_points);
  std::vector<Index> traction_ends;
  r.vector("topology/traction_ends", traction_ends);
  r.expect_size("dead-load edge ends", traction_ends.size(), 2 * topology.tractions.size());
  for (std::size_t e = 0; e < topology.tractions.size(); ++e) {
    topology.tractions[e].a = traction_ends[2 * e], topology.tractions[e].b = traction_ends[2 * e + 1];
    r.expect(traction_ends[2 * e] < topology.n_points && traction_ends[2 * e + 1] < topology.n_points, "has loads on nodes that are not particles");
  }
  for (std::size_t b = 0; b < m.regions.size(); ++b)
    for (std::size_t g = 0; g < m.regions[b].size(); ++g) {
      const std::string key = "regions/" + std::to_string(b) + "/" + std::to_string(g);
      r.vector(key + "/corners", m.regions[b][g].corners);
      std::vector<Index> ends;
      r.vector(key + "/edges", ends);
      m.regions[b][g].edges.clear();
      for (std::size_t e = 0; e + 1 < ends.size(); e += 2) m.regions[b][g].edges.push_back({ends[e], ends[e + 1]});
    }
  for (std::size_t b = 0; b < topology.triangles.size(); ++b) {
    r.vector("topology/triangles/" + std::to_string(b), topology.triangles[b]);
    for (Index v : topology.triangles[b]) r.expect(v >= 0 && v < topology.n_points, "has triangles on nodes that are not particles");
    topology.boundary[b] = boundary_of(topology.triangles[b]);
  }
}

void write_topology(CheckpointWriter& w, const PfemTopology3d& topology, const FemModelT<3>&) {
  w.value("topology/n_points", topology.n_points);
  write_inlets(w, topology.inlets);
  for (std::size_t b = 0; b < topology.tets.size(); ++b) w.vector("topology/tets/" + std::to_string(b), topology.tets[b]);
}

void restore_topology(const CheckpointReader& r, PfemTopology3d& topology, FemModelT<3>& m, bool particles_change) {
  restore_particles(r, topology, m, particles_change);
  restore_inlets(r, topology.inlets, topology.n_points);
  for (std::size_t b = 0; b < topology.tets.size(); ++b) {
    r.vector("topology/tets/" + std::to_string(b), topology.tets[b]);
    for (Index v : topology.tets[b]) r.expect(v >= 0 && v < topology.n_points, "has cells on nodes that are not particles");
    r.expect(topology.tets[b].size() % 4 == 0, "has a broken list of tetrahedra");
    topology.neighbours[b] = tet_face_neighbours(topology.tets[b]);
    topology.surface[b].clear();
    for (const BoundaryFace& f : boundary_faces(topology.tets[b], topology.neighbours[b])) topology.surface[b].push_back(f.nodes);
  }
}

}  // namespace loom
