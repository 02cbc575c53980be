// Lumped mass of every node (seed 000 eq 5 with the reference volume dV_0 = dV_n / J_n): row sum
// rho_0 A_0 / 3 for linear triangles and rho_0 V_0 / 4 for linear tetrahedra, HRZ for quadratic triangles and
// tetrahedra, the row sum for quad9 (see element_mass.hpp). Instantiated for D = 2 and 3.
#pragma once

#include <vector>

#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/quad_points.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {

template <int D>
void compute_lumped_mass(const std::vector<Cells>& cells, const std::vector<QuadPoints<D>>& quad,
                         const std::vector<BodyMaterial>& materials, Nodes<D>& nodes);

}  // namespace loom
