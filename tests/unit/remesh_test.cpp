// PFEM remeshing (systems/remesh): constrained Delaunay triangulation of a point cloud and the alpha-shape
// test of seed 000 eqs 16-18, on point clouds whose answer is worked out by hand in each test.
//
// Grid fixtures with square cells have four cocircular corners per square, so either diagonal is Delaunay;
// the assertions are therefore on what does not depend on that choice (counts, areas, circumradii, which
// edges exist), never on a particular diagonal.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <vector>

#include "engine/core/errors.hpp"
#include "engine/mesh/generators.hpp"
#include "systems/remesh/remesh.hpp"

namespace loom {
namespace {

using Triple = std::array<Index, 3>;

std::set<Triple> triangle_set(const std::vector<Index>& triangles) {
  std::set<Triple> s;
  for (std::size_t t = 0; t < triangles.size(); t += 3) {
    Triple k{triangles[t], triangles[t + 1], triangles[t + 2]};
    std::sort(k.begin(), k.end());
    s.insert(k);
  }
  return s;
}

bool has_edge(const std::vector<Index>& triangles, Index a, Index b) {
  for (std::size_t t = 0; t < triangles.size(); t += 3)
    for (int s = 0; s < 3; ++s) {
      const Index p = triangles[t + std::size_t(s)], q = triangles[t + std::size_t((s + 1) % 3)];
      if ((p == a && q == b) || (p == b && q == a)) return true;
    }
  return false;
}

// Points of a grid of (nx + 1) x (ny + 1) nodes with spacing h from `origin`, appended to `x`.
void add_grid(std::vector<Vec2>& x, Vec2 origin, int nx, int ny, double h) {
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) x.push_back(origin + h * Vec2(i, j));
}

double signed_area(const std::vector<Vec2>& x, const std::vector<Index>& triangles) {
  double area = 0.0;
  for (std::size_t t = 0; t < triangles.size(); t += 3) {
    const Vec2 &a = x[std::size_t(triangles[t])], &b = x[std::size_t(triangles[t + 1])], &c = x[std::size_t(triangles[t + 2])];
    area += 0.5 * ((b - a).x() * (c - a).y() - (c - a).x() * (b - a).y());
  }
  return area;
}

// A convex square of 5 x 5 nodes (spacing 1): every Delaunay triangle has circumradius sqrt(2)/2 = 0.707,
// so alpha * l_char = 1.1 * 1 keeps all 32 and the body is the whole square.
TEST(RemeshPoints, KeepsAConvexSquareWhole) {
  std::vector<Vec2> x;
  add_grid(x, Vec2(0, 0), 4, 4, 1.0);
  RemeshResult r;
  remesh_points(x, {}, RemeshSettings{1.1, 1.0, false}, {}, r);
  EXPECT_EQ(r.triangles.size(), 3u * 32u);
  EXPECT_EQ(r.rejected, 0);
  EXPECT_EQ(r.isolated, 0);
  EXPECT_NEAR(r.area, 16.0, 1e-12);
  EXPECT_NEAR(signed_area(x, r.triangles), 16.0, 1e-12);  // counter-clockwise: positive
  EXPECT_EQ(r.boundary.size(), 16u);                       // 4 sides of 4 edges
  for (const Edge& e : r.boundary) EXPECT_NEAR((x[std::size_t(e[0])] - x[std::size_t(e[1])]).norm(), 1.0, 1e-12);
}

// Two 3 x 3-node squares (spacing 1) 1.5 apart: [0, 2]^2 and [3.5, 5.5] x [0, 2]. The Delaunay triangulation
// also fills the gap [2, 3.5] x [0, 2], a convex hexagon of the six facing points: 4 triangles, each with an
// edge of length >= 1.5 across the gap, so circumradius >= 0.75. With alpha * l_char = 0.72 the 16 square
// triangles (0.707) stay and exactly the 4 gap triangles go; the outline is two closed loops of 8 edges.
TEST(RemeshPoints, RemovesTheTrianglesBridgingAGap) {
  std::vector<Vec2> x;
  add_grid(x, Vec2(0, 0), 2, 2, 1.0);
  add_grid(x, Vec2(3.5, 0), 2, 2, 1.0);
  RemeshResult all;
  remesh_points(x, {}, RemeshSettings{10.0, 1.0, false}, {}, all);
  EXPECT_EQ(all.triangles.size(), 3u * 20u);  // the convex hull: 2 x 8 + 4
  EXPECT_NEAR(all.area, 5.5 * 2.0, 1e-12);

  RemeshResult r;
  remesh_points(x, {}, RemeshSettings{0.72, 1.0, false}, {}, r);
  EXPECT_EQ(r.rejected, 4);
  EXPECT_EQ(r.triangles.size(), 3u * 16u);
  EXPECT_EQ(r.isolated, 0);
  EXPECT_NEAR(r.area, 8.0, 1e-12);
  // No kept triangle has corners on both sides of the gap.
  for (std::size_t t = 0; t < r.triangles.size(); t += 3) {
    int left = 0;
    for (int k = 0; k < 3; ++k) left += x[std::size_t(r.triangles[t + std::size_t(k)])].x() < 2.75;
    EXPECT_TRUE(left == 0 || left == 3) << "triangle " << t / 3 << " bridges the gap";
  }
  EXPECT_EQ(r.boundary.size(), 16u);
  for (const Edge& e : r.boundary) EXPECT_NEAR((x[std::size_t(e[0])] - x[std::size_t(e[1])]).norm(), 1.0, 1e-12);
}

// A point far above a 3 x 3-node square (spacing 1) only joins the two top edges of the square, by triangles
// of circumradius ~4: both are rejected and the point is isolated (left out of the solve by the recipe).
TEST(RemeshPoints, ReportsAPointThatNoTriangleKeepsAsIsolated) {
  std::vector<Vec2> x;
  add_grid(x, Vec2(0, 0), 2, 2, 1.0);
  x.emplace_back(1.0, 10.0);
  RemeshResult r;
  remesh_points(x, {}, RemeshSettings{1.1, 1.0, false}, {}, r);
  EXPECT_EQ(r.isolated, 1);
  EXPECT_EQ(r.rejected, 2);
  EXPECT_EQ(r.triangles.size(), 3u * 8u);
  EXPECT_NEAR(r.area, 4.0, 1e-12);
}

// A thin rhombus: the Delaunay diagonal is the short one (1-3); constraining the long one (0-2) puts it in
// the mesh although it is not Delaunay (seed 000 Fig 2a: the previous boundary is kept).
TEST(RemeshPoints, KeepsAConstraintEdgeThatIsNotDelaunay) {
  const std::vector<Vec2> x = {{0.0, 0.0}, {1.0, -0.3}, {2.0, 0.0}, {1.0, 0.3}};
  const RemeshSettings keep_all{100.0, 1.0, false};
  RemeshResult free_mesh, constrained;
  remesh_points(x, {}, keep_all, {}, free_mesh);
  ASSERT_EQ(free_mesh.triangles.size(), 6u);
  EXPECT_TRUE(has_edge(free_mesh.triangles, 1, 3));
  EXPECT_FALSE(has_edge(free_mesh.triangles, 0, 2));

  remesh_points(x, {Edge{0, 2}}, keep_all, {}, constrained);
  ASSERT_EQ(constrained.triangles.size(), 6u);
  EXPECT_TRUE(has_edge(constrained.triangles, 0, 2));
  EXPECT_FALSE(has_edge(constrained.triangles, 1, 3));
  EXPECT_NEAR(constrained.area, free_mesh.area, 1e-14);
}

// The shifted pattern cuts every quadrilateral by its Delaunay diagonal, so triangulating its own points with
// its own outline as constraints gives back exactly its cells: the identity a PFEM remesh must be on an
// undeformed body (seed 000 §5.1: no spurious connectivity changes).
TEST(RemeshPoints, GivesBackADelaunayMeshFromItsOwnPointsAndBoundary) {
  RectangleSpec spec;
  spec.nx = 8, spec.ny = 4, spec.size = Vec2(2.0, 1.0);
  spec.pattern = GridPattern::shifted;
  const MeshData m = generate_rectangle(spec);
  const std::vector<Edge> outline = boundary_of(m.triangles);
  RemeshResult r;
  remesh_points(m.X, outline, RemeshSettings{1.1, 0.2, false}, {}, r);  // scenes/constrained_block_pfem.toml
  EXPECT_EQ(r.rejected, 0);
  EXPECT_EQ(r.isolated, 0);
  EXPECT_EQ(triangle_set(r.triangles), triangle_set(m.triangles));
  EXPECT_NEAR(r.area, 2.0, 1e-12);
  std::set<std::pair<Index, Index>> a, b;
  for (const Edge& e : r.boundary) a.insert({e[0], e[1]});
  for (const Edge& e : outline) b.insert({e[0], e[1]});
  EXPECT_EQ(a, b);  // same outline, same (counter-clockwise) orientation
}

// eq 17 on a unit square of two triangles {0, 1, 2}, {0, 2, 3}: node 0 and 2 see both sides and the
// diagonal, (1 + 1 + sqrt 2) / 3; nodes 1 and 3 see two sides, 1.
TEST(AverageNeighbourDistance, IsTheMeanEdgeLengthAtEachPoint) {
  const std::vector<Vec2> x = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {5, 5}};
  std::vector<double> d;
  average_neighbour_distance(x, {0, 1, 2, 0, 2, 3}, d);
  ASSERT_EQ(d.size(), 5u);
  const double diag = (2.0 + std::sqrt(2.0)) / 3.0;
  EXPECT_NEAR(d[0], diag, 1e-15);
  EXPECT_NEAR(d[2], diag, 1e-15);
  EXPECT_NEAR(d[1], 1.0, 1e-15);
  EXPECT_NEAR(d[3], 1.0, 1e-15);
  EXPECT_EQ(d[4], 0.0);  // in no triangle
}

