// The linear displacement triangle (p1): one quadrature point at the centroid, constant gradients.
#pragma once

#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/quad_points.hpp"
#include "systems/assemble/elements/displacement_point.hpp"
#include "systems/assemble/elements/tri3.hpp"

namespace loom {

using P1Vector = ElementVector<3>;
using P1Matrix = ElementMatrix<3>;

// What the kernel reads of one cell, gathered from the stores.
struct P1Cell {
  NodalVectors<3> du;  // u - u_n at the corners
  NodalVectors<3> dN;  // dN/dX_n
  double dV_n = 0.0;   // area in B_n
  Mat3 F_n = Mat3::Identity();
  double volume0 = 0.0;  // reference area dV_n / J_n
};

inline P1Cell gather_p1_cell(const Nodes<2>& nodes, const Cells& cells, const QuadPoints<2>& quad, Index c) {
  P1Cell cell;
  for (int a = 0; a < 3; ++a) {
    const Index n = cells.node(c, a);
    cell.du.row(a) = (nodes.u[n] - nodes.u_n[n]).transpose();
  }
  cell.dN = Eigen::Map<const NodalVectors<3>>(quad.grad(c));
  cell.dV_n = quad.weight_n[c];
  cell.F_n = quad.F_n[c];
  cell.volume0 = cell.dV_n / cell.F_n.determinant();
  return cell;
}

template <class MaterialT>
bool p1_internal(const MaterialT& material, const P1Cell& cell, Mat3& F, P1Vector& r, P1Matrix* K) {
  return add_displacement_point<3>(material, cell.du, cell.dN, cell.dV_n, cell.F_n, F, r, K);
}

}  // namespace loom
