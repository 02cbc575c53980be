// One integration domain per simplex: the element-integrated variants fem_up, fem_u of the smoothed elements (a
// triangle in 2D, a tetrahedron in 3D; smoothing over one cell is the cell). The stencil is the corners in cell order,
// triangles = {c, kNoIndex}, the pressure weights 1 / (D + 1) (the centroid value of the linear pressure). Coloured;
// the geometry columns are left at zero (systems/assemble/smoothing_geometry fills them).
#pragma once

#include "engine/core/types.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/edges.hpp"

namespace loom {

// From a tri3 (D = 2) or tet4 (D = 3) block; n_nodes bounds the node indices.
template <int D>
Edges<D> build_cell_domains(const Cells& cells, Index n_nodes);

}  // namespace loom