// eqs 17-18 for clouds of two densities: a fine square [0, 2]^2 (spacing 0.5, triangles of circumradius
// 0.354) and a coarse one [5, 7] x [0, 2] (spacing 1, circumradius 0.707), 3 apart, so every triangle that
// bridges the gap has an edge >= 3 and a circumradius >= 1.5. The previous mesh is each grid's own cells,
// so d_avg is 0.5 ... 0.57 on the fine points and 1 ... 1.14 on the coarse ones.
//  - constant l_char = 0.5, alpha = 1.1 (test radius 0.55): only the fine square survives; the coarse
//    points are all isolated;
//  - local l_char, same alpha: test radii >= 0.55 on fine and >= 1.1 on coarse triangles, <= 1.26 anywhere:
//    both squares are kept whole and the gap is still removed.
TEST(RemeshPoints, LocalCharacteristicLengthFollowsThePointDensity) {
  std::vector<Vec2> x;
  add_grid(x, Vec2(0, 0), 4, 4, 0.5);  // 25 points, 32 triangles
  const Index n_fine = Index(x.size());
  add_grid(x, Vec2(5.0, 0.0), 2, 2, 1.0);  // 9 points, 8 triangles
  std::vector<Index> previous;
  auto grid_cells = [&](Index first, int n) {  // squares cut by their diagonal lower-left -> upper-right
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Index a = first + j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
        previous.insert(previous.end(), {a, b, c, a, c, d});
      }
  };
  grid_cells(0, 4);
  grid_cells(n_fine, 2);
  std::vector<double> d_avg;
  average_neighbour_distance(x, previous, d_avg);
  // Centre points: 6 neighbours, 4 along the axes and 2 along the diagonals.
  EXPECT_NEAR(d_avg[12], (4 * 0.5 + 2 * 0.5 * std::sqrt(2.0)) / 6.0, 1e-15);
  EXPECT_NEAR(d_avg[std::size_t(n_fine) + 4], (4 * 1.0 + 2 * std::sqrt(2.0)) / 6.0, 1e-15);

  RemeshResult constant;
  remesh_points(x, {}, RemeshSettings{1.1, 0.5, false}, {}, constant);
  EXPECT_EQ(constant.triangles.size(), 3u * 32u);
  EXPECT_NEAR(constant.area, 4.0, 1e-12);
  EXPECT_EQ(constant.isolated, 9);

  RemeshResult local;
  remesh_points(x, {}, RemeshSettings{1.1, 0.0, true}, d_avg, local);
  EXPECT_EQ(local.triangles.size(), 3u * 40u);
  EXPECT_EQ(local.isolated, 0);
  EXPECT_NEAR(local.area, 8.0, 1e-12);
  EXPECT_EQ(local.boundary.size(), 16u + 8u);
}

