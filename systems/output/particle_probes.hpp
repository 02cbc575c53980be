// Probes of an MPM run at the converged state, in the order of SceneSpec::probes:
//  reaction: sum over the boundary's prescribed grid dofs of the component of r = f_int + M a - f_ext;
//  point:    displacement component of the material point nearest to `at` in the reference configuration;
//  newton:   Newton iterations of the step (summed over cut-back sub-steps);
//  extent:   largest or smallest current coordinate of the particles along a component;
//  energy:   kinetic sum m v^2 / 2 and elastic sum V_0 psi(F) of the particles, or their total (psi of the
//            mixed formulation: the deviatoric energy plus p^2 / (2 kappa)).
#pragma once

#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/points.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {

struct ParticleProbePlan {
  std::vector<ProbeSpec> probes;
  std::vector<Index> particle;  // point probes: the nearest particle; others kNoIndex
};

ParticleProbePlan plan_particle_probes(const SceneSpec& scene, const Points<2>& particles);

void evaluate_particle_probes(const StepContext& ctx, const ParticleProbePlan& plan, const std::vector<BodyMaterial>& materials,
                              const Points<2>& particles, const LinearSystem& system, const BoundaryConditions<2>& bc,
                              int newton_iterations, std::vector<double>& values);

}  // namespace loom
