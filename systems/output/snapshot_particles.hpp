// Output frames of an MPM run (DESIGN §6): the material points as a point cloud (.vtp) at their current
// positions with point data displacement, velocity (dynamic), pressure, J = det F, Cauchy stress (9
// components, row-major) and von Mises stress; and the active background grid (.vtu) in its undeformed
// position with point data displacement (of the last step), velocity, pressure (mixed) and lumped mass,
// cell data the number of particles. Pressure is seed 003's p of sigma = sigma_dev + p I (positive in
// tension): the unknown of p1p1_up, tr(sigma)/3 for displacement-only grids.
#pragma once

#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/io/frame.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_activity.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/point_locations.hpp"
#include "engine/store/points.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {

template <int D>
void snapshot_particles(const StepContext& ctx, const std::vector<BodyMaterial>& materials, const Points<D>& particles, Frame& frame);

// Method mpm_fem: the FEM bodies' cells follow the grid's in the same file, with cell data body (-1 on the background
// grid's cells), stress (9 components, the mean Cauchy stress of the cell's 3 x 3 Gauss points) and von_mises
// (NaN on the grid's cells, whose stress is the particles').
template <int D>
void snapshot_grid(const StepContext& ctx, const std::vector<BodyMaterial>& materials, const Cells& grid, const GridActivity& activity,
                   const Nodes<D>& grid_nodes, const PointLocations& particle_loc, Frame& frame);

// Cauchy stress of a material point: sigma_dev(F) + p I for the mixed formulation (neo_hooke_split with the
// particle's pressure), tau(b^e) / J for a material with history (be: the particle's b^e), the material's stress
// of F otherwise. False if J <= 0.
bool particle_stress(const BodyMaterial& material, const Mat3& F, bool mixed, double pressure, Mat3& sigma, const Mat3* be = nullptr);

}  // namespace loom