// A jittered cloud with holes opened by a small alpha: the outline remesh_points reads off CGAL's face
// neighbours is boundary_of(triangles), edge for edge and in order; eq 17's means are those of the unique
// edges summed in ascending neighbour order (the sort the counting version replaced), bit for bit.
TEST(RemeshPoints, OutlineAndMeanDistancesEqualTheirDefinitions) {
  std::vector<Vec2> x;
  add_grid(x, Vec2(0, 0), 30, 20, 0.1);
  std::uint64_t state = 7;
  auto jitter = [&] { return double((state = state * 6364136223846793005ull + 1442695040888963407ull) >> 11) / double(1ull << 53) - 0.5; };
  for (auto& p : x) p += 0.06 * Vec2(jitter(), jitter());
  RemeshResult r;
  remesh_points(x, {}, RemeshSettings{0.75, 0.1, false}, {}, r);
  ASSERT_GT(r.rejected, 20);  // holes inside: several boundary loops
  EXPECT_EQ(r.boundary, boundary_of(r.triangles));

  std::vector<double> d;
  average_neighbour_distance(x, r.triangles, d);
  std::set<std::pair<Index, Index>> edges;
  for (std::size_t t = 0; t < r.triangles.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const Index a = r.triangles[t + std::size_t(k)], b = r.triangles[t + std::size_t((k + 1) % 3)];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  std::vector<double> sum(x.size(), 0.0);
  std::vector<int> count(x.size(), 0);
  for (const auto& [a, b] : edges) {  // ascending pairs: each point sees its neighbours in ascending order
    const double l = (x[std::size_t(a)] - x[std::size_t(b)]).norm();
    sum[std::size_t(a)] += l, sum[std::size_t(b)] += l, ++count[std::size_t(a)], ++count[std::size_t(b)];
  }
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_EQ(d[i], count[i] ? sum[i] / count[i] : 0.0) << "point " << i;
}

TEST(RemeshPoints, RejectsCoincidentPoints) {
  const std::vector<Vec2> x = {{0, 0}, {1, 0}, {0, 1}, {1, 0}};
  RemeshResult r;
  EXPECT_THROW(remesh_points(x, {}, RemeshSettings{}, {}, r), RunError);
}

TEST(BoundaryOf, OrientsTheOutlineCounterClockwise) {
  // 3 --- 2
  // |   / |
  // 0 --- 1
  const auto edges = boundary_of({0, 1, 2, 0, 2, 3});
  const std::set<std::pair<Index, Index>> got = [&] {
    std::set<std::pair<Index, Index>> s;
    for (const Edge& e : edges) s.insert({e[0], e[1]});
    return s;
  }();
  EXPECT_EQ(got, (std::set<std::pair<Index, Index>>{{0, 1}, {1, 2}, {2, 3}, {3, 0}}));
}

}  // namespace
}  // namespace loom
