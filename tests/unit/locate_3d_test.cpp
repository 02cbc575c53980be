// systems/locate in 3D (tet4 grids, engine/mesh/tet_background_grid.hpp): on a box of Kuhn cubes the
// arithmetic search and, on the same box distorted, the bucket index and the walk find for every point a cell
// that holds it, the one a brute-force search finds (or, on a shared face, another that also holds it), with
// barycentric coordinates that sum to one and reproduce the point; points on the outer faces are kept and
// points just outside are not; face neighbours are symmetric; locate_points<3> groups points by cell and
// names a point outside the grid with its three coordinates.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <string>

#include "engine/core/errors.hpp"
#include "engine/mesh/tet_background_grid.hpp"
#include "engine/mesh/tet_generators.hpp"
#include "systems/locate/locate_points.hpp"

namespace loom {
namespace {

struct Grid3 {
  Nodes<3> nodes;
  Cells cells;
  GridLayoutT<3> layout;
};

BoxSpec box_spec() {
  BoxSpec spec;
  spec.origin = Vec3(-1.3, 0.4, 2.1);
  spec.size = Vec3(2.0, 1.1, 0.7);  // unequal spacing: 0.4, 0.275, 0.2333...
  spec.nx = 5, spec.ny = 4, spec.nz = 3;
  return spec;
}

Grid3 box_grid(double distortion = 0.0) {
  const BoxSpec spec = box_spec();
  TetMeshData mesh = generate_box(spec);
  if (distortion > 0.0) {
    EXPECT_GT(distort_interior_nodes(mesh, distortion, 7), 0.1);
  }
  Grid3 g;
  build_tet_grid(mesh, distortion > 0.0 ? nullptr : &spec, Formulation::p1, g.nodes, g.cells, g.layout);
  return g;
}

// Barycentric coordinates by an independent route: the 4 x 4 system [x_a; 1] N = [x; 1].
Vec4 bary(const Grid3& g, Index c, const Vec3& x) {
  Eigen::Matrix4d A;
  for (int a = 0; a < 4; ++a) A.col(a) << g.nodes.X[g.cells.node(c, a)], 1.0;
  return A.partialPivLu().solve(Vec4(x.x(), x.y(), x.z(), 1.0));
}

// The cell where x is most inside (largest smallest coordinate), over all cells.
Index brute_force(const Grid3& g, const Vec3& x, double& inside) {
  Index best = kNoIndex;
  inside = -1e300;
  for (Index c = 0; c < g.cells.size(); ++c)
    if (const double m = bary(g, c, x).minCoeff(); m > inside) inside = m, best = c;
  return best;
}

// Uniform points in the box; every third one moved onto a face shared by two tetrahedra (two equal
// coordinates in its cube) and every fifth onto a face between cubes (a lattice plane).
std::vector<Vec3> box_points(int n, unsigned seed) {
  const BoxSpec spec = box_spec();
  const Vec3 h = spec.size.cwiseQuotient(Vec3(spec.nx, spec.ny, spec.nz));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> r;
  for (int k = 0; k < n; ++k) {
    Vec3 s(u(rng) * spec.nx, u(rng) * spec.ny, u(rng) * spec.nz);  // in cube units
    const int a = (k / 3) % 3, b = (a + 1) % 3;
    if (k % 3 == 0) s[b] = std::floor(s[b]) + (s[a] - std::floor(s[a]));
    if (k % 5 == 0) s[k % 3] = std::round(s[k % 3]);
    r.push_back(spec.origin + s.cwiseProduct(h));
  }
  return r;
}

void expect_found(const Grid3& g, const Vec3& x, Index hint) {
  Vec4 N;
  const Index c = find_cell(g.layout, g.cells, g.nodes, x, hint, N);
  ASSERT_NE(c, kNoIndex) << "x = " << x.transpose() << ", hint " << hint;
  EXPECT_GE(N.minCoeff(), -1e-12) << "cell " << c << " does not hold x = " << x.transpose();
  EXPECT_NEAR(N.sum(), 1.0, 1e-14);
  EXPECT_LE((N - bary(g, c, x)).norm(), 1e-12);
  Vec3 back = Vec3::Zero();
  for (int a = 0; a < 4; ++a) back += N[a] * g.nodes.X[g.cells.node(c, a)];
  EXPECT_LE((back - x).norm(), 1e-13 * g.layout.width());
  double inside;
  const Index expected = brute_force(g, x, inside);
  if (inside > 1e-12) {
    EXPECT_EQ(c, expected) << "x = " << x.transpose();
  }
}

TEST(Locate3d, KuhnBoxIsSearchedByArithmetic) {
  const Grid3 g = box_grid();
  ASSERT_TRUE(g.layout.structured);
  ASSERT_EQ(g.cells.size(), 6 * 5 * 4 * 3);
  for (const Vec3& x : box_points(3000, 3)) expect_found(g, x, kNoIndex);
}

TEST(Locate3d, DistortedBoxIsSearchedByBucketsAndWalks) {
  const Grid3 g = box_grid(0.3);
  ASSERT_FALSE(g.layout.structured);
  ASSERT_GT(g.layout.bx * g.layout.by * g.layout.bz, 1);
  std::mt19937 rng(9);
  std::uniform_int_distribution<Index> cell(0, g.cells.size() - 1);
  for (const Vec3& x : box_points(3000, 4)) {
    expect_found(g, x, kNoIndex);   // buckets
    expect_found(g, x, cell(rng));  // walk from a random cell
  }
  // From the far corner's cell, walks across the whole box; without buckets, so that the walk alone finds it.
  Vec4 N;
  const Index far = find_cell(g.layout, g.cells, g.nodes, g.layout.hi, kNoIndex, N);
  Grid3 walk_only = g;
  walk_only.layout.bx = walk_only.layout.by = walk_only.layout.bz = 1;
  walk_only.layout.bucket_offsets = {0, 0};
  walk_only.layout.bucket_cells.clear();
  int walked = 0;
  for (const Vec3& x : box_points(500, 5))
    if ((x - g.layout.lo).norm() < 0.3 * (g.layout.hi - g.layout.lo).norm()) expect_found(walk_only, x, far), ++walked;
  EXPECT_GT(walked, 5);
}

TEST(Locate3d, KeepsPointsOnTheOuterFacesAndRejectsPointsOutside) {
  for (const Grid3& g : {box_grid(), box_grid(0.3)}) {
    for (Index i = 0; i < g.nodes.size(); ++i) expect_found(g, g.nodes.X[i], 0);  // every node, corners included
    const Vec3 lo = g.layout.lo, hi = g.layout.hi, mid = 0.5 * (lo + hi);
    for (int a = 0; a < 3; ++a)
      for (double side : {lo[a], hi[a]}) {
        Vec3 on = mid;
        on[a] = side;
        expect_found(g, on, kNoIndex);
        Vec3 out = on;
        out[a] += side == lo[a] ? -1e-6 : 1e-6;
        Vec4 N;
        EXPECT_EQ(find_cell(g.layout, g.cells, g.nodes, out, kNoIndex, N), kNoIndex) << out.transpose();
        EXPECT_EQ(find_cell(g.layout, g.cells, g.nodes, out, 0, N), kNoIndex) << out.transpose();
      }
    Vec4 N;
    EXPECT_EQ(find_cell(g.layout, g.cells, g.nodes, Vec3(hi + Vec3::Constant(1e-6)), kNoIndex, N), kNoIndex);
    EXPECT_EQ(find_cell(g.layout, g.cells, g.nodes, Vec3(lo - Vec3::Constant(1e-6)), kNoIndex, N), kNoIndex);
  }
}

TEST(Locate3d, FaceNeighboursAreSymmetricAndTheBoxHasItsBoundaryFaces) {
  const Grid3 g = box_grid();
  const int nx = 5, ny = 4, nz = 3;
  ASSERT_EQ(g.cells.neighbour.size(), 4 * g.cells.size());
  Index boundary = 0;
  double volume = 0.0;
  for (Index c = 0; c < g.cells.size(); ++c) {
    volume += g.cells.measure[c];
    for (int a = 0; a < 4; ++a) {
      const Index n = g.cells.neighbour[4 * c + a];
      if (n == kNoIndex) {
        ++boundary;
        continue;
      }
      int back = 0;
      for (int b = 0; b < 4; ++b) back += g.cells.neighbour[4 * n + b] == c;
      EXPECT_EQ(back, 1) << "cells " << c << " and " << n;
      // The shared face is the three corners of c other than corner a, all corners of n.
      std::set<Index> of_n(g.cells.cell_nodes(n), g.cells.cell_nodes(n) + 4);
      for (int b = 0; b < 4; ++b) EXPECT_EQ(of_n.count(g.cells.node(c, b)), b == a ? 0u : 1u);
    }
  }
  EXPECT_EQ(boundary, 2 * 2 * (nx * ny + ny * nz + nz * nx));
  EXPECT_NEAR(volume, 2.0 * 1.1 * 0.7, 1e-13);
  // Colours: no two cells of one colour share a node.
  for (Index k = 0; k < g.cells.n_colours(); ++k) {
    std::set<Index> seen;
    for (Index i = g.cells.colour_offsets[std::size_t(k)]; i < g.cells.colour_offsets[std::size_t(k) + 1]; ++i)
      for (int a = 0; a < 4; ++a) EXPECT_TRUE(seen.insert(g.cells.node(g.cells.by_colour[std::size_t(i)], a)).second);
  }
}

// With one active cell, a point in any cell sharing a corner with it is carried by it (the rings reach it).
TEST(Locate3d, HostActiveCellReachesEveryCellAroundACorner) {
  const Grid3 g = box_grid();
  const Index active = 6 * ((1 * 4 + 2) * 5 + 2) + 3;  // an interior cube's tetrahedron
  GridActivity act;
  act.cell_active.assign(std::size_t(g.cells.size()), 0);
  act.cell_active[std::size_t(active)] = 1;
  const std::set<Index> corners(g.cells.cell_nodes(active), g.cells.cell_nodes(active) + 4);
  int around = 0;
  for (Index c = 0; c < g.cells.size(); ++c) {
    bool shares = false;
    for (int a = 0; a < 4; ++a) shares |= corners.count(g.cells.node(c, a)) > 0;
    if (!shares || c == active) continue;
    ++around;
    Vec3 centre = Vec3::Zero();
    for (int a = 0; a < 4; ++a) centre += 0.25 * g.nodes.X[g.cells.node(c, a)];
    Vec4 N;
    ASSERT_EQ(host_active_cell(g.cells, g.nodes, act, c, centre, N), active) << "from cell " << c;
    EXPECT_NEAR(N.sum(), 1.0, 1e-14);
    EXPECT_LE((N - bary(g, active, centre)).norm(), 1e-12);
  }
  EXPECT_GT(around, 24);
}

Points<3> make_points(const std::vector<Vec3>& X) {
  Points<3> p;
  p.X.use(), p.u.use();
  p.resize(Index(X.size()));
  for (Index i = 0; i < p.X.size(); ++i) p.X[i] = X[std::size_t(i)];
  return p;
}

TEST(Locate3d, LocatePointsGroupsByCellAndNamesAPointOutside) {
  for (const Grid3& g : {box_grid(), box_grid(0.3)}) {
    Points<3> points = make_points(box_points(2000, 8));
    PointLocations loc;
    StepContext ctx;
    locate_points(ctx, g.layout, g.cells, g.nodes, points, loc);
    ASSERT_EQ(loc.cell_offsets.size(), std::size_t(g.cells.size()) + 1);
    ASSERT_EQ(loc.cell_offsets.back(), points.X.size());
    for (Index c = 0; c < g.cells.size(); ++c)
      for (Index k = 0; k < loc.count_in(c); ++k) {
        const Index p = loc.points_in(c)[k];
        EXPECT_EQ(loc.cell[p], c);
        EXPECT_GE(loc.N[p].minCoeff(), -1e-12);
        if (k > 0) {
          EXPECT_LT(loc.points_in(c)[k - 1], p);
        }
      }
    // Moved a little: the previous cells are the walks' starts.
    for (Index p = 0; p < points.X.size(); ++p) points.u[p] = 0.01 * Vec3(std::sin(p), std::cos(p), 0.5 * std::sin(2.0 * p));
    for (Index p = 0; p < points.X.size(); ++p) points.X[p] = points.X[p].cwiseMax(g.layout.lo + Vec3::Constant(0.01)).cwiseMin(g.layout.hi - Vec3::Constant(0.01));
    locate_points(ctx, g.layout, g.cells, g.nodes, points, loc);
    for (Index p = 0; p < points.X.size(); ++p) EXPECT_GE(bary(g, loc.cell[p], points.position(p)).minCoeff(), -1e-12);

    points.X[17] = Vec3(0.25, 0.5, 1.0);
    points.u[17] = Vec3::Zero();
    ctx.step = 4;
    try {
      locate_points(ctx, g.layout, g.cells, g.nodes, points, loc);
      FAIL() << "no error";
    } catch (const RunError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("particle 17 (reference position (0.25, 0.5, 1)) is at (0.25, 0.5, 1)"), std::string::npos) << what;
      EXPECT_NE(what.find("step 4"), std::string::npos) << what;
      EXPECT_NE(what.find("[-1.3, 0.7] x [0.4, 1.5] x [2.1, 2.8]"), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace loom
