// Energies of the mesh-based methods (fem, pfem) for the energy probe, at the last converged step: kinetic
// 1/2 sum_A m_A |v_A|^2 with the lumped mass; elastic sum_q dV_0 psi(F_n) over the quadrature points (dV_0 =
// dV_n / det F_n), for the displacement formulations (p1, tri6, quad9; tet4, tet10) and the hyperelastic materials
// (the loader refuses the others), and the smoothed elements' domains (below); for p1p1_uphi (method fem) sum_q dV_0 psi(F~_n) with dV_0 from the reference
// simplex (the PPP stabilisation's quadratic form is not included); potential -f_ext . u_n of the nodal external forces (body forces and
// tractions, a potential while they are dead loads).
#pragma once

#include <vector>

#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/edges.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/quad_points.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {

struct MeshEnergy {
  double kinetic = 0.0, elastic = 0.0, potential = 0.0;
};

// `domains`: the integration domains of the smoothed elements (es_up, es_u, fem_up, fem_u), whose elastic energy is
// sum_k V_0^k psi(b^e_n) over the domains (V_0 = V_n / sqrt(det b^e_n), the flow being isochoric; hencky_perzyna's
// Hencky energy, or linear_elastic's on the reference geometry with eps = (b^e - I) / 2); their cells add none.
template <int D>
MeshEnergy mesh_energy(const std::vector<BodyMaterial>& materials, const Nodes<D>& nodes, const std::vector<Cells>& cells,
                       const std::vector<QuadPoints<D>>& quad, const BoundaryConditions<D>& bc,
                       const std::vector<Edges<D>>* domains = nullptr);

}  // namespace loom
