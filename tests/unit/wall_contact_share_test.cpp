// A node's share of the boundary facing each wall plane (measure_contact_areas, systems/assemble/wall_contact.hpp):
// each boundary edge counts by its projection on the plane, and only if its outward normal points into the wall.
// The case that matters is the tip of a sharp nose lying on the ground: its base edge faces the ground, its front
// edge faces away, and the tip must keep the base edge's share (with the summed area vector, -(a_base + a_front) . n
// is zero for this wedge, and a flow's nose tip went through the ground unopposed).
#include <gtest/gtest.h>

#include <cmath>

#include "systems/assemble/wall_contact.hpp"

namespace loom {
namespace {

Walls ground_and_side() {
  Walls w;
  w.walls.push_back(Wall{"ground", 1.0, false, kNoIndex});
  w.walls.push_back(Wall{"side", 1.0, false, kNoIndex});
  w.planes.push_back({Vec2(0.0, 0.0), Vec2(0.0, 1.0), 0});   // y = 0, material above
  w.planes.push_back({Vec2(1.0, 0.0), Vec2(-1.0, 0.0), 1});  // x = 1, material to the left
  return w;
}

// A wedge pointing in -x with its tip at the origin: base (0,0)-(1,0), back (1,0)-(1,0.2), front (1,0.2)-(0,0).
Nodes<2> wedge_nodes(bool quadratic) {
  Nodes<2> n;
  n.contact_share.use();
  std::vector<Vec2> X = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 0.2)};
  if (quadratic) X.insert(X.end(), {Vec2(0.5, 0), Vec2(1, 0.1), Vec2(0.5, 0.1)});  // mid-nodes of sides 0, 1, 2
  n.resize(Index(X.size()));
  for (std::size_t i = 0; i < X.size(); ++i) n.X[Index(i)] = X[i];
  return n;
}

Cells wedge_cells(bool quadratic) {
  Cells c(quadratic ? CellType::tri6 : CellType::tri3, quadratic ? Formulation::tri6 : Formulation::p1);
  c.nodes.values() = quadratic ? std::vector<Index>{0, 1, 2, 3, 4, 5} : std::vector<Index>{0, 1, 2};
  c.body.values() = {0};
  return c;
}

TEST(WallContactShare, TheTipOfASharpNoseKeepsItsBaseEdgesShare) {
  const Walls walls = ground_and_side();
  Nodes<2> nodes = wedge_nodes(false);
  measure_contact_areas(StepContext{}, walls, {wedge_cells(false)}, nodes);
  // Ground: half the base edge to each of its ends; the back edge is vertical, the front edge faces up.
  EXPECT_DOUBLE_EQ(nodes.contact_share[0][0], 0.5);
  EXPECT_DOUBLE_EQ(nodes.contact_share[1][0], 0.5);
  EXPECT_DOUBLE_EQ(nodes.contact_share[2][0], 0.0);
  // Side wall at x = 1: the back edge (length 0.2) faces it; the front edge faces -x, away from it.
  EXPECT_DOUBLE_EQ(nodes.contact_share[0][1], 0.0);
  EXPECT_DOUBLE_EQ(nodes.contact_share[1][1], 0.1);
  EXPECT_DOUBLE_EQ(nodes.contact_share[2][1], 0.1);
  // The entries past the scene's planes stay zero.
  for (Index i = 0; i < 3; ++i) EXPECT_TRUE(nodes.contact_share[i].tail(kMaxWallPlanes - 2).isZero(0.0));
}

TEST(WallContactShare, QuadraticEdgesShareAsTheirEdgeShapeFunctions) {
  const Walls walls = ground_and_side();
  Nodes<2> nodes = wedge_nodes(true);
  measure_contact_areas(StepContext{}, walls, {wedge_cells(true)}, nodes);
  EXPECT_DOUBLE_EQ(nodes.contact_share[0][0], 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(nodes.contact_share[1][0], 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(nodes.contact_share[3][0], 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(nodes.contact_share[5][0], 0.0);  // the front edge's mid-node faces up
  EXPECT_NEAR(nodes.contact_share[4][1], 0.2 * 2.0 / 3.0, 1e-15);
}

TEST(WallContactShare, ItFollowsTheBoundaryInTheStartOfStepConfiguration) {
  // Tilt the wedge about its tip by u_n so that its base edge rises with slope 0.1: the base's projection on the
  // ground is cos(tilt) times its length 1; the back edge now faces a little away from the ground and adds nothing
  // to node 1 (the summed area vector would subtract its 0.2 sin(tilt)).
  const Walls walls = ground_and_side();
  Nodes<2> nodes = wedge_nodes(false);
  const double c = 1.0 / std::sqrt(1.01), s = 0.1 * c;
  for (Index i = 0; i < 3; ++i) {
    const Vec2 X = nodes.X[i];
    nodes.u_n[i] = Vec2(c * X.x() - s * X.y(), s * X.x() + c * X.y()) - X;
  }
  measure_contact_areas(StepContext{}, walls, {wedge_cells(false)}, nodes);
  EXPECT_NEAR(nodes.contact_share[0][0], 0.5 * c, 1e-15);
  EXPECT_NEAR(nodes.contact_share[1][0], 0.5 * c, 1e-15);
  // The front edge, rotated by the tilt, still faces up: the tip keeps only the base.
  EXPECT_NEAR(nodes.contact_share[2][0], 0.0, 1e-15);
}

}  // namespace
}  // namespace loom
