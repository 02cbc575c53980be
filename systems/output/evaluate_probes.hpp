// Values of the scene's probes at the converged state, in the order of SceneSpec::probes:
//  reaction: sum over the boundary's prescribed dofs of the given component of r = f_int + M a - f_ext,
//            the force the constraint exerts on the body (its sign follows the axis);
//  point:    displacement component of the node nearest to the probe's reference coordinates;
//  newton:   Newton iterations (linear solves) of the step, summed over its cut-back sub-steps.
#pragma once

#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

struct ProbePlan {
  std::vector<ProbeSpec> probes;
  std::vector<Index> node;  // point probes: nearest node; others kNoIndex
};

// Finds the node of each point probe (nearest in reference coordinates, among the nodes of its body).
ProbePlan plan_probes(const SceneSpec& scene, const Nodes<2>& nodes, const std::vector<Index>& node_body);

void evaluate_probes(const StepContext& ctx, const ProbePlan& plan, const Nodes<2>& nodes, const LinearSystem& system,
                     const BoundaryConditions<2>& bc, int newton_iterations, std::vector<double>& values);

}  // namespace loom
