// Probes `extent` and `pressure_jump` (systems/output/evaluate_probes) on tiny meshes whose states are set
// by hand: the stores come from FemModel on a scene text, then u_n and the point history F_n are written
// directly, and the expected values are worked out in the comments.
//
// Fixture: body "a" is the rectangle [0, 2] x [0, 1] cut into 2 x 1 squares, each split by one diagonal
// (pattern "right"): corner nodes at x in {0, 1, 2}, y in {0, 1}; four cells; three interior edges (the two
// diagonals and the vertical edge x = 1). Body "b" is a unit square far away, [10, 11] x [10, 11]: its nodes
// would dominate any extent of "a" that leaked into it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/methods/model/fem_model.hpp"
#include "systems/output/evaluate_probes.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

std::string scene_text(const std::string& element, const std::string& model) {
  return "[scene]\nname = \"probes\"\n[time]\ndt = 1.0\nsteps = 1\n"
         "[[material]]\nname = \"m\"\nmodel = \"" + model + "\"\nK = 1.0\nG = 0.6\n"
         "[[body]]\nname = \"a\"\nmaterial = \"m\"\nelement = \"" + element + "\"\n"
         "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [2.0, 1.0], divisions = [2, 1], pattern = \"right\" }\n"
         "[[body]]\nname = \"b\"\nmaterial = \"m\"\nelement = \"" + element + "\"\n"
         "mesh = { generator = \"rectangle\", origin = [10.0, 10.0], size = [1.0, 1.0], divisions = [1, 1] }\n"
         "[[probe]]\nname = \"x_max\"\nkind = \"extent\"\nbody = \"a\"\ncomponent = \"x\"\n"
         "[[probe]]\nname = \"x_min\"\nkind = \"extent\"\nbody = \"a\"\ncomponent = \"x\"\nbound = \"min\"\n"
         "[[probe]]\nname = \"y_max\"\nkind = \"extent\"\nbody = \"a\"\ncomponent = \"y\"\nbound = \"max\"\n"
         "[[probe]]\nname = \"y_min\"\nkind = \"extent\"\nbody = \"a\"\ncomponent = \"y\"\nbound = \"min\"\n"
         "[[probe]]\nname = \"jump_a\"\nkind = \"pressure_jump\"\nbody = \"a\"\n"
         "[[probe]]\nname = \"jump_b\"\nkind = \"pressure_jump\"\nbody = \"b\"\n"
         "[[probe]]\nname = \"y_max_b\"\nkind = \"extent\"\nbody = \"b\"\ncomponent = \"y\"\n"
         "[output]\nevery = 0\n";
}

struct Probed {
  FemModel model;
  explicit Probed(const std::string& element, const std::string& model_name = "linear_elastic")
      : model(testing::scene_from_text(scene_text(element, model_name))) {}

  std::vector<double> evaluate() {
    const ProbePlan plan = plan_probes(model.scene, model.nodes, model.cells, model.node_body);
    StepContext ctx;
    ctx.scene = &model.scene;
    std::vector<double> values;
    evaluate_probes(ctx, plan, model.materials, model.nodes, model.cells, model.quad, model.system, model.bc, 0, RemeshStats{}, {}, values);
    return values;
  }
  // Sets F_n = diag(1 + e, 1 + e, 1) at point q of cell c of body "a" (cells of "a" come first in the block).
  void set_strain(Index c, int q, double e) {
    QuadPoints<2>& quad = model.quad[0];
    Mat3 F = Mat3::Identity();
    F(0, 0) = F(1, 1) = 1.0 + e;
    quad.F_n[c * quad.per_cell + q] = F;
  }
  // The cells of body "a" in square 0 (x <= 1) and square 1, and which of each touches the edge x = 1.
  void squares(std::vector<Index>& left, std::vector<Index>& right, Index& left_at_edge, Index& right_at_edge) const {
    const Cells& cells = model.cells[0];
    for (Index c = 0; c < cells.size(); ++c) {
      if (cells.body[c] != 0) continue;
      double x_mean = 0.0;
      int on_edge = 0;
      for (int k = 0; k < 3; ++k) {
        const double x = model.nodes.X[cells.node(c, k)].x();
        x_mean += x / 3.0;
        on_edge += std::abs(x - 1.0) < 1e-12;
      }
      (x_mean < 1.0 ? left : right).push_back(c);
      if (on_edge == 2) (x_mean < 1.0 ? left_at_edge : right_at_edge) = c;
    }
  }
};

