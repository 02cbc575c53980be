// quad9 cells (engine/mesh/quad9_shape.hpp, quad9_grid.cpp) and their location (systems/locate):
// Lagrange property, partition of unity and exact quadratic fields; gradients against central differences
// on a curved (non-affine) cell; the inverse map; the 3 x 3 Gauss rule's degree; graded rectangles with
// midpoint refinement (the sizes of seed 004's grids), and points located by arithmetic.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/graph/step_context.hpp"
#include "engine/mesh/quad9_grid.hpp"
#include "engine/mesh/quad9_shape.hpp"
#include "systems/locate/locate_points.hpp"

namespace loom {
namespace {

const Vec2 kLattice[9] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, -1}, {1, 0}, {0, 1}, {-1, 0}, {0, 0}};

// A curved cell: the lattice of [0, 2] x [0, 1] with every node moved by a smooth quadratic map.
Quad9Coordinates curved_cell() {
  Quad9Coordinates X;
  for (int a = 0; a < 9; ++a) {
    const Vec2 s = kLattice[a];
    X.row(a) << 1.0 + s.x() + 0.1 * s.y() * s.y(), 0.5 + 0.5 * s.y() + 0.08 * s.x() * s.x() - 0.05 * s.x() * s.y();
  }
  return X;
}

TEST(Quad9Shape, LagrangePropertyAndQuadraticFields) {
  for (int a = 0; a < 9; ++a) {
    const Quad9Values N = quad9_shape(kLattice[a]);
    for (int b = 0; b < 9; ++b) EXPECT_NEAR(N[b], a == b ? 1.0 : 0.0, 1e-15);
  }
  // Any biquadratic field is reproduced; its gradient too.
  auto f = [](const Vec2& s) { return 0.3 + s.x() - 2 * s.y() + 0.7 * s.x() * s.y() + s.x() * s.x() * s.y() * s.y() - 0.4 * s.y() * s.y(); };
  Quad9Values nodal;
  for (int a = 0; a < 9; ++a) nodal[a] = f(kLattice[a]);
  for (const Vec2& s : {Vec2(0.3, -0.7), Vec2(-0.9, 0.2), Vec2(0.55, 0.55)}) {
    const Quad9Values N = quad9_shape(s);
    EXPECT_NEAR(N.sum(), 1.0, 1e-15);
    EXPECT_NEAR(N.dot(nodal), f(s), 1e-14);
    const Quad9Gradients dN = quad9_reference_gradients(s);
    EXPECT_NEAR(dN.col(0).sum(), 0.0, 1e-15);
    const double h = 1e-6;
    EXPECT_NEAR(dN.col(0).dot(nodal), (f(s + Vec2(h, 0)) - f(s - Vec2(h, 0))) / (2 * h), 1e-8);
    EXPECT_NEAR(dN.col(1).dot(nodal), (f(s + Vec2(0, h)) - f(s - Vec2(0, h))) / (2 * h), 1e-8);
  }
}

TEST(Quad9Shape, PhysicalGradientsAndInverseMapOnACurvedCell) {
  const Quad9Coordinates X = curved_cell();
  // A field linear in x: its gradient is exact everywhere (isoparametric completeness).
  const Vec2 grad(0.7, -1.3);
  Quad9Values nodal;
  for (int a = 0; a < 9; ++a) nodal[a] = grad.dot(X.row(a).transpose());
  for (const Vec2& s : {Vec2(0.3, -0.7), Vec2(-0.9, 0.2), Vec2(0.55, 0.95)}) {
    double det = 0.0;
    const Quad9Gradients dN = quad9_gradients(X, s, &det);
    EXPECT_GT(det, 0.0);
    EXPECT_NEAR((dN.transpose() * nodal - grad).norm(), 0.0, 1e-13);
    // Gradients against differences through the inverse map: N_a(xi(x)).
    const Vec2 x = X.transpose() * quad9_shape(s);
    Vec2 xi;
    ASSERT_TRUE(quad9_inverse_map(X, x, xi));
    EXPECT_NEAR((xi - s).norm(), 0.0, 1e-13);
    const double h = 1e-6;
    for (int d = 0; d < 2; ++d) {
      Vec2 xp = x, xm = x, sp, sm;
      xp[d] += h, xm[d] -= h;
      ASSERT_TRUE(quad9_inverse_map(X, xp, sp));
      ASSERT_TRUE(quad9_inverse_map(X, xm, sm));
      const Quad9Values fd = (quad9_shape(sp) - quad9_shape(sm)) / (2 * h);
      EXPECT_LE((fd - dN.col(d)).cwiseAbs().maxCoeff(), 1e-7);
    }
  }
}

// A small cell far from the origin (the rolling disk's grid at J = 4 near x = 20): the inverse map converges
// to the coordinates' round-off, every time.
TEST(Quad9Shape, InverseMapOfASmallCellFarFromTheOrigin) {
  const Vec2 lattice[9] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, -1}, {1, 0}, {0, 1}, {-1, 0}, {0, 0}};
  Quad9Coordinates X;
  for (int a = 0; a < 9; ++a) X.row(a) << 20.0375 + 0.0375 * lattice[a].x(), 1.1 + 0.0271 * lattice[a].y();
  for (int k = 0; k < 1000; ++k) {
    const Vec2 s(-1.0 + 2.0 * ((k * 37) % 1000) / 999.0, -1.0 + 2.0 * ((k * 91) % 1000) / 999.0);
    Vec2 xi;
    ASSERT_TRUE(quad9_inverse_map(X, X.transpose() * quad9_shape(s), xi)) << k;
    EXPECT_NEAR((xi - s).norm(), 0.0, 1e-11);
  }
}

