// Assembly of the formulations of seed 001 (es_up, es_u, fem_up, fem_u): the kernels of the integration
// domains of an Edges store (elements/smoothed_domain.hpp) and the triangles' share of the pressure
// equation. Called by assemble_system between the cell blocks and the nodal terms; race-free by colour like
// every block. The domains' updated history, stress and det f are written to the store at each assembly.
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
void assemble_domain_block(const StepContext& ctx, bool tangent, const std::vector<BodyMaterial>& materials, const Nodes<2>& nodes,
                           const BoundaryConditions<2>& bc, Edges<2>& domains, const CellScatter& scatter, LinearSystem& system,
                           std::atomic<Index>& inverted);

// Adds -(K_pp,K + K_stab) p of every triangle of a mixed block (es_up, fem_up); cells.measure holds the
// reference areas.
void assemble_triangle_pressure_terms(bool tangent, const std::vector<BodyMaterial>& materials, const Nodes<2>& nodes,
                                      const BoundaryConditions<2>& bc, const Cells& cells, const CellScatter& scatter,
                                      LinearSystem& system);

// Triangles of a seed-001 block that are inverted or degenerate at the iterate: the domains' det f > 0 does
// not see a triangle folding between them.
Index inverted_triangles(const Nodes<2>& nodes, const Cells& cells);

}  // namespace loom
