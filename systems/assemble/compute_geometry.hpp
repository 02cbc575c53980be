// Geometry of the previous configuration B_n (seed 000 §2): shape gradients dN/dX_n and weights dV_n of
// every quadrature point, from the node positions X + u_n. Run at set-up and at every commit (the
// updated-Lagrangian reference moves with the converged state).
#pragma once

#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/quad_points.hpp"

namespace loom {

// Sizes each QuadPoints store for its cell block (F_n = F = I) and fills the geometry.
void allocate_quad_points(const std::vector<Cells>& cells, std::vector<QuadPoints<2>>& quad);

// Returns the number of cells whose area in B_n is not positive (inverted or degenerate).
Index compute_geometry(const Nodes<2>& nodes, const std::vector<Cells>& cells, std::vector<QuadPoints<2>>& quad);

}  // namespace loom
