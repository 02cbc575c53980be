// The quadratic displacement triangle (tri6) at its three points (seed 000 §4.1, Fig 5).
#pragma once

#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/quad_points.hpp"
#include "systems/assemble/elements/displacement_point.hpp"

namespace loom {

using Tri6Vector = ElementVector<6>;
using Tri6Matrix = ElementMatrix<6>;

struct Tri6Cell {
  NodalVectors<6> du;      // u - u_n at the six nodes
  NodalVectors<6> dN[3];   // dN/dX_n at each point
  double dV_n[3] = {0, 0, 0};
  Mat3 F_n[3];
};

inline Tri6Cell gather_tri6_cell(const Nodes<2>& nodes, const Cells& cells, const QuadPoints<2>& quad, Index c) {
  Tri6Cell cell;
  for (int a = 0; a < 6; ++a) {
    const Index n = cells.node(c, a);
    cell.du.row(a) = (nodes.u[n] - nodes.u_n[n]).transpose();
  }
  for (int q = 0; q < 3; ++q) {
    const Index p = 3 * c + q;
    cell.dN[q] = Eigen::Map<const NodalVectors<6>>(quad.grad(p));
    cell.dV_n[q] = quad.weight_n[p];
    cell.F_n[q] = quad.F_n[p];
  }
  return cell;
}

template <class MaterialT>
bool tri6_internal(const MaterialT& material, const Tri6Cell& cell, Mat3 F[3], Tri6Vector& r, Tri6Matrix* K) {
  for (int q = 0; q < 3; ++q)
    if (!add_displacement_point<6>(material, cell.du, cell.dN[q], cell.dV_n[q], cell.F_n[q], F[q], r, K)) return false;
  return true;
}

}  // namespace loom