// With K = 1 and eps = diag(e, e, 0), the small-strain stress is sigma = lambda tr(eps) I + 2 mu eps, so
// p = -tr(sigma) / 3 = -(3 lambda 2e + 2 mu 2e) / 3 = -2 (lambda + 2 mu / 3) e = -2 K e = -2 e.
double linear_pressure(double e) { return -2.0 * e; }

TEST(EvaluateProbes, ExtentIsTheLargestOrSmallestConvergedCoordinateOfTheBody) {
  Probed p("p1");
  Nodes<2>& nodes = p.model.nodes;
  ASSERT_EQ(nodes.size(), 6 + 4);
  // u_n(X) = (0.3 - 0.9 X_x X_y, 0.1 - 0.2 X_x^2), so the current positions x = X + u_n are
  //   (0,0) -> (0.3, 0.1)   (1,0) -> (1.3, -0.1)   (2,0) -> (2.3, -0.7)
  //   (0,1) -> (0.3, 1.1)   (1,1) -> (0.4,  0.9)   (2,1) -> (0.5,  0.3)
  // x: max 2.3, min 0.3; y: max 1.1 (at (0,1), not at the right end), min -0.7. The iterate u holds
  // something else: the probes read the converged state.
  for (Index i = 0; i < nodes.size(); ++i) {
    const Vec2 X = nodes.X[i];
    nodes.u_n[i] = Vec2(0.3 - 0.9 * X.x() * X.y(), 0.1 - 0.2 * X.x() * X.x());
    nodes.u[i] = Vec2(50.0, -50.0);
  }
  // Body "b" (nodes at 10 .. 11) moved up by 2: its own extent sees it, body "a"'s do not.
  for (Index i = 0; i < nodes.size(); ++i)
    if (p.model.node_body[std::size_t(i)] == 1) nodes.u_n[i] = Vec2(0.0, 2.0);
  const std::vector<double> v = p.evaluate();
  EXPECT_DOUBLE_EQ(v[0], 2.3);
  EXPECT_DOUBLE_EQ(v[1], 0.3);
  EXPECT_DOUBLE_EQ(v[2], 1.1);
  EXPECT_DOUBLE_EQ(v[3], -0.7);
  EXPECT_DOUBLE_EQ(v[6], 13.0);
}

TEST(EvaluateProbes, ExtentIncludesTri6MidNodes) {
  // Mid-nodes are nodes of the body: lifting only the mid-node of the top edge of square 0, at (0.5, 1),
  // by 0.25 makes it the highest point.
  Probed p("tri6");
  Nodes<2>& nodes = p.model.nodes;
  Index mid = kNoIndex;
  for (Index i = 0; i < nodes.size(); ++i)
    if ((nodes.X[i] - Vec2(0.5, 1.0)).norm() < 1e-12) mid = i;
  ASSERT_NE(mid, kNoIndex);
  nodes.u_n[mid] = Vec2(0.0, 0.25);
  EXPECT_DOUBLE_EQ(p.evaluate()[2], 1.25);
}

