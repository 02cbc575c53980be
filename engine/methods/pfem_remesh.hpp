// The PFEM remesh stage (seed 000 §3, §4.1): before each step, the particles at their converged
// positions X_n are triangulated anew (remesh), the quadrature history is transferred (map), TRI6
// mid-nodes are dropped and re-created on straight edges with interpolated nodal data, and the
// dof numbering, sparsity and colouring are rebuilt -- the last two only if the connectivity changed.
//
// In the pfem recipe the particles are the first n_points nodes of the Nodes store: they keep their index
// and all their nodal columns across remeshes; TRI6 mid-nodes are appended after them. (DESIGN §2 puts
// persistent particles in Points: keeping them as the leading nodes avoids copying every nodal column
// twice per step and a second index space; Points stays the store of MPM's material points.)
#pragma once

#include <vector>

#include "engine/methods/fem_model.hpp"
#include "engine/timing/timers.hpp"
#include "systems/map/map_state.hpp"
#include "systems/remesh/remesh.hpp"

namespace loom {

struct PfemSettings {
  RemeshSettings remesh;
  MapSettings map;
  int every = 1;  // remesh every this many steps
};

// What the next remesh needs of the current mesh: per body, its corner triangles and boundary polygon.
struct PfemTopology {
  Index n_points = 0;                              // nodes [0, n_points) are the particles
  std::vector<std::vector<Index>> points_of_body;  // global node indices of each body's particles
  std::vector<std::vector<Index>> triangles;       // per body: corner connectivity (global indices)
  std::vector<std::vector<Edge>> boundary;         // per body: boundary polygon (global indices)
  std::vector<TractionEdge<2>> tractions;          // loaded edges of the initial mesh, on corners (dead loads)
};

struct RemeshReport {
  bool changed = false;       // the connectivity changed: sparsity, colouring and dofs were rebuilt
  Index triangles = 0, rejected = 0, isolated = 0;
  double area_before = 0.0, area_after = 0.0;  // of the corner triangles in X_n
  MapStats map;
  RemeshStats stats() const { return {changed, rejected, isolated, area_after - area_before}; }
};

// The topology of the mesh the model was built with (the generated mesh).
PfemTopology initial_topology(const FemModel& model);

// Remeshes the model's bodies at X = X_ref + u_n and transfers the state; see the header comment.
RemeshReport remesh_model(const PfemSettings& settings, PfemTopology& topology, FemModel& model, Timers& timers);

// Boundary conditions (eq-24 ties, frozen tractions of `topology`), dofs, sparsity and scatters of the
// model's current cells; the dof numbering and pattern are rebuilt if the connectivity changed or the dof
// kinds differ (a restart from a checkpoint passes true).
void rebuild_system(FemModel& model, const PfemTopology& topology, bool connectivity_changed);

}  // namespace loom
