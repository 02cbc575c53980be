// free_rigid_motions: the rigid motions that the prescribed components of a static model leave free
// (engine/methods/model/rigid_motions.hpp), on a 2 x 1 block of four triangles and on two separate blocks.
#include <gtest/gtest.h>

#include "engine/methods/model/rigid_motions.hpp"

namespace loom {
namespace {

// Nodes 0..5: (0,0) (1,0) (2,0) (0,1) (1,1) (2,1); four counter-clockwise triangles.
struct Block {
  std::vector<Vec2> X{{0, 0}, {1, 0}, {2, 0}, {0, 1}, {1, 1}, {2, 1}};
  Cells cells{CellType::tri3};
  Block() { cells.nodes.values() = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4}; }
  std::vector<char> held(std::initializer_list<std::pair<int, int>> components) const {
    std::vector<char> h(2 * X.size(), 0);
    for (auto [node, d] : components) h[std::size_t(2 * node + d)] = 1;
    return h;
  }
  std::vector<FreeRigidMotion> free(std::initializer_list<std::pair<int, int>> components) const {
    return free_rigid_motions(X, {&cells}, held(components));
  }
};

TEST(FreeRigidMotions, AClampAtOneCornerAndARollerElsewhereHoldEverything) {
  const Block b;
  EXPECT_TRUE(b.free({{0, 0}, {0, 1}, {2, 1}}).empty());
  EXPECT_TRUE(b.free({{0, 0}, {0, 1}, {3, 0}}).empty());
}

TEST(FreeRigidMotions, AClampAtOneNodeLeavesTheRotationAboutIt) {
  const Block b;
  const auto f = b.free({{4, 0}, {4, 1}});
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].free_motions, 1);
  ASSERT_TRUE(f[0].rotation);
  EXPECT_NEAR(f[0].centre.x(), 1.0, 1e-12);
  EXPECT_NEAR(f[0].centre.y(), 1.0, 1e-12);
  EXPECT_EQ(f[0].describe(), "can rotate freely about (1, 1)");
}

// u_x = 0 at (0, 0) and (0, 1) holds the x translation and the rotation; y stays free. u_y = 0 along the
// bottom holds y and the rotation; x stays free.
TEST(FreeRigidMotions, RollersOfOneDirectionLeaveTheOtherTranslation) {
  const Block b;
  const auto f = b.free({{0, 0}, {3, 0}});
  ASSERT_EQ(f.size(), 1u);
  EXPECT_FALSE(f[0].rotation);
  EXPECT_NEAR(std::abs(f[0].direction.y()), 1.0, 1e-12);
  EXPECT_EQ(f[0].describe(), "can translate freely along y");
  const auto g = b.free({{0, 1}, {1, 1}, {2, 1}});  // u_y = 0 along the bottom
  ASSERT_EQ(g.size(), 1u);
  EXPECT_EQ(g[0].describe(), "can translate freely along x");
}

// u_x = 0 at two nodes of the bottom line: a rotation about a point of that line moves them along y only,
// so it stays free with the y translation (two free motions); nothing held: all three.
TEST(FreeRigidMotions, CountsSeveralFreeMotionsAndNothingHeld) {
  const Block b;
  const auto f = b.free({{0, 0}, {1, 0}});
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].free_motions, 2);
  const auto none = b.free({});
  ASSERT_EQ(none.size(), 1u);
  EXPECT_EQ(none[0].free_motions, 3);
  EXPECT_EQ(none[0].held_components, 0);
}

// Pieces are found from the connectivity: a second block that shares no node needs its own conditions.
TEST(FreeRigidMotions, EachConnectedPieceNeedsItsOwnConditions) {
  Block b;
  for (int k = 0; k < 6; ++k) b.X.push_back(b.X[std::size_t(k)] + Vec2(5, 0));
  std::vector<Index> second;
  for (Index v : b.cells.nodes.values()) second.push_back(v + 6);
  b.cells.nodes.values().insert(b.cells.nodes.values().end(), second.begin(), second.end());
  const auto f = free_rigid_motions(b.X, {&b.cells}, b.held({{0, 0}, {0, 1}, {2, 1}}));
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].free_motions, 3);
  EXPECT_EQ(f[0].nodes.front(), 6);
}

}  // namespace
}  // namespace loom
