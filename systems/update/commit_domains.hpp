// Accepts a converged step on the integration domains of seed 001 (run after commit_step, which moved
// u_n): the history b^e_n <- b^e, each triangle's stored stress (the mean of its three edges' stress, or
// its own domain's for fem_up / fem_u; seed 001 §3.5, what output and probes read), and the domains'
// geometry in the new B_n.
#pragma once

#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/edges.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/quad_points.hpp"

namespace loom {

void commit_domains(const StepContext& ctx, const std::vector<Cells>& cells, const Nodes<2>& nodes, std::vector<QuadPoints<2>>& quad,
                    std::vector<Edges<2>>& edges);

// The triangles' stored stress from their domains (also at set-up and after a restore).
void domain_stress_to_cells(const std::vector<Edges<2>>& edges, std::vector<QuadPoints<2>>& quad);

}  // namespace loom
