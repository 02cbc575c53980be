// Lumped mass of every node (seed 000 eq 5 with the reference volume dV_0 = dV_n / J_n): row sum
// rho_0 A_0 / 3 for linear triangles, HRZ for quadratic ones (see element_mass.hpp).
#pragma once

#include <vector>

#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/quad_points.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {

void compute_lumped_mass(const std::vector<Cells>& cells, const std::vector<QuadPoints<2>>& quad,
                         const std::vector<BodyMaterial>& materials, Nodes<2>& nodes);

}  // namespace loom
