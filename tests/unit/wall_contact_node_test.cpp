// The penalty of one node against a wall (systems/assemble/wall_contact.hpp): the residual must be continuous
// where a node touches (Newton stalls on a jump) and the tangent must be its derivative. The cases: a node that
// arrives at a stick wall within the step (anchored where its path crosses the plane), one held from an earlier
// step, one already behind the plane at the start, and a frictionless wall, on an inclined plane so that no
// component is trivially zero.
#include <gtest/gtest.h>

#include <cmath>

#include "systems/assemble/wall_contact.hpp"

namespace loom {
namespace {

WallPlane inclined() {
  WallPlane p;
  p.point = Vec2(0.1, -0.2);
  p.normal = Vec2(0.3, 1.0).normalized();
  return p;
}

Vec2 along(const WallPlane& p) { return Vec2(p.normal.y(), -p.normal.x()); }

// Central differences of r against K at x, relative to the largest entry of K.
double tangent_error(const WallPlane& p, double k, bool stick, bool held, const Vec2& c, const Vec2& x_n, const Vec2& x) {
  const NodeContact at = node_contact(p, k, stick, held, c, x_n, x);
  const double h = 1e-7;
  double worst = 0.0;
  for (int j = 0; j < 2; ++j) {
    Vec2 e = Vec2::Zero();
    e[j] = h;
    const Vec2 fd = (node_contact(p, k, stick, held, c, x_n, x + e).r - node_contact(p, k, stick, held, c, x_n, x - e).r) / (2 * h);
    worst = std::max(worst, (fd - at.K.col(j)).cwiseAbs().maxCoeff());
  }
  return worst / at.K.cwiseAbs().maxCoeff();
}

TEST(WallContactNode, AnArrivingNodeIsAnchoredWhereItsPathCrossesThePlane) {
  const WallPlane p = inclined();
  const Vec2 x_n = p.point + 2e-3 * p.normal + 0.4 * along(p);
  const Vec2 x = x_n - 3e-3 * p.normal + 5e-3 * along(p);  // 1e-3 behind the plane, 5e-3 along it
  const Vec2 c = first_contact_point(p, x_n, x);
  EXPECT_NEAR(p.gap(c), 0.0, 1e-15);
  // Two thirds of the way: the gap goes from 2e-3 to -1e-3.
  EXPECT_NEAR((c - x_n).dot(along(p)), 5e-3 * 2.0 / 3.0, 1e-15);
  const NodeContact r = node_contact(p, 1e6, true, false, Vec2::Zero(), x_n, x);
  EXPECT_NEAR(r.r.dot(p.normal), 1e6 * -1e-3, 1e-9);
  EXPECT_NEAR(r.r.dot(along(p)), 1e6 * 5e-3 / 3.0, 1e-9);
  EXPECT_NEAR(r.penetration, 1e-3, 1e-15);
}

TEST(WallContactNode, TheStickForceOfAnArrivingNodeGrowsFromZero) {
  // Across the plane the residual must not jump: at a penetration of 1e-12 it is within k * 1e-12 of zero
  // (the projection of x_n as anchor would give k * 5e-3 along the plane).
  const WallPlane p = inclined();
  const Vec2 x_n = p.point + 2e-3 * p.normal;
  const double k = 1e6;
  for (double g : {1e-12, 0.0, -1e-12}) {
    const Vec2 x = p.point + g * p.normal + 5e-3 * along(p);
    EXPECT_LE(node_contact(p, k, true, false, Vec2::Zero(), x_n, x).r.norm(), 5 * k * 1e-12) << "gap " << g;
  }
}

TEST(WallContactNode, TheTangentIsTheDerivativeOfTheResidual) {
  const WallPlane p = inclined();
  const Vec2 x_n = p.point + 2e-3 * p.normal + 0.4 * along(p);
  const Vec2 x = x_n - 3e-3 * p.normal + 5e-3 * along(p);
  const Vec2 held_point = p.point + 0.39 * along(p);
  const double k = 1e6;
  EXPECT_LT(tangent_error(p, k, true, false, Vec2::Zero(), x_n, x), 1e-7) << "stick, arriving";
  EXPECT_LT(tangent_error(p, k, true, true, held_point, x_n, x), 1e-7) << "stick, held";
  EXPECT_LT(tangent_error(p, k, true, false, Vec2::Zero(), x - 1e-3 * p.normal, x), 1e-7) << "stick, behind at the start";
  EXPECT_LT(tangent_error(p, k, false, false, Vec2::Zero(), x_n, x), 1e-7) << "free slip";
  // The arriving node's tangent is unsymmetric (the anchor moves with the node's gap).
  const NodeContact arriving = node_contact(p, k, true, false, Vec2::Zero(), x_n, x);
  EXPECT_GT((arriving.K - arriving.K.transpose()).norm(), 1e-3 * arriving.K.norm());
}

TEST(WallContactNode, ANodeInFrontOfTheWallFeelsNothing) {
  const WallPlane p = inclined();
  const NodeContact c = node_contact(p, 1e6, true, false, Vec2::Zero(), p.point + 1e-3 * p.normal, p.point + 1e-9 * p.normal);
  EXPECT_TRUE(c.r.isZero(0.0));
  EXPECT_TRUE(c.K.isZero(0.0));
}

}  // namespace
}  // namespace loom
