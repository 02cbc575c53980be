// Mesh generators (engine/mesh/generators): counts, orientation, covered area, no duplicate nodes, a
// conforming outline; Cook's membrane; interior distortion.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include "engine/mesh/boundary_edges.hpp"
#include "engine/mesh/generators.hpp"

namespace loom {
namespace {

double signed_area(const MeshData& m, Index t) {
  const Vec2& a = m.X[std::size_t(m.triangles[std::size_t(3 * t)])];
  const Vec2& b = m.X[std::size_t(m.triangles[std::size_t(3 * t + 1)])];
  const Vec2& c = m.X[std::size_t(m.triangles[std::size_t(3 * t + 2)])];
  return 0.5 * ((b - a).x() * (c - a).y() - (c - a).x() * (b - a).y());
}

double min_area(const MeshData& m) {
  double r = INFINITY;
  for (Index t = 0; t < m.n_triangles(); ++t) r = std::min(r, signed_area(m, t));
  return r;
}

double total_area(const MeshData& m) {
  double s = 0;
  for (Index t = 0; t < m.n_triangles(); ++t) s += signed_area(m, t);
  return s;
}

double outline_length(const MeshData& m) {
  double s = 0;
  for (const auto& e : boundary_edges(m.triangles, 3)) s += (m.X[std::size_t(e.b)] - m.X[std::size_t(e.a)]).norm();
  return s;
}

Index closest_pair_count(const MeshData& m, double tol) {
  Index n = 0;
  for (std::size_t i = 0; i < m.X.size(); ++i)
    for (std::size_t j = i + 1; j < m.X.size(); ++j) n += (m.X[i] - m.X[j]).norm() < tol;
  return n;
}

// Number of triangles using each node.
std::vector<int> valence(const MeshData& m) {
  std::vector<int> v(m.X.size(), 0);
  for (Index n : m.triangles) ++v[std::size_t(n)];
  return v;
}

RectangleSpec rectangle(int nx, int ny, GridPattern p) {
  RectangleSpec s;
  s.origin = Vec2(1.0, -2.0);
  s.size = Vec2(3.0, 2.0);
  s.nx = nx, s.ny = ny;
  s.pattern = p;
  return s;
}

void expect_valid_rectangle(const MeshData& m, const RectangleSpec& s) {
  EXPECT_GT(min_area(m), 0.0) << "every triangle counter-clockwise with positive area";
  EXPECT_NEAR(total_area(m), s.size.x() * s.size.y(), 1e-12);
  EXPECT_NEAR(outline_length(m), 2 * (s.size.x() + s.size.y()), 1e-12) << "no hole, no overlap";
  EXPECT_EQ(closest_pair_count(m, 1e-9), 0) << "duplicate nodes";
  for (int v : valence(m)) EXPECT_GT(v, 0) << "unused node";
  for (const Vec2& x : m.X) {
    EXPECT_GE(x.x(), s.origin.x() - 1e-12);
    EXPECT_LE(x.x(), s.origin.x() + s.size.x() + 1e-12);
    EXPECT_GE(x.y(), s.origin.y() - 1e-12);
    EXPECT_LE(x.y(), s.origin.y() + s.size.y() + 1e-12);
  }
}

}  // namespace

TEST(GenerateRectangle, RightPatternCountsAndGeometry) {
  const auto spec = rectangle(4, 3, GridPattern::right);
  const MeshData m = generate_rectangle(spec);
  EXPECT_EQ(m.n_triangles(), 2 * 4 * 3);
  EXPECT_EQ(Index(m.X.size()), 5 * 4);
  expect_valid_rectangle(m, spec);
}

TEST(GenerateRectangle, AlternatingPatternCountsAndGeometry) {
  const auto spec = rectangle(5, 4, GridPattern::alternating);
  const MeshData m = generate_rectangle(spec);
  EXPECT_EQ(m.n_triangles(), 2 * 5 * 4);
  EXPECT_EQ(Index(m.X.size()), 6 * 5);
  expect_valid_rectangle(m, spec);
}

TEST(GenerateRectangle, ShiftedPatternCountsAndGeometry) {
  // 8 x 4 divisions: node rows 0, 2, 4 hold nx + 1 = 9 nodes; the shifted rows 1, 3 hold nx midpoints plus
  // two end points, nx + 2 = 10. Each strip between two rows is zipped into one triangle per segment of
  // either row: nx + (nx + 1).
  const int nx = 8, ny = 4;
  const auto spec = rectangle(nx, ny, GridPattern::shifted);
  const MeshData m = generate_rectangle(spec);
  EXPECT_EQ(Index(m.X.size()), 3 * (nx + 1) + 2 * (nx + 2));  // 47
  EXPECT_EQ(m.n_triangles(), ny * (2 * nx + 1));               // 68
  expect_valid_rectangle(m, spec);
  // The shifted rows sit half an edge off the regular grid (besides their end points).
  const double h = spec.size.x() / nx;
  int half_offset = 0;
  for (const Vec2& x : m.X) {
    const double k = (x.x() - spec.origin.x()) / h;
    if (std::abs(k - std::round(k) - 0.5) < 1e-9 || std::abs(k - std::round(k) + 0.5) < 1e-9) ++half_offset;
  }
  EXPECT_EQ(half_offset, 2 * nx);
}

TEST(GenerateRectangle, OddRowCountWithShiftedPattern) {
  const auto spec = rectangle(3, 3, GridPattern::shifted);
  const MeshData m = generate_rectangle(spec);
  EXPECT_EQ(Index(m.X.size()), 2 * 4 + 2 * 5);
  EXPECT_EQ(m.n_triangles(), 3 * 7);
  expect_valid_rectangle(m, spec);
}

TEST(GenerateRectangle, AlternatingPatternFlipsTheDiagonals) {
  // 2 x 2 squares: with one diagonal direction the centre node is in 6 triangles; with the checkerboard
  // every diagonal meets at the centre (8 triangles) or at the corners.
  auto centre_valence = [](GridPattern p) {
    const MeshData m = generate_rectangle(rectangle(2, 2, p));
    for (std::size_t i = 0; i < m.X.size(); ++i)
      if ((m.X[i] - Vec2(2.5, -1.0)).norm() < 1e-12) return valence(m)[i];
    return -1;
  };
  EXPECT_EQ(centre_valence(GridPattern::right), 6);
  EXPECT_EQ(centre_valence(GridPattern::alternating), 8);
}

TEST(GenerateCooksMembrane, CoversTheTrapezoid) {
  const Vec2 corners[4] = {Vec2(0, 0), Vec2(48, 44), Vec2(48, 60), Vec2(0, 44)};
  double shoelace = 0, perimeter = 0;
  for (int k = 0; k < 4; ++k) {
    const Vec2 &p = corners[k], &q = corners[(k + 1) % 4];
    shoelace += 0.5 * (p.x() * q.y() - q.x() * p.y());
    perimeter += (q - p).norm();
  }
  for (GridPattern p : {GridPattern::right, GridPattern::alternating, GridPattern::shifted}) {
    const MeshData m = generate_cooks_membrane(6, 4, p);
    EXPECT_GT(min_area(m), 0.0);
    EXPECT_NEAR(total_area(m), shoelace, 1e-9);
    EXPECT_NEAR(outline_length(m), perimeter, 1e-9);
    EXPECT_EQ(closest_pair_count(m, 1e-9), 0);
  }
  // Every corner is a node.
  const MeshData m = generate_cooks_membrane(6, 4, GridPattern::right);
  for (const Vec2& c : corners) {
    bool found = false;
    for (const Vec2& x : m.X) found = found || (x - c).norm() < 1e-12;
    EXPECT_TRUE(found) << c.transpose();
  }
}

TEST(DistortInteriorNodes, MovesOnlyInteriorNodesAndKeepsCellsValid) {
  for (GridPattern p : {GridPattern::right, GridPattern::alternating, GridPattern::shifted})
    for (std::uint64_t seed = 1; seed <= 200; ++seed) {
      // 0.25 is the largest fraction the schema allows; the altitude bound proves no cell can invert.
      const auto spec = rectangle(8, 6, p);
      const MeshData before = generate_rectangle(spec);
      MeshData after = before;
      distort_interior_nodes(after, 0.25, seed);
      std::set<Index> boundary;
      for (const auto& e : boundary_edges(before.triangles, 3)) boundary.insert(e.a), boundary.insert(e.b);
      int moved = 0;
      for (std::size_t i = 0; i < before.X.size(); ++i) {
        const double d = (after.X[i] - before.X[i]).norm();
        if (boundary.count(Index(i))) EXPECT_EQ(d, 0.0) << "boundary node " << i;
        else moved += d > 0.0;
        EXPECT_LE(d, 0.25 * spec.size.x() / 8 + 1e-15);  // bounded by the fraction of an altitude <= the edge
      }
      EXPECT_EQ(moved, int(before.X.size() - boundary.size()));
      EXPECT_EQ(after.triangles, before.triangles);
      EXPECT_GT(min_area(after), 0.0);
      EXPECT_NEAR(total_area(after), spec.size.x() * spec.size.y(), 1e-12);
    }
}

TEST(DistortInteriorNodes, IsDeterministicForASeed) {
  const MeshData base = generate_rectangle(rectangle(5, 5, GridPattern::right));
  MeshData a = base, b = base, c = base;
  distort_interior_nodes(a, 0.2, 42);
  distort_interior_nodes(b, 0.2, 42);
  distort_interior_nodes(c, 0.2, 43);
  EXPECT_EQ(a.X, b.X);
  EXPECT_NE(a.X, c.X);
  MeshData zero = base;
  distort_interior_nodes(zero, 0.0, 42);
  EXPECT_EQ(zero.X, base.X);
}

TEST(ScaleMesh, ScalesEveryCoordinate) {
  MeshData m = generate_rectangle(rectangle(2, 2, GridPattern::right));
  const double area = total_area(m);
  scale_mesh(m, 3.0);
  EXPECT_NEAR(total_area(m), 9.0 * area, 1e-12);
}

}  // namespace loom