TEST(Quad9Shape, GaussRuleIsExactToDegreeFivePerDirection) {
  const Quad9Gauss& rule = quad9_gauss();
  for (int p = 0; p <= 5; ++p)
    for (int q = 0; q <= 5; ++q) {
      double sum = 0.0;
      for (std::size_t k = 0; k < 9; ++k) sum += rule.weight[k] * std::pow(rule.xi[k].x(), p) * std::pow(rule.xi[k].y(), q);
      auto moment = [](int n) { return n % 2 ? 0.0 : 2.0 / (n + 1); };
      EXPECT_NEAR(sum, moment(p) * moment(q), 1e-14) << p << " " << q;
    }
  // The curved cell's area: sum of weight det J = area of the mapped lattice (checked against the same map
  // integrated by a fine midpoint rule).
  const Quad9Coordinates X = curved_cell();
  double gauss = 0.0, fine = 0.0;
  for (std::size_t k = 0; k < 9; ++k) {
    double det = 0.0;
    quad9_gradients(X, rule.xi[k], &det);
    gauss += rule.weight[k] * det;
  }
  const int n = 400;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double det = 0.0;
      quad9_gradients(X, Vec2(-1 + (i + 0.5) * 2.0 / n, -1 + (j + 0.5) * 2.0 / n), &det);
      fine += det * 4.0 / (n * n);
    }
  EXPECT_NEAR(gauss, fine, 1e-5);
}

// Seed 004's rolling-disk grid (the authors' mesh file): 20 x 4 cells on [-2, 22] x [-1.6, 3.4], heights
// growing by 1.25; J = 4 has 20 480 cells and 82 689 nodes, a bottom cell 0.0542 high.
TEST(Quad9Grid, GradedRefinedRectangleHasThePapersSizes) {
  GradedRectangle r;
  r.origin = Vec2(-2.0, -1.6), r.size = Vec2(24.0, 5.0), r.nx = 20, r.ny = 4, r.grading = Vec2(1.0, 1.25);
  const double h0 = 5.0 * 0.25 / (std::pow(1.25, 4) - 1.0);
  EXPECT_NEAR(h0, 0.8672, 5e-5);
  for (int J = 0; J <= 4; ++J) {
    r.refinements = J;
    Nodes<2> nodes;
    Cells cells;
    GridLayout layout;
    build_quad9_grid(r, Formulation::p1, nodes, cells, layout);
    const int n = 1 << J;
    EXPECT_EQ(cells.size(), Index(80 * n * n));
    EXPECT_EQ(nodes.size(), Index(40 * n + 1) * Index(8 * n + 1));
    EXPECT_NEAR(layout.y_lines[1] - layout.y_lines[0], h0 / n, 1e-12);
    EXPECT_EQ(layout.y_lines.back(), 3.4);
    double area = 0.0;
    for (Index c = 0; c < cells.size(); ++c) area += cells.measure[c];
    EXPECT_NEAR(area, 120.0, 1e-9);
    // Mid-side and centre nodes halfway between the corners; colours share no node.
    for (Index c = 0; c < cells.size(); c += 37) {
      const Vec2 x0 = nodes.X[cells.node(c, 0)], x2 = nodes.X[cells.node(c, 2)];
      EXPECT_NEAR((nodes.X[cells.node(c, 8)] - 0.5 * (x0 + x2)).norm(), 0.0, 1e-12);
      EXPECT_NEAR((nodes.X[cells.node(c, 4)] - 0.5 * (nodes.X[cells.node(c, 0)] + nodes.X[cells.node(c, 1)])).norm(), 0.0, 1e-12);
    }
    if (J == 4) {
      EXPECT_NEAR(layout.y_lines[1] - layout.y_lines[0], 0.0542, 5e-5);
    }
  }
}

TEST(Quad9Grid, LocatesPointsByArithmetic) {
  GradedRectangle r;
  r.origin = Vec2(-0.5, -0.5), r.size = Vec2(1.0, 1.0), r.nx = 3, r.ny = 2, r.grading = Vec2(1.5, 0.7), r.refinements = 2;
  Nodes<2> nodes;
  Cells cells;
  GridLayout layout;
  build_quad9_grid(r, Formulation::p1, nodes, cells, layout);
  Points<2> points;
  points.X.use(), points.u.use();
  const Vec2 xs[] = {{-0.5, -0.5}, {0.5, 0.5}, {0.1234, -0.321}, {-0.4999, 0.4999}, {0.2, 0.0}};
  points.resize(5);
  for (Index p = 0; p < 5; ++p) points.X[p] = xs[p], points.u[p].setZero();
  PointLocations loc;
  loc.xi.use();
  StepContext ctx;
  locate_points(ctx, layout, cells, nodes, points, loc);
  for (Index p = 0; p < 5; ++p) {
    const Index c = loc.cell[p];
    ASSERT_NE(c, kNoIndex);
    EXPECT_LE(loc.xi[p].cwiseAbs().maxCoeff(), 1.0 + 1e-12);
    Quad9Coordinates X;
    for (int a = 0; a < 9; ++a) X.row(a) = nodes.X[cells.node(c, a)].transpose();
    EXPECT_NEAR((X.transpose() * quad9_shape(loc.xi[p]) - xs[p]).norm(), 0.0, 1e-14);
  }
  points.u[2] = Vec2(5.0, 0.0);  // outside
  EXPECT_THROW(locate_points(ctx, layout, cells, nodes, points, loc), RunError);
}

}  // namespace
}  // namespace loom
