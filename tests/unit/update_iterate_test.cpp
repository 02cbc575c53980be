// update_iterate (systems/update/update_iterate.cpp) in 2D and 3D: a node's D displacements take the first D
// components of its increment, and the next one goes to phi only when the node has D + 1 dofs: in 3D a pure
// displacement node has 3 dofs and its phi (still used by a store) must not move.
#include <gtest/gtest.h>

#include "systems/update/update_iterate.hpp"

namespace loom {
namespace {

template <int D>
void check(int per_node, bool phi_moves) {
  Nodes<D> nodes;
  nodes.phi.use();
  nodes.phi_n.use();  // the two go together (reset_iterate copies phi_n)
  nodes.resize(2);
  LinearSystem system;
  system.dofs.build(per_node, std::vector<DofKind>(std::size_t(2 * per_node), DofKind::free));
  system.increment_full = Eigen::VectorXd::LinSpaced(2 * per_node, 1.0, 2.0 * per_node);
  update_iterate(0.5, system, nodes);
  for (Index i = 0; i < 2; ++i) {
    for (int d = 0; d < D; ++d) EXPECT_DOUBLE_EQ(nodes.u[i][d], 0.5 * (i * per_node + d + 1)) << "node " << i << " component " << d;
    EXPECT_DOUBLE_EQ(nodes.phi[i], phi_moves ? 1.0 + 0.5 * (i * per_node + D + 1) : 1.0) << "node " << i;
  }
  reset_iterate(nodes);
  for (Index i = 0; i < 2; ++i) EXPECT_EQ(nodes.u[i], nodes.u_n[i]);
}

}  // namespace

TEST(UpdateIterate, TwoDimensions) {
  check<2>(2, false);
  check<2>(3, true);
}

TEST(UpdateIterate, ThreeDimensions) {
  check<3>(3, false);
  check<3>(4, true);
}

}  // namespace loom
