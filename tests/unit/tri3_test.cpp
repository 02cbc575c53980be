// Linear triangle (systems/assemble/elements/tri3.hpp): gradients and signed area, quadrature rule.
#include <gtest/gtest.h>

#include "systems/assemble/elements/tri3.hpp"

namespace loom {
namespace {

const Vec2 kA(0.3, -0.2), kB(2.1, 0.4), kC(0.9, 1.7);

}  // namespace

TEST(Tri3Gradients, SignedAreaOfAHandCheckedTriangle) {
  Tri3Gradients dN;
  EXPECT_DOUBLE_EQ(tri3_gradients(Vec2(0, 0), Vec2(2, 0), Vec2(0, 1), dN), 1.0);
  EXPECT_DOUBLE_EQ(tri3_gradients(Vec2(0, 0), Vec2(0, 1), Vec2(2, 0), dN), -1.0);  // clockwise
  EXPECT_EQ(tri3_gradients(Vec2(0, 0), Vec2(1, 1), Vec2(2, 2), dN), 0.0);           // degenerate
}

TEST(Tri3Gradients, HandCheckedValuesOnARightTriangle) {
  // N0 = 1 - x/2 - y, N1 = x/2, N2 = y on (0,0), (2,0), (0,1).
  Tri3Gradients dN;
  tri3_gradients(Vec2(0, 0), Vec2(2, 0), Vec2(0, 1), dN);
  Tri3Gradients expected;
  expected << -0.5, -1.0, 0.5, 0.0, 0.0, 1.0;
  EXPECT_LE((dN - expected).norm(), 1e-15);
}

TEST(Tri3Gradients, PartitionOfUnityGradientsSumToZero) {
  Tri3Gradients dN;
  tri3_gradients(kA, kB, kC, dN);
  EXPECT_LE(dN.colwise().sum().norm(), 1e-14);
}

TEST(Tri3Gradients, ReproduceTheGradientOfALinearField) {
  Tri3Gradients dN;
  tri3_gradients(kA, kB, kC, dN);
  const Vec2 g(1.7, -0.8);
  auto f = [&](const Vec2& x) { return 4.2 + g.dot(x); };
  const Vec2 grad = f(kA) * dN.row(0).transpose() + f(kB) * dN.row(1).transpose() + f(kC) * dN.row(2).transpose();
  EXPECT_LE((grad - g).norm(), 1e-14);
  // Coordinates themselves: sum_A x_A (x) dN^A = I.
  Eigen::Matrix2d I = kA * dN.row(0) + kB * dN.row(1) + kC * dN.row(2);
  EXPECT_LE((I - Eigen::Matrix2d::Identity()).norm(), 1e-14);
}

TEST(Tri3Gradients, AreInvariantUnderCyclicRelabelling) {
  Tri3Gradients a, b;
  const double area_a = tri3_gradients(kA, kB, kC, a);
  const double area_b = tri3_gradients(kB, kC, kA, b);
  EXPECT_DOUBLE_EQ(area_a, area_b);
  EXPECT_LE((a.row(1) - b.row(0)).norm() + (a.row(2) - b.row(1)).norm() + (a.row(0) - b.row(2)).norm(), 1e-14);
}

TEST(Tri3Rule3, IntegratesQuadraticsExactly) {
  // On (0,0), (1,0), (0,1): int x^2 = 1/12, int x y = 1/24, int 1 = 1/2.
  const Vec2 corner[3] = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  double ixx = 0, ixy = 0, i1 = 0;
  for (const auto& q : kTri3Rule3) {
    EXPECT_DOUBLE_EQ(q[0] + q[1] + q[2], 1.0);
    const Vec2 x = q[0] * corner[0] + q[1] * corner[1] + q[2] * corner[2];
    const double w = 0.5 / 3.0;
    ixx += w * x.x() * x.x(), ixy += w * x.x() * x.y(), i1 += w;
  }
  EXPECT_NEAR(ixx, 1.0 / 12, 1e-15);
  EXPECT_NEAR(ixy, 1.0 / 24, 1e-15);
  EXPECT_NEAR(i1, 0.5, 1e-15);
}

}  // namespace loom
