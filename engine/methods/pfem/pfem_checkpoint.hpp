// What a checkpoint of a pfem or es_pfem run keeps of its topology besides the stores (recipes/fem_checkpoint.cpp):
// the corner cells of every body (the next remesh's previous mesh), the particle count, and what renumbering the
// particles touched (2D: inlets' rows, dead-load edges, mesh-file regions; 3D: dead-load faces). Restoring checks
// every index against the restored nodes (a checkpoint of another scene is bad input, not a crash) and rebuilds
// what follows from them (the boundary polygons or surfaces); the caller then rebuilds the system.
#pragma once

#include "engine/io/checkpoint.hpp"
#include "engine/methods/model/fem_model.hpp"
#include "engine/methods/pfem/pfem_topology.hpp"

namespace loom {

void write_topology(CheckpointWriter& w, const PfemTopology& topology, const FemModel& model);
void write_topology(CheckpointWriter& w, const PfemTopology3d& topology, const FemModelT<3>& model);

// `particles_change`: the particle set may differ from the scene's (insertion, removal, inflow).
void restore_topology(const CheckpointReader& r, PfemTopology& topology, FemModel& model, bool particles_change);
void restore_topology(const CheckpointReader& r, PfemTopology3d& topology, FemModelT<3>& model, bool particles_change);

}  // namespace loom
