// Penalty contact of mesh nodes with rigid walls (seed 001 §1.8; engine/store/walls.hpp).
//
// A node i of a body the plane acts on, at x = X + u, is in contact when g = (x - x_w) . n <= 0. Its share of
// the boundary that faces the wall, A_i = sum_e max(0, -a_ie . n) over its boundary edges e, a_ie its share of
// edge e's length times the edge's outward normal in B_n (fixed during the step, so the tangent is exact),
// carries the penalty
//   r_i += k_N A_i g n,                    K_ii += k_N A_i n n^T          (normal)
//   r_i += k_N A_i (I - n n^T)(x - c),     K_ii += k_N A_i (I - n n^T)    (stick walls)
// A_i is the node's tributary length of the penalty integral int k_N g N_i over the boundary that faces the
// wall, each edge counted by its projection on the wall: a corner on a flat base counts only its base edge, and
// the tip of a sharp nose its base edge, whatever its front edge does (a weight max(0, -(sum_e a_ie) . n) of
// the summed area vector lets the front edge cancel the base and the tip go through the wall).
// c is the node's first-contact point: where it touched at an earlier converged step, or else where its path
// in this step, x_n -> x, crosses the plane: c = x_n + s (x - x_n), s = g_n / (g_n - g), so that the tangential
// force of an arriving node grows from zero with its penetration, x - c = phi (x - x_n), phi = -g / (g_n - g),
// and the residual stays continuous where it touches (the projection of x_n would switch on k_N A (x - x_n)_t at
// once: a jump that stalls Newton on the nose of a spreading flow). The tangent then has the unsymmetric part
// k_N A (I - n n^T)(x - x_n) (d phi / dg) n^T, d phi / dg = -g_n / (g_n - g)^2: exact with UMFPACK (the mixed
// elements), its upper triangle only with an SPD back-end (displacement elements), in the step a node touches. A
// node already behind the plane at the start of the step (g_n <= 0: a particle inserted there) takes the
// projection of x_n. The residual holds f_int - f_ext, so the force the
// wall exerts on the node is minus these terms. A resting body's nodes settle at g = -p / k_N (p the contact
// pressure): k_N = 100 E / h keeps g below 1 % of h while p < E.
//
// 3D: the same with planes and the boundary faces of the tetrahedra: a face's area vector a_f = (b - a) x (c - a) / 2
// (outward), each corner's share a third of it (tet10: the corners 0 and each mid-edge node a third, the integrals
// of the quadratic face's shape functions).
#pragma once

#include <type_traits>
#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/walls.hpp"

namespace loom {

// The penalty terms of one node, x its current and x_n its start-of-step position, k = k_N A_i; `held`: it
// holds `held_point` from an earlier step.
template <int D = 2>
struct NodeContactT {
  Vec<D> r = Vec<D>::Zero();  // the residual's part (the wall pushes with minus this)
  Eigen::Matrix<double, D, D> K = Eigen::Matrix<double, D, D>::Zero();
  double penetration = 0.0;
};
using NodeContact = NodeContactT<2>;
template <int D>
NodeContactT<D> node_contact(const WallPlaneT<D>& p, double k, bool stick, bool held, const std::type_identity_t<Vec<D>>& held_point,
                             const std::type_identity_t<Vec<D>>& x_n, const std::type_identity_t<Vec<D>>& x);

// Where a node not yet held by a stick wall is anchored when it ends the step at x behind it (see above).
template <int D>
Vec<D> first_contact_point(const WallPlaneT<D>& p, const std::type_identity_t<Vec<D>>& x_n, const std::type_identity_t<Vec<D>>& x);

// Each node's share of the boundary in B_n facing each wall plane, A_i above: its share of each boundary edge
// (half of it on linear cells; 1/6 to the corners and 2/3 to the mid-node of the three-node edges of tri6 and
// quad9, the integrals of their edge shape functions) times the edge's length projected on the plane, for the
// edges whose outward normal points into the wall. Interior nodes get 0.
template <int D>
void measure_contact_areas(const StepContext& ctx, const WallsT<D>& walls, const std::vector<Cells>& cells, Nodes<D>& nodes);

// Adds the penalty terms of every node behind a wall to the assembled Newton system (residual_full, residual,
// and with `tangent` the matrix). Each node writes only its own entries.
template <int D>
void add_wall_contact(const WallsT<D>& walls, const std::vector<Index>& node_body, const Nodes<D>& nodes, bool tangent, LinearSystem& system);

// After a converged step, before commit_step moves u into u_n: nodes behind a stick wall keep (or get) their
// first-contact point; nodes that left every stick wall forget it.
template <int D>
void commit_wall_contact(const StepContext& ctx, const WallsT<D>& walls, const std::vector<Index>& node_body, Nodes<D>& nodes);

// The force each wall exerts on the bodies and its largest penetration, at the converged state (u_n). Nodes whose
// displacement is prescribed in both directions are left out here and in add_wall_contact.
template <int D>
std::vector<WallResult> wall_results(const WallsT<D>& walls, const std::vector<Index>& node_body, const Nodes<D>& nodes, const DofMap& dofs);

}  // namespace loom
