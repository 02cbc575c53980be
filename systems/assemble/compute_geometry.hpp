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

// Sizes each QuadPoints store for its cell block (F_n = F = I) and fills the geometry. Points per cell: p1 one;
// tri6 and p1p1_uphi the simplex's degree-2 rule (D + 1 points: three on triangles, four on tetrahedra); quad9 nine.
template <int D>
void allocate_quad_points(const std::vector<Cells>& cells, std::vector<QuadPoints<D>>& quad);

// Returns the number of cells whose measure in B_n is not positive (inverted or degenerate). D = 2: tri3, tri6,
// quad9 cells; D = 3: tet4, tet10 (instantiated for both).
template <int D>
Index compute_geometry(const Nodes<D>& nodes, const std::vector<Cells>& cells, std::vector<QuadPoints<D>>& quad);

}  // namespace loom
