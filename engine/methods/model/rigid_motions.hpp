// Which rigid motions a static model leaves free. Without inertia, a connected piece of a body is held only
// by its prescribed displacement components; the tangent is singular (or, after round-off, nearly so and
// the answer an arbitrary rigid shift) unless they fix the piece's three rigid motions: translations along
// x and y and the rotation. A prescribed component u_d at X_i fixes the motions m with
// m_d(X_i) = 0; with m(X) = t + omega e_z x (X - X_c), the row of component d at node i is
//   d = x: [1, 0, -(Y_i - Y_c) / L],   d = y: [0, 1, (X_i - X_c) / L]
// (L: the piece's size, so that the three columns are comparable). The free motions span the null space of
// these rows, found from the eigenvalues of the 3 x 3 matrix A^T A.
#pragma once

#include <string>
#include <vector>

#include "engine/core/types.hpp"
#include "engine/store/cells.hpp"

namespace loom {

struct FreeRigidMotion {
  std::vector<Index> nodes;  // the piece: nodes of cells connected to each other
  int free_motions = 0;      // 1..3
  bool rotation = false;     // one free motion, a rotation about `centre`
  Vec2 centre = Vec2::Zero();
  Vec2 direction = Vec2::Zero();  // one free motion, a translation along it (unit)
  int held_components = 0;        // prescribed components on the piece
  std::string describe() const;   // "can rotate freely about (0, 0)", "can translate freely along x", ...
};

// held[2 i + d] != 0: component d of node i is prescribed. Cells in `blocks` (all of their cells, or the
// listed ones when `active` is given) connect their nodes into pieces.
std::vector<FreeRigidMotion> free_rigid_motions(const std::vector<Vec2>& X, const std::vector<const Cells*>& blocks,
                                                const std::vector<char>& held, const std::vector<Index>* active = nullptr);

}  // namespace loom
