// Assembly of the formulations of seed 001 (es_up, es_u, fem_up, fem_u): the kernels of the integration
// domains of an Edges store (elements/smoothed_domain.hpp) and the simplices' share of the pressure
// equation. Called by assemble_system between the cell blocks and the nodal terms; race-free by colour like
// every block. The domains' updated history, stress and det f are written to the store at each assembly.
// 2D: edge domains (3 or 4 nodes) on triangles; 3D: face domains (4 or 5 nodes) on tetrahedra.
#pragma once

#include <atomic>

#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/edges.hpp"
#include "engine/store/nodes.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {

// Adds the domains' residual (and tangent); counts domains whose state does not exist in `inverted`.
template <int D>
void assemble_domain_block(const StepContext& ctx, bool tangent, const std::vector<BodyMaterial>& materials, const Nodes<D>& nodes,
                           const BoundaryConditions<D>& bc, Edges<D>& domains, const CellScatter& scatter, LinearSystem& system,
                           std::atomic<Index>& inverted);

// Adds -(K_pp,K + K_stab) p of every triangle (tetrahedron) of a mixed block (es_up, fem_up); cells.measure holds
// the reference areas (volumes).
template <int D>
void assemble_simplex_pressure_terms(bool tangent, const std::vector<BodyMaterial>& materials, const Nodes<D>& nodes,
                                     const BoundaryConditions<D>& bc, const Cells& cells, const CellScatter& scatter, LinearSystem& system);

// Triangles (tetrahedra) of a seed-001 block that are inverted or degenerate at the iterate: the domains' det f > 0
// does not see a simplex folding between them.
template <int D>
Index inverted_simplices(const Nodes<D>& nodes, const Cells& cells);

}  // namespace loom
