// Isoparametric displacement cells integrated at NQ points with the gradients cached in QuadPoints: the
// quadratic triangle (tri6, three points; seed 000 §4.1, Fig 5), the biquadratic quadrilateral (quad9,
// 3 x 3 Gauss; seed 004 §2.2), and in 3D the linear tetrahedron (one point) and the quadratic one (tet10, four points). Each point adds P grad N dV_0 and its tangent (displacement_point.hpp).
#pragma once

#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/quad_points.hpp"
#include "systems/assemble/elements/displacement_point.hpp"

namespace loom {

template <int NEN, int NQ, int D = 2>
struct IsoparametricCell {
  NodalVectors<NEN, D> du;     // u - u_n at the nodes
  NodalVectors<NEN, D> dN[NQ]; // dN/dX_n at each point
  double dV_n[NQ] = {};
  Mat3 F_n[NQ];
};

template <int NEN, int NQ, int D = 2>
IsoparametricCell<NEN, NQ, D> gather_isoparametric_cell(const Nodes<D>& nodes, const Cells& cells, const QuadPoints<D>& quad, Index c) {
  IsoparametricCell<NEN, NQ, D> cell;
  for (int a = 0; a < NEN; ++a) {
    const Index n = cells.node(c, a);
    cell.du.row(a) = (nodes.u[n] - nodes.u_n[n]).transpose();
  }
  for (int q = 0; q < NQ; ++q) {
    const Index p = NQ * c + q;
    cell.dN[q] = Eigen::Map<const NodalVectors<NEN, D>>(quad.grad(p));
    cell.dV_n[q] = quad.weight_n[p];
    cell.F_n[q] = quad.F_n[p];
  }
  return cell;
}

template <class MaterialT, int NEN, int NQ, int D>
bool isoparametric_internal(const MaterialT& material, const IsoparametricCell<NEN, NQ, D>& cell, Mat3 F[NQ], ElementVector<NEN, D>& r,
                            ElementMatrix<NEN, D>* K) {
  for (int q = 0; q < NQ; ++q)
    if (!add_displacement_point<NEN, D>(material, cell.du, cell.dN[q], cell.dV_n[q], cell.F_n[q], F[q], r, K)) return false;
  return true;
}

// Reference volume of the cell: sum of dV_n / det F_n over its points.
template <int NEN, int NQ, int D>
double reference_volume(const IsoparametricCell<NEN, NQ, D>& cell) {
  double volume0 = 0.0;
  for (int q = 0; q < NQ; ++q) volume0 += cell.dV_n[q] / cell.F_n[q].determinant();
  return volume0;
}

using Tri6Cell = IsoparametricCell<6, 3>;
using Tri6Vector = ElementVector<6>;
using Tri6Matrix = ElementMatrix<6>;
using Quad9Cell = IsoparametricCell<9, 9>;

inline Tri6Cell gather_tri6_cell(const Nodes<2>& nodes, const Cells& cells, const QuadPoints<2>& quad, Index c) {
  return gather_isoparametric_cell<6, 3>(nodes, cells, quad, c);
}

template <class MaterialT>
bool tri6_internal(const MaterialT& material, const Tri6Cell& cell, Mat3 F[3], Tri6Vector& r, Tri6Matrix* K) {
  return isoparametric_internal(material, cell, F, r, K);
}

}  // namespace loom
