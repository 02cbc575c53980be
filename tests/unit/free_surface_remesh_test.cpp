// The free-surface remesh (SurfaceMode::constrained, systems/remesh/remesh.hpp): the triangles inside the
// previous boundary, plus where two surfaces meet, minus where the body opens inside; crossing boundary edges
// repaired. Point sets on unit grids whose answers are counted by hand in each test.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <set>
#include <vector>

#include "engine/mesh/generators.hpp"
#include "systems/remesh/boundary_crossings.hpp"
#include "systems/remesh/boundary_loops.hpp"
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

// A body made of the rectangles (i, j) of a grid with lines at xs and ys, those for which `keep(i, j)`, each cut
// lower-left to upper-right; only the points of kept rectangles, numbered in row order.
struct SquareBody {
  std::vector<Vec2> x;
  std::vector<Index> triangles;
};

SquareBody grid_body(const std::vector<double>& xs, const std::vector<double>& ys, const std::function<bool(int, int)>& keep,
                     SquareBody into = {}) {
  const int nx = int(xs.size()) - 1, ny = int(ys.size()) - 1;
  std::vector<Index> id(std::size_t((nx + 1) * (ny + 1)), kNoIndex);
  auto point = [&](int i, int j) {
    Index& k = id[std::size_t(j * (nx + 1) + i)];
    if (k == kNoIndex) k = Index(into.x.size()), into.x.emplace_back(xs[std::size_t(i)], ys[std::size_t(j)]);
    return k;
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (keep(i, j)) {
        const Index a = point(i, j), b = point(i + 1, j), c = point(i + 1, j + 1), d = point(i, j + 1);
        into.triangles.insert(into.triangles.end(), {a, b, c, a, c, d});
      }
  return into;
}

std::vector<double> range(double from, int n) {
  std::vector<double> v;
  for (int k = 0; k <= n; ++k) v.push_back(from + k);
  return v;
}

// Unit squares of an nx x ny grid from `origin`.
SquareBody square_body(int nx, int ny, const std::function<bool(int, int)>& keep, Vec2 origin = Vec2::Zero(), SquareBody into = {}) {
  return grid_body(range(origin.x(), nx), range(origin.y(), ny), keep, std::move(into));
}

RemeshSettings settings(SurfaceMode mode, double alpha = 1.1) { return RemeshSettings{alpha, 1.0, false, mode}; }

bool all_counter_clockwise(const std::vector<Vec2>& x, const std::vector<Index>& t) {
  for (std::size_t k = 0; k < t.size(); k += 3) {
    const Vec2 &a = x[std::size_t(t[k])], &b = x[std::size_t(t[k + 1])], &c = x[std::size_t(t[k + 2])];
    if (!((b - a).x() * (c - a).y() - (c - a).x() * (b - a).y() > 0.0)) return false;
  }
  return true;
}

// A Delaunay mesh remeshed with its own outline gives itself back in both modes (an idle remesh changes nothing).
TEST(FreeSurfaceRemesh, GivesBackADelaunayMeshFromItsOwnPointsAndBoundary) {
  RectangleSpec spec;
  spec.nx = 8, spec.ny = 4, spec.size = Vec2(2.0, 1.0);
  spec.pattern = GridPattern::shifted;
  const MeshData m = generate_rectangle(spec);
  RemeshResult r;
  remesh_points(m.X, boundary_of(m.triangles), m.triangles, RemeshSettings{1.1, 0.2, false, SurfaceMode::constrained}, {}, r);
  EXPECT_EQ(triangle_set(r.triangles), triangle_set(m.triangles));
  EXPECT_EQ(r.rejected + r.merged + r.crossings + r.isolated, 0);
  EXPECT_NEAR(r.area, 2.0, 1e-12);
}

// An L of 12 unit squares (4 x 4 without the top-right 2 x 2). Its concave corner at (2, 2) has the neighbours
// (2, 3) and (3, 2) on the surface; the triangle they make with it (circumradius 0.707) passes the alpha test:
// the alpha mode fills that ear (area 12.5), the constrained mode keeps the surface (12: two boundary edges apart
// along it is one surface).
TEST(FreeSurfaceRemesh, KeepsAConcaveSurfaceThatTheAlphaShapeFills) {
  const SquareBody body = square_body(4, 4, [](int i, int j) { return i < 2 || j < 2; });
  const std::vector<Edge> outline = boundary_of(body.triangles);
  RemeshResult alpha, constrained;
  remesh_points(body.x, outline, body.triangles, settings(SurfaceMode::alpha), {}, alpha);
  remesh_points(body.x, outline, body.triangles, settings(SurfaceMode::constrained), {}, constrained);
  EXPECT_NEAR(alpha.area, 12.5, 1e-12);
  EXPECT_NEAR(constrained.area, 12.0, 1e-12);
  EXPECT_EQ(constrained.triangles.size(), 3u * 24u);
  EXPECT_EQ(constrained.merged, 0);
  EXPECT_EQ(constrained.boundary.size(), outline.size());
  EXPECT_TRUE(all_counter_clockwise(body.x, constrained.triangles));
}

// Two 2 x 2 squares one above the other: [0, 2]^2 and [0, 2] x [2 + gap, 4 + gap]. Across a gap of 0.3 the four
// triangles that bridge it (two corners on one square, one on the other: edges 1 and sqrt(1 + 0.09) = 1.04) are
// within alpha l_char = 1.1 and join two loops: the surfaces merge into one body of area 8 + 2 * 0.3 with one
// outline. Across a gap of 0.5 (edges 1.12) or 3 they stay apart: two bodies.
TEST(FreeSurfaceRemesh, MergesTwoSurfacesThatMeet) {
  for (const double gap : {0.3, 0.5, 3.0}) {
    SquareBody body = square_body(2, 2, [](int, int) { return true; });
    body = square_body(2, 2, [](int, int) { return true; }, Vec2(0.0, 2.0 + gap), body);
    RemeshResult r;
    remesh_points(body.x, boundary_of(body.triangles), body.triangles, settings(SurfaceMode::constrained), {}, r);
    const bool merged = gap < 0.4;
    EXPECT_EQ(r.merged, merged ? 4 : 0) << "gap " << gap;
    EXPECT_NEAR(r.area, merged ? 8.0 + 2.0 * gap : 8.0, 1e-12);
    EXPECT_EQ(boundary_loops(Index(body.x.size()), r.boundary).length.size(), merged ? 1u : 2u);
    EXPECT_TRUE(all_counter_clockwise(body.x, r.triangles));
  }
}

// A block of unit squares 5 wide and 3 high with a slot in its middle column, cut from the top two squares deep:
// 3 wide, its walls are more than alpha * l_char apart and it stays open; 0.4 wide, the triangles across it join
// points three or more boundary edges apart (the two walls), pass the alpha test and close it: a fold closing.
// Only the ears at the slot's bottom (corners two edges apart: one surface) may stay open.
TEST(FreeSurfaceRemesh, ClosesANarrowSlotButNotAWideOne) {
  for (const double width : {0.4, 3.0}) {
    const std::vector<double> xs = {0.0, 1.0, 2.0, 2.0 + width, 3.0 + width, 4.0 + width};
    const SquareBody body = grid_body(xs, range(0.0, 3), [](int i, int j) { return !(i == 2 && j >= 1); });
    RemeshResult r;
    remesh_points(body.x, boundary_of(body.triangles), body.triangles, settings(SurfaceMode::constrained), {}, r);
    const double block = 3.0 * (4.0 + width), body_area = block - 2.0 * width;
    if (width < 1.0) {
      EXPECT_GT(r.merged, 0);
      EXPECT_GT(r.area, body_area + 0.5 * 2.0 * width);  // at least half of the slot closed
      EXPECT_LE(r.area, block + 1e-12);
    } else {
      EXPECT_EQ(r.merged, 0);
      EXPECT_NEAR(r.area, body_area, 1e-12);
    }
    EXPECT_EQ(r.rejected, 0);
    EXPECT_TRUE(all_counter_clockwise(body.x, r.triangles));
  }
}

// The points of a 6 x 6 unit grid but for the 3 x 3 centre's.
std::vector<Vec2> block_with_empty_centre() {
  RectangleSpec spec;
  spec.nx = 6, spec.ny = 6, spec.size = Vec2(6.0, 6.0);
  const MeshData grid = generate_rectangle(spec);
  std::vector<Vec2> x;
  for (const Vec2& p : grid.X)
    if (!(p.x() > 1.5 && p.x() < 4.5 && p.y() > 1.5 && p.y() < 4.5)) x.push_back(p);
  return x;
}

// A 6 x 6 block whose 3 x 3 centre has no points (the previous mesh spanned it with large triangles): the
// triangles in the hole fail the alpha test and have no edge on the surface, so the body opens there; the ones at
// the hole's corners (circumradius 0.707) stay. The new outline has a second loop around the hole.
TEST(FreeSurfaceRemesh, OpensWhereTheBodyTearsInside) {
  const std::vector<Vec2> x = block_with_empty_centre();
  RemeshResult delaunay;  // the previous mesh: every triangle of the hull
  remesh_points(x, {}, RemeshSettings{1e9, 1.0, false}, {}, delaunay);
  ASSERT_NEAR(delaunay.area, 36.0, 1e-12);
  RemeshResult r;
  remesh_points(x, boundary_of(delaunay.triangles), delaunay.triangles, settings(SurfaceMode::constrained), {}, r);
  EXPECT_GT(r.rejected, 0);
  EXPECT_LT(r.area, 36.0 - 4.0);
  EXPECT_GT(r.area, 36.0 - 16.0);
  EXPECT_EQ(boundary_loops(Index(x.size()), r.boundary).length.size(), 2u);
  for (std::size_t t = 0; t < r.triangles.size(); t += 3) {
    const Vec2 c = (x[std::size_t(r.triangles[t])] + x[std::size_t(r.triangles[t + 1])] + x[std::size_t(r.triangles[t + 2])]) / 3.0;
    EXPECT_FALSE(c.x() > 2.5 && c.x() < 3.5 && c.y() > 2.5 && c.y() < 3.5) << "a triangle spans the hole's centre";
  }
}

// The same block as above, stretched to three times its width in one step: with the local l_char (eqs 17-18:
// each point's mean neighbour distance in the previous mesh, which has stretched with it) nothing tears, the
// triangles of the hole's stretched-free twin stay. A body opens only where a triangle is large against the
// spacing its corners had.
TEST(FreeSurfaceRemesh, DoesNotTearAUniformlyStretchedBody) {
  SquareBody body = square_body(6, 6, [](int, int) { return true; });
  for (Vec2& p : body.x) p.x() *= 3.0;
  std::vector<double> d_avg;
  average_neighbour_distance(body.x, body.triangles, d_avg);
  RemeshResult r;
  remesh_points(body.x, boundary_of(body.triangles), body.triangles, RemeshSettings{1.1, 0.0, true, SurfaceMode::constrained}, d_avg, r);
  EXPECT_EQ(r.rejected, 0);
  EXPECT_EQ(r.merged, 0);
  EXPECT_NEAR(r.area, 108.0, 1e-10);
}

// A 2 x 2 block whose top-middle point has been pushed through the bottom surface to (1, -0.5): four boundary
// edges cross. Both modes leave them out of the constraints, count them, and return a valid mesh whose outline
// does not cross itself (before the repair this was an error that stopped the run).
TEST(FreeSurfaceRemesh, RepairsABoundaryThatCrossesItself) {
  SquareBody body = square_body(2, 2, [](int, int) { return true; });
  const std::vector<Edge> outline = boundary_of(body.triangles);
  for (Vec2& p : body.x)
    if (p == Vec2(1.0, 2.0)) p = Vec2(1.0, -0.5);
  for (const SurfaceMode mode : {SurfaceMode::alpha, SurfaceMode::constrained}) {
    RemeshResult r;
    ASSERT_NO_THROW(remesh_points(body.x, outline, body.triangles, settings(mode, 2.0), {}, r));
    EXPECT_EQ(r.crossings, 4);
    EXPECT_FALSE(r.triangles.empty());
    EXPECT_TRUE(all_counter_clockwise(body.x, r.triangles));
    const std::vector<char> c = crossing_edges(body.x, r.boundary);
    EXPECT_EQ(std::count(c.begin(), c.end(), 1), 0);
  }
}

// Graded spacing (RemeshSettings::spacing_at): two rows of points 0.25 apart on a wall (y = 0) under rows 2 apart,
// the middle point of the upper fine row sunk by 0.04. With its neighbours it makes a sliver of circumradius 0.80
// whose empty circle reaches up into the coarse cells (centre (2, 1.01)); its corners' l_char^loc is 0.49, so the
// alpha test alone cut it out (a slit, and in a run the mass of the corner left without a triangle). Against the
// spacing at its centre on a ramp from 0.25 at the wall to 2 it stays; without the field the old answer stands.
TEST(FreeSurfaceRemesh, KeepsASliverOfFineCornersBesideCoarseCells) {
  std::vector<Vec2> x;
  for (int i = 0; i <= 16; ++i) x.emplace_back(0.25 * i, 0.0);
  for (int i = 0; i <= 16; ++i) x.emplace_back(0.25 * i, i == 8 ? 0.21 : 0.25);
  for (const double y : {2.25, 4.25})
    for (int i = 0; i <= 2; ++i) x.emplace_back(2.0 * i, y);
  RemeshResult delaunay;  // the previous mesh: every triangle of the hull
  remesh_points(x, {}, RemeshSettings{1e9, 1.0, false}, {}, delaunay);
  std::vector<double> d_avg;
  average_neighbour_distance(x, delaunay.triangles, d_avg);
  RemeshSettings graded{1.3, 0.0, true, SurfaceMode::constrained};
  RemeshResult plain;
  remesh_points(x, boundary_of(delaunay.triangles), delaunay.triangles, graded, d_avg, plain);
  EXPECT_EQ(plain.rejected, 1);
  EXPECT_LT(plain.area, delaunay.area - 1e-4);
  graded.spacing_at = [](const Vec2& p) { return 0.25 + 1.75 * std::clamp(p.y() / 2.0, 0.0, 1.0); };
  RemeshResult r;
  remesh_points(x, boundary_of(delaunay.triangles), delaunay.triangles, graded, d_avg, r);
  EXPECT_EQ(r.rejected, 0);
  EXPECT_EQ(triangle_set(r.triangles), triangle_set(delaunay.triangles));
  EXPECT_NEAR(r.area, delaunay.area, 1e-12);
}

// The field does not hide a void: the 6 x 6 block with an empty 3 x 3 centre opens as before when the spacing
// everywhere is the grid's.
TEST(FreeSurfaceRemesh, StillOpensWhereTheSpacingFieldIsTheGrids) {
  const std::vector<Vec2> x = block_with_empty_centre();
  RemeshResult delaunay;
  remesh_points(x, {}, RemeshSettings{1e9, 1.0, false}, {}, delaunay);
  RemeshSettings s = settings(SurfaceMode::constrained);
  RemeshResult without, with;
  remesh_points(x, boundary_of(delaunay.triangles), delaunay.triangles, s, {}, without);
  s.spacing_at = [](const Vec2&) { return 1.0; };
  remesh_points(x, boundary_of(delaunay.triangles), delaunay.triangles, s, {}, with);
  EXPECT_GT(with.rejected, 0);
  EXPECT_EQ(triangle_set(with.triangles), triangle_set(without.triangles));
}

}  // namespace
}  // namespace loom
