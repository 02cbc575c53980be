// Changing a PFEM body's particle set between steps: particles removed, new ones appended, and the previous mesh
// edited with them, so that the next remesh still has a valid mesh to take its surface from. Used by particle
// insertion and removal (particle_edits.hpp) and inflow (inlet_flow.hpp).
//
// A new particle is either the midpoint of two particles a, b of one edge, with every nodal column interpolated
// linearly (X, u, v, a, p, J, ...: seed 001 §3.1 "inserted particles get linearly interpolated nodal variables";
// X + u is then the edge's midpoint), or a fresh particle at x moving at v: undeformed, unstressed, J = 1.
// Mass (the lumped mass column, when the run has one): a removed particle's goes to the particle it merges into, a
// midpoint starts with none (the remesh gives it a share of the triangles it splits), and the corners of fresh
// material's triangles gain its mass, rho A / 3 each; so the particles' masses add up to the body's mass.
#pragma once

#include <vector>

#include "engine/methods/model/fem_model.hpp"
#include "engine/methods/pfem/pfem_topology.hpp"

namespace loom {

struct NewParticle {
  Index body = 0;
  Index a = kNoIndex, b = kNoIndex;  // the midpoint of particles a and b ...
  Vec2 x = Vec2::Zero();             // ... or else a fresh particle at x
  Vec2 v = Vec2::Zero();             //     moving at v
};

struct ParticleSetChange {
  std::vector<char> remove;  // per current particle: 1 if it goes
  std::vector<Index> merge_into;  // per current particle that goes: the particle that takes its mass (or kNoIndex)
  std::vector<NewParticle> add;
  // Per body, the previous mesh after the change: particle indices in the extended numbering, where the current
  // particles keep theirs and add[k] is n_points + k. No triangle may hold a removed particle.
  std::vector<std::vector<Index>> triangles;
  // Triangles of new, unstressed material (inflow strips; extended numbering): their corners gain rho A / 3 of mass.
  std::vector<Index> fresh_triangles;
  // Per inlet: its driven row after the change (extended numbering), when the change sets it.
  std::vector<std::vector<Index>> inlet_rows;
  std::vector<char> inlet_row_set;

  explicit ParticleSetChange(const PfemTopology& topo)
      : remove(std::size_t(topo.n_points), 0), merge_into(std::size_t(topo.n_points), kNoIndex), triangles(topo.triangles), inlet_rows(topo.inlets.size()), inlet_row_set(topo.inlets.size(), 0) {}
  Index n_removed() const;
  bool empty() const { return add.empty() && n_removed() == 0 && triangles_unchanged_; }
  void mark_triangles_changed() { triangles_unchanged_ = false; }

 private:
  bool triangles_unchanged_ = true;
};

// Applies `change`: the particles are compacted (removed ones dropped, the order of the others kept), the new ones
// appended, the mid-nodes dropped (a remesh re-creates them); everything that holds particle indices is renumbered:
// the topology (triangles, boundary, points of each body, traction edges: an edge that lost a particle is dropped,
// inlet rows), node_body, the regions of mesh files (a removed particle leaves its groups) and the corners of the old
// cells (their mid-node slots become kNoIndex: the old cells are only read by the state transfer). Returns the new
// index of every particle that was there before (kNoIndex: removed).
std::vector<Index> apply_particle_change(const ParticleSetChange& change, PfemTopology& topo, FemModel& model);

}  // namespace loom
