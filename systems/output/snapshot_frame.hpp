// Takes an output frame of the converged state (u_n, F_n): node positions in the current configuration,
// point data displacement (velocity for dynamic runs, phi for mixed u-phi runs), cell data Cauchy stress
// (9 components,
// row-major), pressure = -tr(sigma)/3, J = det F, von Mises stress sqrt(3/2 dev(sigma):dev(sigma)), body.
// Cells with several quadrature points report the average of their points.
// With output.nodal_stress, also point data nodal_stress (9 components) and nodal_von_mises: each node's value the
// volume-weighted mean of the cell stress of its cells.
#pragma once

#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/io/frame.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/quad_points.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {

template <int D>
void snapshot_frame(const StepContext& ctx, const std::vector<BodyMaterial>& materials, const Nodes<D>& nodes,
                    const std::vector<Cells>& cells, const std::vector<QuadPoints<D>>& quad, Frame& frame);

}  // namespace loom
