// The pieces of the free-surface remesh that look at the boundary polygon alone (systems/remesh): which of its
// edges cross, its loops and distances along them, and point location in a set of triangles. Hand-drawn fixtures.
#include <gtest/gtest.h>

#include <vector>

#include "systems/remesh/boundary_crossings.hpp"
#include "systems/remesh/boundary_loops.hpp"
#include "systems/remesh/point_in_mesh.hpp"

namespace loom {
namespace {

// A bowtie 0 -> 1 -> 2 -> 3 -> 0 on the corners (0,0), (2,2), (2,0), (0,2): its two diagonals cross at (1,1),
// its two vertical sides do not.
TEST(CrossingEdges, FlagsBothEdgesOfACrossing) {
  const std::vector<Vec2> x = {{0, 0}, {2, 2}, {2, 0}, {0, 2}};
  const std::vector<Edge> edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  EXPECT_EQ(crossing_edges(x, edges), (std::vector<char>{1, 0, 1, 0}));
}

// Touching is not crossing: a shared end point, an end point on the other edge (a T), collinear overlap. A
// triangulation splits a constraint at a point that lies on it without creating a point.
TEST(CrossingEdges, IgnoresEdgesThatOnlyTouch) {
  const std::vector<Vec2> x = {{0, 0}, {2, 0}, {1, 0}, {1, 1}, {3, 0}, {0, 1}};
  EXPECT_EQ(crossing_edges(x, {{0, 1}, {1, 3}}), (std::vector<char>{0, 0}));  // shared end
  EXPECT_EQ(crossing_edges(x, {{0, 1}, {2, 3}}), (std::vector<char>{0, 0}));  // T: (1, 0) on 0-1
  EXPECT_EQ(crossing_edges(x, {{0, 1}, {2, 4}}), (std::vector<char>{0, 0}));  // collinear overlap
  EXPECT_EQ(crossing_edges(x, {{0, 3}, {5, 1}}), (std::vector<char>{1, 1}));  // (0,0)-(1,1) and (0,1)-(2,0)
}

// A long chain of short edges folded back over itself once: only the two edges that cross are flagged, whatever
// the bucket grid does with a polygon much longer than wide.
TEST(CrossingEdges, FindsOneCrossingInALongPolygon) {
  std::vector<Vec2> x;
  for (int i = 0; i <= 200; ++i) x.emplace_back(0.01 * i, 0.0);
  for (int i = 200; i >= 0; --i) x.emplace_back(0.01 * i + 0.005, 0.003);
  x.back() = Vec2(0.5, -0.003);  // the last point dips under the first stretch
  std::vector<Edge> edges;
  for (Index i = 0; i + 1 < Index(x.size()); ++i) edges.push_back({i, i + 1});
  const std::vector<char> c = crossing_edges(x, edges);
  std::vector<Index> flagged;
  for (std::size_t k = 0; k < c.size(); ++k)
    if (c[k]) flagged.push_back(Index(k));
  // The last edge, from (0.015, 0.003) down to (0.5, -0.003), crosses y = 0 at x = 0.2575: edge 25 of the first
  // stretch, [0.25, 0.26].
  EXPECT_EQ(flagged, (std::vector<Index>{25, Index(edges.size()) - 1}));
}

// A square (0..3 counter-clockwise) with a square hole (4..7 clockwise): two loops of four edges.
TEST(BoundaryLoops, WalksEachLoopAndMeasuresAlongIt) {
  const std::vector<Edge> b = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 7}, {7, 6}, {6, 5}, {5, 4}};
  const BoundaryLoops loops = boundary_loops(9, b);
  ASSERT_EQ(loops.length.size(), 2u);
  EXPECT_EQ(loops.length[0], 4);
  EXPECT_EQ(loops.length[1], 4);
  EXPECT_EQ(steps_along(loops, 0, 1), 1);
  EXPECT_EQ(steps_along(loops, 0, 2), 2);
  EXPECT_EQ(steps_along(loops, 0, 3), 1);  // the shorter way round
  EXPECT_EQ(steps_along(loops, 4, 6), 2);
  EXPECT_EQ(steps_along(loops, 0, 4), kNoIndex);  // different loops
  EXPECT_EQ(steps_along(loops, 0, 8), kNoIndex);  // 8 is on no loop
  EXPECT_EQ(loops.loop[8], kNoIndex);
}

// Two loops that touch at point 0 (a pinch, a figure of eight) are walked as one through it: every edge once,
// and points on either side of the pinch are few steps apart (they are close to each other).
TEST(BoundaryLoops, WalksLoopsThatShareAPointAsOne) {
  const std::vector<Edge> b = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {3, 4}, {4, 0}};
  const BoundaryLoops loops = boundary_loops(5, b);
  ASSERT_EQ(loops.length.size(), 1u);
  EXPECT_EQ(loops.length[0], 6);
  EXPECT_EQ(steps_along(loops, 1, 4), 2);  // 1 -> 0 -> 4 (back through the pinch)
  EXPECT_EQ(steps_along(loops, 2, 3), 2);
}

// Two triangles overlapping (one clockwise): the union.
TEST(PointInMesh, LocatesInTheUnionOfTriangles) {
  const std::vector<Vec2> x = {{0, 0}, {2, 0}, {0, 2}, {1, 1}, {3, 1}, {1, 3}};
  const std::vector<Index> t = {0, 1, 2, 3, 5, 4};  // the second one clockwise
  const PointInMesh mesh(x, t);
  EXPECT_TRUE(mesh.contains(Vec2(0.5, 0.5)));
  EXPECT_TRUE(mesh.contains(Vec2(1.2, 1.2)));   // in both
  EXPECT_TRUE(mesh.contains(Vec2(2.0, 1.5)));   // the second only
  EXPECT_TRUE(mesh.contains(Vec2(1.0, 0.0)));   // on an edge
  EXPECT_FALSE(mesh.contains(Vec2(2.0, 0.5)));  // between them
  EXPECT_FALSE(mesh.contains(Vec2(-0.1, 0.5)));
  EXPECT_FALSE(mesh.contains(Vec2(5.0, 5.0)));  // outside the buckets
}

}  // namespace
}  // namespace loom
