// Seed 004's receding-contact correction (Aulisa & Capodaglio §5, eq 47 corrected; spec §1.10). Grid
// contact is sticky: the nodes of a cell side on a wall (u = 0) drag the particles near it. For a particle
// of such a quad9 cell that moves away from the wall, its deformation gradient uses modified displacements
// of the side's three nodes f, extrapolated quadratically from the next two rows m and o of the cell:
//   u*_f = (1 - C_c) u_f + C_c (4/3 u_m - 1/3 u_o),   other nodes unchanged,
// so that at C_c = 1 the normal derivative of u* vanishes on the side (the printed eq 47 swaps m and o,
// which does not). u* = T u with a constant T per particle and step; F then depends on u through the
// trial gradients dN* = T^T dN (dN*_f = (1 - C_c) dN_f, dN*_m = dN_m + 4/3 C_c dN_f, dN*_o = dN_o - 1/3 C_c dN_f).
// The inertia and the particle's position use the unmodified u.
#pragma once

#include <array>

#include "systems/assemble/elements/displacement_point.hpp"

namespace loom {

// Local quad9 nodes of side s (0: eta = -1, 1: xi = +1, 2: eta = +1, 3: xi = -1): the side's nodes and the
// two rows behind them, matched node by node.
struct Quad9SideRows {
  std::array<int, 3> face, next, far;
};
inline const Quad9SideRows& quad9_side_rows(int side) {
  static const std::array<Quad9SideRows, 4> rows = {{{{0, 4, 1}, {7, 8, 5}, {3, 6, 2}},
                                                     {{1, 5, 2}, {4, 8, 6}, {0, 7, 3}},
                                                     {{2, 6, 3}, {5, 8, 7}, {1, 4, 0}},
                                                     {{3, 7, 0}, {6, 8, 4}, {2, 5, 1}}}};
  return rows[std::size_t(side)];
}

// dN* = T^T dN for a particle receding from `side`.
inline NodalVectors<9> receding_trial_gradients(const NodalVectors<9>& dN, int side, double c_c) {
  const Quad9SideRows& s = quad9_side_rows(side);
  NodalVectors<9> g = dN;
  for (int k = 0; k < 3; ++k) {
    const auto f = dN.row(s.face[std::size_t(k)]);
    g.row(s.face[std::size_t(k)]) = (1.0 - c_c) * f;
    g.row(s.next[std::size_t(k)]) += (4.0 / 3.0) * c_c * f;
    g.row(s.far[std::size_t(k)]) -= (1.0 / 3.0) * c_c * f;
  }
  return g;
}

}  // namespace loom
