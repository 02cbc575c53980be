// Dof numbering (engine/linalg/dof_map): free dofs numbered node by node; prescribed and absent dofs
// get no equation.
#include <gtest/gtest.h>

#include "engine/linalg/dof_map.hpp"

namespace loom {

TEST(DofMap, NumbersFreeDofsNodeByNode) {
  using K = DofKind;
  DofMap d;
  d.build(2, {K::free, K::prescribed, K::free, K::free, K::absent, K::free});
  EXPECT_EQ(d.per_node, 2);
  EXPECT_EQ(d.n_nodes(), 3);
  EXPECT_EQ(d.n_dofs(), 6);
  EXPECT_EQ(d.n_free, 4);
  EXPECT_EQ(d.equation, (std::vector<Index>{0, kNoIndex, 1, 2, kNoIndex, 3}));
  EXPECT_EQ(d.dof(2, 1), 5);
  EXPECT_EQ(d.dof(1, 0), 2);
}

TEST(DofMap, ThreeDofsPerNode) {
  using K = DofKind;
  DofMap d;
  d.build(3, {K::prescribed, K::free, K::absent, K::free, K::free, K::free});
  EXPECT_EQ(d.n_nodes(), 2);
  EXPECT_EQ(d.n_free, 4);
  EXPECT_EQ(d.equation[std::size_t(d.dof(1, 2))], 3);
  EXPECT_EQ(d.equation[std::size_t(d.dof(0, 2))], kNoIndex);
}

TEST(DofMap, RebuildRenumbers) {
  using K = DofKind;
  DofMap d;
  d.build(1, {K::free, K::free, K::free});
  d.build(1, {K::prescribed, K::free});
  EXPECT_EQ(d.n_nodes(), 2);
  EXPECT_EQ(d.n_free, 1);
  EXPECT_EQ(d.equation, (std::vector<Index>{kNoIndex, 0}));
}

TEST(DofMap, EmptyMapHasNoNodes) {
  DofMap d;
  EXPECT_EQ(d.n_nodes(), 0);
  EXPECT_EQ(d.n_dofs(), 0);
}

}  // namespace loom
