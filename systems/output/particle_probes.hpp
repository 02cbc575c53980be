// Probes of an MPM run at the converged state, in the order of SceneSpec::probes:
//  reaction: sum over the boundary's prescribed grid dofs of the component of r = f_int + M a - f_ext;
//  point:    displacement component of the tracer point that started at `at` and moves with the grid's
//            displacement increments (the traction points' kinematics): the material point at `at`;
//  newton:   Newton iterations of the step (summed over cut-back sub-steps);
//  extent:   largest or smallest current coordinate of the particles along a component;
//  pressure_jump: mean |p_a - p_b| over the sides of the active grid (each once), the nodal pressure
//            oscillation of the mixed formulation (seed 003 Fig 5a);
//  energy:   kinetic sum m v^2 / 2 and elastic sum V_0 psi(F) of the particles, or their total (psi of the
//            mixed formulation: the deviatoric energy plus p^2 / (2 kappa)).
#pragma once

#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/grid_activity.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/points.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {

struct ParticleProbePlan {
  std::vector<ProbeSpec> probes;
  std::vector<Index> tracer;  // point probes: their tracer point (in probe order); others kNoIndex
};

ParticleProbePlan plan_particle_probes(const SceneSpec& scene);

// The grid stores are read by pressure_jump probes and mpm_fem's energies only.
template <int D>
struct GridView {
  const Cells& grid;
  const GridActivity& activity;
  const Nodes<D>& nodes;
};

// D = 2 or 3 (3D: angular_momentum reads the probe's component of sum m r x v; pressure_jump is 2D).
template <int D>
void evaluate_particle_probes(const StepContext& ctx, const ParticleProbePlan& plan, const std::vector<BodyMaterial>& materials,
                              const Points<D>& particles, const Points<D>& probe_points, const Points<D>& traction_points,
                              const GridView<D>& grid,
                              const LinearSystem& system, const BoundaryConditions<D>& bc, int newton_iterations,
                              std::vector<double>& values);

}  // namespace loom
