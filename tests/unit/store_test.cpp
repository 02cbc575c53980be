#include <gtest/gtest.h>

#include "engine/store/nodes.hpp"
#include "engine/store/points.hpp"

namespace loom {

TEST(Points, SwapRemoveMovesTheLastPointIntoTheGap) {
  Points<2> p;
  p.X.use();
  p.mass.use();
  for (int i = 0; i < 4; ++i) {
    p.X.values().push_back(Vec2(i, 0));
    p.mass.values().push_back(10.0 * i);
  }
  p.swap_remove(1);
  ASSERT_EQ(p.size(), 3);
  EXPECT_EQ(p.X[1], Vec2(3, 0));
  EXPECT_EQ(p.mass[1], 30.0);
  EXPECT_TRUE(p.F.empty());  // an unused column holds nothing
}

TEST(Points, PermuteReordersEveryUsedColumnTogether) {
  Points<2> p;
  p.X.use();
  p.body.use();
  for (int i = 0; i < 3; ++i) p.X.values().push_back(Vec2(i, i)), p.body.values().push_back(i);
  p.permute({2, 0, 1});
  EXPECT_EQ(p.X[0], Vec2(2, 2));
  EXPECT_EQ(p.body[0], 2);
  EXPECT_EQ(p.body[2], 1);
}

TEST(Nodes, ResizeAllocatesOnlyUsedColumns) {
  Nodes<2> n;
  n.v.use();
  n.resize(5);
  EXPECT_EQ(n.X.size(), 5);
  EXPECT_EQ(n.v.size(), 5);
  EXPECT_EQ(n.a.size(), 0);
  EXPECT_FALSE(n.lumped_mass.used());
}

}  // namespace loom