TEST(EvaluateProbes, PressureJumpIsTheMeanJumpAcrossInteriorEdges) {
  Probed p("p1");
  std::vector<Index> left, right;
  Index left_at_edge = kNoIndex, right_at_edge = kNoIndex;
  p.squares(left, right, left_at_edge, right_at_edge);
  ASSERT_EQ(left.size(), 2u);
  ASSERT_EQ(right.size(), 2u);
  ASSERT_NE(left_at_edge, kNoIndex);
  ASSERT_NE(right_at_edge, kNoIndex);
  const Index left_other = left[0] == left_at_edge ? left[1] : left[0];
  const Index right_other = right[0] == right_at_edge ? right[1] : right[0];

  // 1. Undeformed: no pressure anywhere, no jump.
  EXPECT_EQ(p.evaluate()[4], 0.0);

  // 2. Strains e: left_other 0.01, left_at_edge 0.03, right_at_edge -0.02, right_other 0.00, so the
  //    pressures -2e are -0.02, -0.06, 0.04, 0.0 and the three interior edges carry
  //      diagonal of square 0: |-0.02 - (-0.06)| = 0.04
  //      edge x = 1:            |-0.06 - 0.04|    = 0.10
  //      diagonal of square 1: |0.04 - 0.0|       = 0.04
  //    mean 0.18 / 3 = 0.06. Boundary edges do not count (with them the mean would differ).
  p.set_strain(left_other, 0, 0.01);
  p.set_strain(left_at_edge, 0, 0.03);
  p.set_strain(right_at_edge, 0, -0.02);
  p.set_strain(right_other, 0, 0.0);
  EXPECT_NEAR(linear_pressure(0.03), -0.06, 1e-15);
  std::vector<double> v = p.evaluate();
  EXPECT_NEAR(v[4], 0.06, 1e-14);
  // Body "b" (one square, two cells, one interior edge) is undeformed: 0, and it does not see body "a".
  EXPECT_EQ(v[5], 0.0);

  // 3. A uniform pressure has no jump whatever its size.
  for (Index c : {left_other, left_at_edge, right_at_edge, right_other}) p.set_strain(c, 0, 0.05);
  EXPECT_NEAR(p.evaluate()[4], 0.0, 1e-15);
}

TEST(EvaluateProbes, PressureJumpAveragesTheThreePointsOfTri6Cells) {
  Probed p("tri6");
  std::vector<Index> left, right;
  Index left_at_edge = kNoIndex, right_at_edge = kNoIndex;
  p.squares(left, right, left_at_edge, right_at_edge);
  ASSERT_EQ(p.model.quad[0].per_cell, 3);
  // Square 0 uniform at e = 0.02 (p = -0.04). Cell right_at_edge: e = 0, 0.03, 0.06 at its points, mean
  // 0.03 (p = -0.06); right_other e = 0.03 at every point. Jumps: diagonal 0 -> 0, edge x = 1 ->
  // |-0.04 - (-0.06)| = 0.02, diagonal 1 -> 0; mean 0.02 / 3. Taking one point instead of the mean would
  // give 0.04 / 3 or 0.
  for (Index c : left)
    for (int q = 0; q < 3; ++q) p.set_strain(c, q, 0.02);
  for (int q = 0; q < 3; ++q) {
    p.set_strain(right_at_edge, q, 0.03 * q);
    p.set_strain(right[0] == right_at_edge ? right[1] : right[0], q, 0.03);
  }
  EXPECT_NEAR(p.evaluate()[4], 0.02 / 3.0, 1e-14);
}

TEST(EvaluateProbes, PressureJumpOfTheMixedElementUsesTheNeoHookePressureOfItsHistory) {
  // p1p1_uphi (Neo-Hooke only) stores F~_n at its three points. Neo-Hooke with K = 1, G = 0.6
  // (mu = 0.6, lambda = K - 2 mu / 3 = 0.6) and F = diag(s, s, 1): J = s^2, b = diag(s^2, s^2, 1),
  //   sigma = (mu (b - I) + lambda ln J I) / J,  p = -tr(sigma) / 3 = -(2 mu (s^2 - 1) + 3 lambda ln J) / (3 J).
  // s = 1.1: J = 1.21, p = -(2 0.6 0.21 + 1.8 ln 1.21) / 3.63 = -(0.252 + 0.343117) / 3.63 = -0.163944.
  Probed p("p1p1_uphi", "neo_hooke");
  std::vector<Index> left, right;
  Index left_at_edge = kNoIndex, right_at_edge = kNoIndex;
  p.squares(left, right, left_at_edge, right_at_edge);
  for (Index c : right)
    for (int q = 0; q < 3; ++q) p.set_strain(c, q, 0.1);  // square 1 at s = 1.1, square 0 undeformed
  const double pressure = -(2.0 * 0.6 * 0.21 + 3.0 * 0.6 * std::log(1.21)) / (3.0 * 1.21);
  EXPECT_NEAR(pressure, -0.163944, 1e-6);
  // Only the edge x = 1 jumps: mean |pressure| / 3.
  EXPECT_NEAR(p.evaluate()[4], std::abs(pressure) / 3.0, 1e-14);
}

}  // namespace
}  // namespace loom
