// Method mpm_fem (seed 004 §4): a FEM cell's nodes in its undeformed configuration X^ = X - u_n (after the step's
// commit u_n is the FEM nodes' displacement) and in its current one x = X + u, so that F = dx/dX^ at its Gauss
// points, for its energy (particle_probes.cpp) and its stress in the grid's frame (snapshot_particles.cpp).
#pragma once

#include "engine/mesh/quad9_shape.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

inline void coupled_cell_coordinates(const Cells& grid, const Nodes<2>& nodes, Index c, Quad9Coordinates& x, Quad9Coordinates& X) {
  for (int a = 0; a < 9; ++a) {
    const Index i = grid.node(c, a);
    x.row(a) = (nodes.X[i] + nodes.u[i]).transpose();
    X.row(a) = (nodes.X[i] - nodes.u_n[i]).transpose();
  }
}

}  // namespace loom
