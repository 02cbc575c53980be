// systems/locate: every point is found in a cell that contains it (triangles and quad4 squares), its shape functions reproduce its
// position, the arithmetic (structured) and walking (unstructured) searches agree with a brute-force
// search, points on the outer boundary are kept, and a point outside the grid is an error naming it.
#include <gtest/gtest.h>

#include <random>

#include "engine/core/errors.hpp"
#include "engine/mesh/background_grid.hpp"
#include "engine/mesh/generators.hpp"
#include "engine/mesh/grid_shape.hpp"
#include "systems/locate/locate_points.hpp"
#include "tests/support/grid_stores.hpp"

namespace loom {
namespace {

using Grid = testing::GridStores;

Grid rectangle_grid(GridPattern pattern, bool structured, double distortion = 0.0) {
  RectangleSpec spec;
  spec.origin = Vec2(-1.0, 0.5);
  spec.size = Vec2(3.0, 2.0);
  spec.nx = 12, spec.ny = 7;
  spec.pattern = pattern;
  MeshData mesh = generate_rectangle(spec);
  distort_interior_nodes(mesh, distortion, 5);
  Grid g;
  build_background_grid(mesh, structured && distortion == 0.0 ? &spec : nullptr, Formulation::p1, g.nodes, g.cells, g.layout);
  return g;
}

Grid cooks_grid() {
  Grid g;
  build_background_grid(generate_cooks_membrane(9, 6, GridPattern::alternating), nullptr, Formulation::p1, g.nodes, g.cells, g.layout);
  return g;
}

Vec3 bary(const Grid& g, Index c, const Vec2& x) {
  Eigen::Matrix3d A;
  for (int a = 0; a < 3; ++a) A.col(a) << g.nodes.X[g.cells.node(c, a)], 1.0;
  return A.inverse() * Vec3(x.x(), x.y(), 1.0);
}

// Random points inside the grid: in random cells at random barycentric coordinates.
std::vector<Vec2> points_inside(const Grid& g, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<Index> cell(0, g.cells.size() - 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec2> r;
  for (int k = 0; k < n; ++k) {
    double a = u(rng), b = u(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const Index c = cell(rng);
    r.push_back((1 - a - b) * g.nodes.X[g.cells.node(c, 0)] + a * g.nodes.X[g.cells.node(c, 1)] + b * g.nodes.X[g.cells.node(c, 2)]);
  }
  return r;
}

void expect_found(const Grid& g, const Vec2& x, Index hint) {
  Vec4 N;
  const Index c = find_cell(g.layout, g.cells, g.nodes, x, hint, N);
  ASSERT_NE(c, kNoIndex) << "x = " << x.transpose();
  EXPECT_GE(bary(g, c, x).minCoeff(), -1e-9) << "cell " << c << " does not hold x = " << x.transpose();
  EXPECT_LE((N.head<3>() - bary(g, c, x)).norm(), 1e-12);
  EXPECT_EQ(N[3], 0.0);
  Vec2 back = Vec2::Zero();
  for (int a = 0; a < 3; ++a) back += N[a] * g.nodes.X[g.cells.node(c, a)];
  EXPECT_LE((back - x).norm(), 1e-12 * g.layout.width());
}

TEST(LocatePoints, ArithmeticSearchFindsTheCellOfEveryPoint) {
  for (auto pattern : {GridPattern::right, GridPattern::alternating}) {
    const Grid g = rectangle_grid(pattern, true);
    ASSERT_TRUE(g.layout.structured);
    for (const Vec2& x : points_inside(g, 2000, 3)) expect_found(g, x, kNoIndex);
  }
}

TEST(LocatePoints, WalkAndBucketsFindTheCellOfEveryPoint) {
  for (const Grid& g : {rectangle_grid(GridPattern::alternating, false, 0.2), cooks_grid()}) {
    ASSERT_FALSE(g.layout.structured);
    std::mt19937 rng(9);
    std::uniform_int_distribution<Index> cell(0, g.cells.size() - 1);
    for (const Vec2& x : points_inside(g, 2000, 4)) {
      expect_found(g, x, kNoIndex);  // buckets
      expect_found(g, x, cell(rng));  // walk from a random cell
    }
  }
}

TEST(LocatePoints, KeepsPointsOnTheOuterBoundaryAndRejectsPointsOutside) {
  for (const Grid& g : {rectangle_grid(GridPattern::right, true), cooks_grid()}) {
    for (Index i = 0; i < g.nodes.size(); ++i) expect_found(g, g.nodes.X[i], 0);  // every node, corners included
    Vec4 N;
    const Vec2 far = g.layout.hi + Vec2(1e-3, 0.0) * g.layout.width();
    EXPECT_EQ(find_cell(g.layout, g.cells, g.nodes, far, kNoIndex, N), kNoIndex);
    EXPECT_EQ(find_cell(g.layout, g.cells, g.nodes, far, 0, N), kNoIndex);
  }
}

Points<2> make_points(const std::vector<Vec2>& X) {
  Points<2> p;
  p.X.use(), p.u.use();
  p.resize(Index(X.size()));
  for (Index i = 0; i < p.X.size(); ++i) p.X[i] = X[std::size_t(i)];
  return p;
}

// quad4: the point's square by arithmetic, bilinear shape functions that are nonnegative, sum to one and
// reproduce the position (also the grid's corners and outer edges); gradients that reproduce the gradient
// of a bilinear field, checked against central differences of N.
TEST(LocatePoints, QuadGridFindsTheSquareAndItsBilinearShapeFunctions) {
  RectangleSpec spec;
  spec.origin = Vec2(-1.0, 0.5), spec.size = Vec2(3.0, 2.0), spec.nx = 12, spec.ny = 7;
  Grid g;
  build_quad_grid(spec, Formulation::p1, g.nodes, g.cells, g.layout);
  ASSERT_EQ(g.cells.size(), 84);
  ASSERT_EQ(g.cells.stride, 4);
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> ux(-1.0, 2.0), uy(0.5, 2.5);
  std::vector<Vec2> xs;
  for (int k = 0; k < 2000; ++k) xs.emplace_back(ux(rng), uy(rng));
  for (Index i = 0; i < g.nodes.size(); ++i) xs.push_back(g.nodes.X[i]);
  auto field = [](const Vec2& x) { return 0.3 + 1.1 * x.x() - 0.7 * x.y() + 0.9 * x.x() * x.y(); };
  for (std::size_t k = 0; k < xs.size(); ++k) {
    const Vec2& x = xs[k];
    Vec4 N;
    const Index c = find_cell(g.layout, g.cells, g.nodes, x, kNoIndex, N);
    ASSERT_NE(c, kNoIndex) << "x = " << x.transpose();
    if (k < 2000) {
      EXPECT_EQ(c, Index(int((x.y() - 0.5) / (2.0 / 7))) * 12 + int((x.x() + 1.0) / 0.25));
    }
    EXPECT_GE(N.minCoeff(), -1e-12);
    EXPECT_NEAR(N.sum(), 1.0, 1e-14);
    Vec2 back = Vec2::Zero();
    double f = 0.0;
    for (int a = 0; a < 4; ++a) back += N[a] * g.nodes.X[g.cells.node(c, a)], f += N[a] * field(g.nodes.X[g.cells.node(c, a)]);
    EXPECT_LE((back - x).norm(), 1e-13);
    EXPECT_NEAR(f, field(x), 1e-13);  // bilinear fields are reproduced
    const CornerGradients<4> dN = grid_shape_gradients<4>(g.cells, g.nodes, c, N);
    Vec2 grad = Vec2::Zero();
    for (int a = 0; a < 4; ++a) grad += field(g.nodes.X[g.cells.node(c, a)]) * dN.row(a).transpose();
    EXPECT_LE((grad - Vec2(1.1 + 0.9 * x.y(), -0.7 + 0.9 * x.x())).norm(), 1e-12);
    for (int d = 0; d < 2; ++d) {
      const Vec2 e = 1e-6 * Vec2::Unit(d);
      const Vec4 dN_fd = (grid_shape_at(g.cells, g.nodes, c, x + e) - grid_shape_at(g.cells, g.nodes, c, x - e)) / 2e-6;
      EXPECT_LE((dN_fd - dN.col(d)).norm(), 1e-8);
    }
  }
  Vec4 N;
  EXPECT_EQ(find_cell(g.layout, g.cells, g.nodes, Vec2(2.01, 1.0), kNoIndex, N), kNoIndex);
  // Neighbours across the sides (a, a + 1): the square's right neighbour is across side 1.
  EXPECT_EQ(g.cells.neighbour[4 * 13 + 1], 14);
  EXPECT_EQ(g.cells.neighbour[4 * 13 + 2], 25);
  EXPECT_EQ(g.cells.neighbour[4 * 0 + 0], kNoIndex);
}

TEST(LocatePoints, GroupsPointsByCellInIndexOrder) {
  const Grid g = rectangle_grid(GridPattern::alternating, true);
  const Points<2> points = make_points(points_inside(g, 500, 8));
  PointLocations loc;
  StepContext ctx;
  locate_points(ctx, g.layout, g.cells, g.nodes, points, loc);
  ASSERT_EQ(loc.cell_offsets.size(), std::size_t(g.cells.size()) + 1);
  ASSERT_EQ(loc.cell_offsets.back(), points.X.size());
  for (Index c = 0; c < g.cells.size(); ++c)
    for (Index k = 0; k < loc.count_in(c); ++k) {
      EXPECT_EQ(loc.cell[loc.points_in(c)[k]], c);
      if (k > 0) {
        EXPECT_LT(loc.points_in(c)[k - 1], loc.points_in(c)[k]);
      }
    }
}

TEST(LocatePoints, APointOutsideTheGridIsAnErrorNamingIt) {
  const Grid g = cooks_grid();
  Points<2> points = make_points(points_inside(g, 50, 11));
  points.u[17] = Vec2(100.0, 0.0);
  PointLocations loc;
  StepContext ctx;
  ctx.step = 4;
  try {
    locate_points(ctx, g.layout, g.cells, g.nodes, points, loc);
    FAIL() << "no error";
  } catch (const RunError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("particle 17"), std::string::npos) << what;
    EXPECT_NE(what.find("step 4"), std::string::npos) << what;
    EXPECT_NE(what.find("left the background grid"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace loom
