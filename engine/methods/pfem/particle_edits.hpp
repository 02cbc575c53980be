// Particle insertion and removal for PFEM free-surface flows (seed 001 §3.1: "particles are deleted or inserted
// to avoid clogging or separation"; the paper gives no criteria, its spec's ambiguity 12 proposes these):
//  - removal: of two particles joined by an edge of the previous mesh shorter than remove_below * h0, one goes
//    (an interior one rather than one on the surface; two surface particles only if they are neighbours along it);
//    its triangles are given to the other, so the mesh stays valid (a removal that would fold a triangle is not
//    made);
//  - insertion: a particle at the midpoint of every edge of the previous mesh longer than insert_above * h0, the
//    triangles split to hold it, its nodal values interpolated linearly (particle_set.hpp).
// Near a wall with a spacing of its own ([[wall]] spacing) h0 is graded: the wall's spacing on it, growing linearly
// to the body's one body spacing away, at the edge's midpoint.
// Particles whose motion or load is prescribed (Dirichlet boundaries, dead-load edges, inlet rows) are never
// removed; edges touching an inlet row are not split. h0 is the body's spacing (PfemTopology::spacing).
#pragma once

#include <vector>

#include "engine/methods/model/fem_model.hpp"
#include "engine/methods/pfem/particle_set.hpp"
#include "engine/methods/pfem/pfem_topology.hpp"

namespace loom {

// A wall line near which h0 is graded: from `spacing` on it to the body's h0 at a distance `ramp` (0: h0) on the
// side `normal` points to. body: the only body it grades (kNoIndex: every body).
struct GradedWall {
  Vec2 point = Vec2::Zero(), normal = Vec2::UnitY();
  double spacing = 0.0;
  Index body = kNoIndex;
  double ramp = 0.0;
};

struct ParticleEditSettings {
  double insert_above = 0.0, remove_below = 0.0;  // factors of h0; 0: off
  std::vector<GradedWall> graded = {};
  bool active() const { return insert_above > 0.0 || remove_below > 0.0; }
};

// The spacing at x of a body whose spacing is h0 (body b), graded near the settings' walls.
double local_spacing(const ParticleEditSettings& settings, Index b, double h0, const Vec2& x);

// Plans the removals, then the insertions on what remains, on the previous mesh at X_n; adds them to `change`
// (which may already hold other edits on the same numbering). `fixed`: per particle, 1 if it must stay.
void plan_particle_edits(const ParticleEditSettings& settings, const PfemTopology& topo, const Nodes<2>& nodes,
                         const std::vector<char>& fixed, ParticleSetChange& change);

// Per particle, 1 if its motion or load is prescribed: a Dirichlet dof, an end of a dead-load edge, an inlet row.
std::vector<char> fixed_particles(const PfemTopology& topo, const BoundaryConditions<2>& bc);

}  // namespace loom
