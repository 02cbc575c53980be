// Boundary edges (engine/mesh/boundary_edges): edges used by one cell, oriented as in that cell.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <utility>

#include "engine/mesh/boundary_edges.hpp"
#include "engine/mesh/generators.hpp"

namespace loom {

TEST(BoundaryEdges, UnitSquareOfTwoTrianglesHasFourCounterClockwiseEdges) {
  // 3 --- 2
  // |   / |    cells {0, 1, 2} and {0, 2, 3}; the diagonal 0-2 is interior.
  // | /   |
  // 0 --- 1
  const std::vector<Index> tris = {0, 1, 2, 0, 2, 3};
  const auto edges = boundary_edges(tris, 3);
  ASSERT_EQ(edges.size(), 4u);
  // Ordered by cell, then side; each edge keeps its cell's orientation.
  const Index expected[4][4] = {{0, 1, 0, 0}, {1, 2, 0, 1}, {2, 3, 1, 1}, {3, 0, 1, 2}};  // a, b, cell, side
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(edges[k].a, expected[k][0]);
    EXPECT_EQ(edges[k].b, expected[k][1]);
    EXPECT_EQ(edges[k].cell, expected[k][2]);
    EXPECT_EQ(edges[k].side, expected[k][3]);
  }
}

TEST(BoundaryEdges, OutlineOfAGridIsAClosedCounterClockwiseLoop) {
  RectangleSpec spec;
  spec.nx = 4, spec.ny = 3;
  spec.pattern = GridPattern::shifted;
  const MeshData m = generate_rectangle(spec);
  const auto edges = boundary_edges(m.triangles, 3);
  // Each outline node starts one edge and ends one edge.
  std::map<Index, int> starts, ends;
  double signed_area = 0;  // shoelace over the outline: positive when counter-clockwise
  for (const auto& e : edges) {
    ++starts[e.a], ++ends[e.b];
    const Vec2 &p = m.X[std::size_t(e.a)], &q = m.X[std::size_t(e.b)];
    signed_area += 0.5 * (p.x() * q.y() - q.x() * p.y());
    // the edge is the cell's side `side`
    EXPECT_EQ(m.triangles[std::size_t(3 * e.cell + e.side)], e.a);
    EXPECT_EQ(m.triangles[std::size_t(3 * e.cell + (e.side + 1) % 3)], e.b);
  }
  EXPECT_EQ(starts.size(), edges.size());
  EXPECT_EQ(ends.size(), edges.size());
  for (const auto& [node, n] : starts) EXPECT_EQ(n, 1) << node;
  EXPECT_NEAR(signed_area, 1.0, 1e-12);
  // bottom row: nx = 4 segments; top row (r = 3, shifted): nx + 1 = 5; left and right: one per strip, ny = 3.
  EXPECT_EQ(edges.size(), std::size_t(4 + 5 + 3 + 3));
}

TEST(BoundaryEdges, ReadsCornersOfWiderCells) {
  // The same two triangles with three extra (mid-side) nodes per cell: only the corners count.
  const std::vector<Index> tri6 = {0, 1, 2, 10, 11, 12, 0, 2, 3, 12, 13, 14};
  const auto edges = boundary_edges(tri6, 6);
  ASSERT_EQ(edges.size(), 4u);
  std::set<std::pair<Index, Index>> found;
  for (const auto& e : edges) found.insert({e.a, e.b});
  EXPECT_EQ(found, (std::set<std::pair<Index, Index>>{{0, 1}, {1, 2}, {2, 3}, {3, 0}}));
}

}  // namespace loom
