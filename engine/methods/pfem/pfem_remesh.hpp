// The PFEM remesh stage (seed 000 §3, §4.1): before each step, the particles at their converged
// positions X_n are triangulated anew (remesh), the quadrature history is transferred (map), TRI6
// mid-nodes are dropped and re-created on straight edges with interpolated nodal data, and the
// dof numbering, sparsity and colouring are rebuilt -- the last two only if the connectivity changed.
//
// Before the triangulation the particle set may change (engine/methods/pfem/particle_edits.hpp: insertion at long
// edges and removal of close pairs; engine/methods/pfem/inlet_flow.hpp: inflow rows); the previous mesh is edited with
// it, so that its boundary still constrains the new triangulation. pfem_topology.hpp says where particles live.
#pragma once

#include <vector>

#include "engine/methods/model/fem_model.hpp"
#include "engine/methods/pfem/particle_edits.hpp"
#include "engine/methods/pfem/pfem_topology.hpp"
#include "engine/timing/timers.hpp"
#include "systems/map/map_state.hpp"
#include "systems/remesh/remesh.hpp"
#include "systems/remesh/remesh_3d.hpp"

namespace loom {

struct PfemSettings {
  RemeshSettings remesh;
  Remesh3dSettings remesh_3d;  // scene.dimension = 3 (systems/remesh/remesh_3d.hpp)
  MapSettings map;
  int every = 1;  // remesh every this many steps
  ParticleEditSettings edits;
};

// The settings of the scene's [remesh] and [map] (and its graded walls' spacing).
PfemSettings pfem_settings_of(const SceneSpec& scene);

struct RemeshReport {
  bool changed = false;       // the connectivity changed: sparsity, colouring and dofs were rebuilt
  Index triangles = 0, rejected = 0, isolated = 0, merged = 0, crossings = 0;  // triangles: the cells (3D: tetrahedra)
  Index inserted = 0, removed = 0;             // particles
  Index flipped = 0, slivers = 0, capped = 0, repaired = 0;  // 3D (Remesh3dResult)
  double area_before = 0.0, area_after = 0.0;  // of the corner cells in X_n (before: of the mesh before any change; 3D: volumes)
  double new_material_mass = 0.0;  // dynamic es_pfem: the mass of the cells that filled gaps where surfaces met (added)
  MapStats map;
  RemeshStats stats() const {
    return {changed, rejected, isolated, merged, crossings, inserted, removed, area_after - area_before, flipped, slivers, capped, repaired};
  }
};

// The topology of the mesh the model was built with (the generated mesh).
PfemTopology initial_topology(const FemModel& model);
PfemTopology3d initial_topology(const FemModelT<3>& model);

// Remeshes the model's bodies at X = X_ref + u_n and transfers the state; see the header comment. t_n: the time at
// the start of the step (inlets start and end by it).
RemeshReport remesh_model(const PfemSettings& settings, double t_n, PfemTopology& topology, FemModel& model, Timers& timers);
// On tetrahedra (pfem_remesh_3d.cpp): the 3D remesh of every body, tet10 mid-nodes dropped and re-created, the history
// carried by the 3D map_state; particle insertion and inflow (inlet_flow_3d.hpp), no removal.
RemeshReport remesh_model(const PfemSettings& settings, double t_n, PfemTopology3d& topology, FemModelT<3>& model, Timers& timers);

// Boundary conditions (eq-24 ties, frozen tractions of `topology`), dofs, sparsity and scatters of the
// model's current cells; the dof numbering and pattern are rebuilt if the connectivity changed or the dof
// kinds differ (a restart from a checkpoint passes true).
void rebuild_system(FemModel& model, const PfemTopology& topology, bool connectivity_changed);
void rebuild_system(FemModelT<3>& model, const PfemTopology3d& topology, bool connectivity_changed);

}  // namespace loom
