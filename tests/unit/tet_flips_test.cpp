// systems/remesh/tet_flips (spec 3d-free-surface §3 R3.4): the quality measure on known tetrahedra; a 2-3 flip,
// a 3-2 flip and a 5-ring edge removal on hand-built cavities; no change where the only improving move would cross
// the surface; on a jittered Kuhn lattice fewer slivers with the volume, the surface faces and the face adjacency
// kept; the same result twice and for the tets listed in another order or with their corners rotated.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "engine/core/types.hpp"
#include "engine/mesh/tet_adjacency.hpp"
#include "systems/remesh/delaunay_check.hpp"
#include "systems/remesh/tet_flips.hpp"

namespace loom {
namespace {

using Quad = std::array<Index, 4>;
using Tri = std::array<Index, 3>;

double volume(const std::vector<Vec3>& x, const std::vector<Index>& tets, std::size_t t) {
  const Vec3 &a = x[tets[4 * t]], &b = x[tets[4 * t + 1]], &c = x[tets[4 * t + 2]], &d = x[tets[4 * t + 3]];
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

double total_volume(const std::vector<Vec3>& x, const std::vector<Index>& tets) {
  double v = 0.0;
  for (std::size_t t = 0; t < tets.size() / 4; ++t) v += volume(x, tets, t);
  return v;
}

double min_quality(const std::vector<Vec3>& x, const std::vector<Index>& tets) {
  double q = 1.0;
  for (std::size_t t = 0; t < tets.size() / 4; ++t)
    q = std::min(q, tet_quality(x[tets[4 * t]], x[tets[4 * t + 1]], x[tets[4 * t + 2]], x[tets[4 * t + 3]]));
  return q;
}

Index count_below(const std::vector<Vec3>& x, const std::vector<Index>& tets, double q) {
  Index n = 0;
  for (std::size_t t = 0; t < tets.size() / 4; ++t)
    n += tet_quality(x[tets[4 * t]], x[tets[4 * t + 1]], x[tets[4 * t + 2]], x[tets[4 * t + 3]]) < q;
  return n;
}

// How many tets use each face (sorted corners).
std::map<Tri, int> face_use(const std::vector<Index>& tets) {
  static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  std::map<Tri, int> use;
  for (std::size_t t = 0; t < tets.size() / 4; ++t)
    for (const auto& f : kFaces) {
      Tri k{tets[4 * t + f[0]], tets[4 * t + f[1]], tets[4 * t + f[2]]};
      std::sort(k.begin(), k.end());
      ++use[k];
    }
  return use;
}

// Faces used once, outward-oriented, each rotated to start at its smallest corner (orientation kept).
std::vector<Tri> surface(const std::vector<Index>& tets) {
  static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  const std::map<Tri, int> use = face_use(tets);
  std::vector<Tri> faces;
  for (std::size_t t = 0; t < tets.size() / 4; ++t)
    for (const auto& f : kFaces) {
      Tri k{tets[4 * t + f[0]], tets[4 * t + f[1]], tets[4 * t + f[2]]};
      Tri s = k;
      std::sort(s.begin(), s.end());
      if (use.at(s) != 1) continue;
      std::rotate(k.begin(), std::min_element(k.begin(), k.end()), k.end());
      faces.push_back(k);
    }
  std::sort(faces.begin(), faces.end());
  return faces;
}

std::vector<Quad> sorted_tets(const std::vector<Index>& tets) {
  std::vector<Quad> s;
  for (std::size_t t = 0; t < tets.size() / 4; ++t) {
    Quad k{tets[4 * t], tets[4 * t + 1], tets[4 * t + 2], tets[4 * t + 3]};
    std::sort(k.begin(), k.end());
    s.push_back(k);
  }
  std::sort(s.begin(), s.end());
  return s;
}

// The invariants of every flip sequence: same volume and surface, positive tets, a conforming adjacency.
void expect_valid_and_same_boundary(const std::vector<Vec3>& x, const std::vector<Index>& before,
                                    const std::vector<Index>& after, double tol) {
  const double v0 = total_volume(x, before);
  EXPECT_NEAR(total_volume(x, after), v0, tol * std::abs(v0));
  EXPECT_EQ(surface(after), surface(before));
  for (std::size_t t = 0; t < after.size() / 4; ++t) EXPECT_GT(volume(x, after, t), 0.0) << "tet " << t;
  for (const auto& [face, n] : face_use(after)) EXPECT_LE(n, 2) << face[0] << " " << face[1] << " " << face[2];
}

// The ring of n tets around edge (a, b): a regular n-gon p_0..p_n-1 inscribed in the unit circle at z = 0 and two
// apexes a = point n near (0, 0, h) and b = point n + 1 near (0, 0, -h); each (a, b, p_i, p_i+1) positive.
void ring_of_tets(int n, double h, std::vector<Vec3>& x, std::vector<Index>& tets) {
  x.clear(), tets.clear();
  for (int i = 0; i < n; ++i) {
    const double t = -2.0 * M_PI * i / n;  // clockwise seen from a: (a, b, p_i, p_i+1) positive
    x.emplace_back(std::cos(t), std::sin(t), 0.0);
  }
  x.emplace_back(0.1, 0.05, h), x.emplace_back(-0.05, 0.02, -h);
  for (int i = 0; i < n; ++i) tets.insert(tets.end(), {Index(n), Index(n + 1), Index(i), Index((i + 1) % n)});
}

TEST(TetFlips, QualityIsOneForTheRegularTetAndZeroForAFlatOne) {
  const Vec3 a(1, 1, 1), b(1, -1, -1), c(-1, -1, 1), d(-1, 1, -1);  // regular, positively oriented
  ASSERT_GT((b - a).dot((c - a).cross(d - a)), 0.0);
  EXPECT_NEAR(tet_quality(a, b, c, d), 1.0, 1e-14);
  EXPECT_NEAR(tet_quality(a, b, d, c), -1.0, 1e-14);  // inverted: the sign of the volume
  EXPECT_EQ(tet_quality(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.3, 0.4, 0)), 0.0);
  EXPECT_EQ(tet_quality(a, a, c, d), 0.0);  // coincident corners
  // A Kuhn tet of the unit cube: S = 1 + sqrt(2), V = 1/6, R = sqrt(3)/2, so 3 r_in / R = sqrt(3) / (1 + sqrt(2)).
  const double kuhn = std::sqrt(3.0) / (1.0 + std::sqrt(2.0));
  EXPECT_NEAR(tet_quality(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(1, 1, 1)), kuhn, 1e-14);
  const Vec3 p(0.1, 0.2, 0.3), q(1.3, -0.1, 0.2), r(0.4, 1.1, -0.2), s(0.3, 0.2, 0.9);
  const double q0 = tet_quality(p, q, r, s);
  EXPECT_GT(q0, 0.1);
  EXPECT_LT(q0, 0.99);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Vec3 t(5.0, -3.0, 2.0);
  const auto m = [&](const Vec3& v) -> Vec3 { return 1e-3 * (R * v) + t; };
  EXPECT_NEAR(tet_quality(m(p), m(q), m(r), m(s)), q0, 1e-9);  // 1e-9: round-off of the translated coordinates
  EXPECT_NEAR(tet_quality(q, r, p, s), q0, 1e-14);  // an even permutation of the corners
}

TEST(TetFlips, FlipsTwoFlatTetsIntoThree) {
  std::vector<Vec3> x;
  std::vector<Index> ring;
  ring_of_tets(3, 0.17, x, ring);  // a, b close to the triangle: the 2-tet form has two flat caps
  const std::vector<Index> before{3, 0, 1, 2, 4, 0, 2, 1};  // (a, triangle), (b, triangle reversed)
  ASSERT_GT(volume(x, before, 0), 0.0);
  ASSERT_GT(volume(x, before, 1), 0.0);
  std::vector<Index> tets = before;
  const FlipStats s = improve_by_flips(x, tets, FlipSettings{});
  EXPECT_EQ(s.flips23, 1);
  EXPECT_EQ(s.flips32 + s.edge_removals, 0);
  EXPECT_EQ(tets.size(), 12u);
  EXPECT_EQ(sorted_tets(tets), sorted_tets(ring));
  EXPECT_NEAR(s.worst_after, min_quality(x, ring), 1e-14);
  EXPECT_GT(s.worst_after, s.worst_before);
  expect_valid_and_same_boundary(x, before, tets, 1e-14);
}

TEST(TetFlips, FlipsThreeNeedlesAroundALongEdgeIntoTwo) {
  std::vector<Vec3> x;
  std::vector<Index> before;
  ring_of_tets(3, 3.0, x, before);  // a long edge ab through a small triangle
  std::vector<Index> tets = before;
  const FlipStats s = improve_by_flips(x, tets, FlipSettings{});
  EXPECT_EQ(s.flips32, 1);
  EXPECT_EQ(s.flips23 + s.edge_removals, 0);
  EXPECT_EQ(sorted_tets(tets), (std::vector<Quad>{{0, 1, 2, 3}, {0, 1, 2, 4}}));
  EXPECT_GT(s.worst_after, 0.5);
  EXPECT_LT(s.worst_before, 0.2);
  expect_valid_and_same_boundary(x, before, tets, 1e-14);
}

TEST(TetFlips, RemovesAnEdgeWithARingOfFive) {
  std::vector<Vec3> x;
  std::vector<Index> before;
  ring_of_tets(5, 3.0, x, before);
  std::vector<Index> tets = before;
  const FlipStats s = improve_by_flips(x, tets, FlipSettings{});
  EXPECT_EQ(s.edge_removals, 1);
  EXPECT_EQ(tets.size(), 4u * 6u);  // 2 (n - 2) tets
  EXPECT_GT(s.worst_after, 3.0 * s.worst_before);  // 0.142 -> 0.493
  for (std::size_t t = 0; t < tets.size() / 4; ++t)  // edge (a, b) = (5, 6) is gone
    EXPECT_FALSE(std::count(tets.begin() + 4 * t, tets.begin() + 4 * t + 4, 5) &&
                 std::count(tets.begin() + 4 * t, tets.begin() + 4 * t + 4, 6));
  expect_valid_and_same_boundary(x, before, tets, 1e-14);
}

// Every triangulation of the ring polygon p_i..p_j, each triangle (i, k, j) giving tets (a, p_i, p_k, p_j) and
// (b, p_i, p_j, p_k): the largest worst quality, by exhaustive recursion (the oracle of the dynamic programme).
double best_triangulation(const std::vector<Vec3>& x, int n, int i, int j) {
  if (j - i < 2) return 2.0;
  double best = -2.0;
  for (int k = i + 1; k < j; ++k)
    best = std::max(best, std::min({best_triangulation(x, n, i, k), best_triangulation(x, n, k, j),
                                    tet_quality(x[n], x[i], x[k], x[j]), tet_quality(x[n + 1], x[i], x[j], x[k])}));
  return best;
}

TEST(TetFlips, EdgeRemovalFindsTheBestTriangulationOfTheRing) {
  for (int n = 4; n <= 7; ++n) {
    std::vector<Vec3> x;
    std::vector<Index> before;
    ring_of_tets(n, 3.0, x, before);
    x[2] += Vec3(0.1, -0.2, 0.05);  // break the symmetry: a unique optimum
    std::vector<Index> tets = before;
    const FlipStats s = improve_by_flips(x, tets, FlipSettings{});
    EXPECT_EQ(s.edge_removals, 1) << n;
    EXPECT_EQ(tets.size(), 4u * (2 * n - 4)) << n;
    // The ring starts at p_0 in both: the optimum over all triangulations does not depend on the start.
    EXPECT_NEAR(s.worst_after, best_triangulation(x, n, 0, n - 1), 1e-14) << n;
    expect_valid_and_same_boundary(x, before, tets, 1e-14);
  }
}

TEST(TetFlips, NeverFlipsAcrossTheSurface) {
  std::vector<Vec3> x;
  std::vector<Index> ring;
  ring_of_tets(3, 3.0, x, ring);
  std::vector<Index> open(ring.begin(), ring.begin() + 8);  // two of the three needles: edge ab on the surface
  std::vector<Index> tets = open;
  const FlipStats s = improve_by_flips(x, tets, FlipSettings{});
  EXPECT_EQ(s.flips23 + s.flips32 + s.edge_removals, 0);
  EXPECT_EQ(tets, open);
  EXPECT_EQ(s.below_before, 2);  // both needles were visited
  EXPECT_EQ(s.below_after, 2);
}

// A jittered n^3 lattice (spacing 1, each point moved by up to `jitter` per coordinate; std::mt19937's raw output
// is fixed by the standard, its distributions are not) cut into Kuhn tets, 6 per cube along the 000-111 diagonal.
void jittered_kuhn(int n, double jitter, std::vector<Vec3>& x, std::vector<Index>& tets) {
  std::mt19937 rng(2024);
  const auto uniform = [&] { return 2.0 * (double(rng()) / 4294967296.0) - 1.0; };
  x.clear(), tets.clear();
  const auto id = [n](int i, int j, int k) { return Index(i + (n + 1) * (j + (n + 1) * k)); };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        x.emplace_back(i, j, k);
        for (int c = 0; c < 3; ++c) x.back()[c] += jitter * uniform();
      }
  static constexpr int kPaths[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& path : kPaths) {
          std::array<int, 3> c{i, j, k};
          Quad t{id(i, j, k), 0, 0, 0};
          for (int s = 0; s < 3; ++s) ++c[path[s]], t[s + 1] = id(c[0], c[1], c[2]);
          const int inversions = (path[0] > path[1]) + (path[0] > path[2]) + (path[1] > path[2]);
          if (inversions % 2) std::swap(t[2], t[3]);  // an odd path is negatively oriented as listed
          tets.insert(tets.end(), t.begin(), t.end());
        }
}

TEST(TetFlips, JitteredKuhnLatticeLosesSlivers) {
  std::vector<Vec3> x;
  std::vector<Index> before;
  jittered_kuhn(8, 0.3, x, before);  // at 0.2 no tet falls below q = 0.25; at 0.35 some invert
  for (std::size_t t = 0; t < before.size() / 4; ++t) ASSERT_GT(volume(x, before, t), 0.0);
  std::vector<Index> tets = before;
  const FlipStats s = improve_by_flips(x, tets, FlipSettings{});
  EXPECT_EQ(s.below_before, count_below(x, before, 0.2));
  EXPECT_EQ(s.below_after, count_below(x, tets, 0.2));
  EXPECT_NEAR(s.worst_before, min_quality(x, before), 1e-14);
  EXPECT_NEAR(s.worst_after, min_quality(x, tets), 1e-14);
  // Measured (3072 tets): q < 0.1: 28 -> 0; q < 0.2: 83 -> 12; worst 0.0005 -> 0.1085 (2 flips 3-2, 53 edge
  // removals, no 2-3).
  EXPECT_GE(count_below(x, before, 0.1), 20);
  EXPECT_EQ(count_below(x, tets, 0.1), 0);
  EXPECT_LE(4 * s.below_after, s.below_before);
  EXPECT_GT(s.worst_after, 0.1);
  EXPECT_GT(s.flips32 + s.edge_removals, 0);
  expect_valid_and_same_boundary(x, before, tets, 1e-13);
}

TEST(TetFlips, ResultDependsOnTheTetsNotOnTheirOrder) {
  std::vector<Vec3> x;
  std::vector<Index> before;
  jittered_kuhn(8, 0.3, x, before);
  const FlipSettings settings{0.3, 3};  // many flips, some of them competing for the same tets
  std::vector<Index> first = before, second = before;
  improve_by_flips(x, first, settings);
  improve_by_flips(x, second, settings);
  EXPECT_EQ(first, second);
  ASSERT_NE(sorted_tets(first), sorted_tets(before));  // something flipped
  // The tets listed backwards, each with its corners rotated by an even permutation (0 1 2 3) -> (1 2 0 3).
  std::vector<Index> shuffled;
  for (std::size_t t = before.size() / 4; t-- > 0;)
    shuffled.insert(shuffled.end(), {before[4 * t + 1], before[4 * t + 2], before[4 * t], before[4 * t + 3]});
  improve_by_flips(x, shuffled, settings);
  EXPECT_EQ(sorted_tets(shuffled), sorted_tets(first));
}

// The Delaunay repair (R3.8): Lawson's flips with the sliver bar.

// Interior faces that fail the remesh's in-sphere test (either way, with its margin).
Index non_delaunay_faces(const std::vector<Vec3>& x, const std::vector<Index>& tets) {
  static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  const auto nbr = tet_face_neighbours(tets);
  Index n = 0;
  for (std::size_t t = 0; t < nbr.size(); ++t)
    for (int f = 0; f < 4; ++f) {
      const Index o = nbr[t][std::size_t(f)];
      if (o < 0 || std::size_t(o) < t) continue;
      const Index* T = &tets[4 * t];
      const Index* O = &tets[4 * std::size_t(o)];
      Index apex_o = O[0];
      for (int m = 0; m < 4; ++m)
        if (O[m] != T[kFaces[f][0]] && O[m] != T[kFaces[f][1]] && O[m] != T[kFaces[f][2]]) apex_o = O[m];
      n += strictly_inside_sphere(x[T[0]], x[T[1]], x[T[2]], x[T[3]], x[apex_o]) ||
           strictly_inside_sphere(x[O[0]], x[O[1]], x[O[2]], x[O[3]], x[T[f]]);
    }
  return n;
}
TEST(TetFlipsRepair, FlipsANonDelaunayFaceTwoToThree) {
  std::vector<Vec3> x;
  std::vector<Index> ring;
  ring_of_tets(3, 0.17, x, ring);  // a and b near the triangle: each lies inside the other tet's circumsphere
  const std::vector<Index> before{3, 0, 1, 2, 4, 0, 2, 1};
  std::vector<Index> tets = before;
  const DelaunayRepairStats s = repair_delaunay(x, tets, FlipSettings{0.0, 3});
  EXPECT_EQ(s.flips, 1);
  EXPECT_EQ(s.failing_after, 0);
  EXPECT_EQ(sorted_tets(tets), sorted_tets(ring));
  expect_valid_and_same_boundary(x, before, tets, 1e-14);
}

TEST(TetFlipsRepair, FlipsThreeTetsAroundAnEdgeIntoTwo) {
  std::vector<Vec3> x;
  std::vector<Index> before;
  ring_of_tets(3, 3.0, x, before);  // a and b far from the triangle: the two tets on it are the Delaunay ones
  std::vector<Index> tets = before;
  const DelaunayRepairStats s = repair_delaunay(x, tets, FlipSettings{0.0, 3});
  EXPECT_EQ(s.flips, 1);
  EXPECT_EQ(s.failing_after, 0);
  EXPECT_EQ(sorted_tets(tets), (std::vector<Quad>{{0, 1, 2, 3}, {0, 1, 2, 4}}));
  expect_valid_and_same_boundary(x, before, tets, 1e-14);
}

// A delaunay mesh is left alone.
TEST(TetFlipsRepair, LeavesADelaunayMeshAsItIs) {
  std::vector<Vec3> x;
  std::vector<Index> before;
  ring_of_tets(3, 3.0, x, before);
  std::vector<Index> tets = before;
  repair_delaunay(x, tets, FlipSettings{0.0, 3});
  const std::vector<Index> delaunay = tets;
  const DelaunayRepairStats s = repair_delaunay(x, tets, FlipSettings{0.0, 3});
  EXPECT_EQ(s.flips, 0);
  EXPECT_EQ(s.passes, 0);
  EXPECT_EQ(tets, delaunay);
}

// A jittered Kuhn lattice (far from Delaunay): with no bar the repair mends most non-Delaunay faces (Lawson's flips
// can stop short of the Delaunay mesh in 3D: the faces left have no flip to locally Delaunay positive tets); with the
// sliver bar it makes no tet worse than both the bar and the worst it started with. Volume and surface kept exactly
// either way, and the result is the same for the tets listed in another order.
TEST(TetFlipsRepair, JitteredKuhnLatticeLosesMostNonDelaunayFacesAndMakesNoSliver) {
  std::vector<Vec3> x;
  std::vector<Index> before;
  jittered_kuhn(6, 0.2, x, before);
  std::vector<Index> free = before;
  const DelaunayRepairStats a = repair_delaunay(x, free, FlipSettings{0.0, 3});
  const Index failing_before = non_delaunay_faces(x, before);
  std::printf("[repair] jittered Kuhn 6^3 (%ld non-Delaunay faces), no bar: %ld flips in %d passes, %ld faces left failing\n",
              long(failing_before), long(a.flips), a.passes, long(a.failing_after));
  EXPECT_EQ(a.failing_after, non_delaunay_faces(x, free));
  EXPECT_LE(5 * a.failing_after, failing_before);
  EXPECT_EQ(a.stuck, 0);  // no bar: a face left is never "beside a sliver" below a floor of 0
  expect_valid_and_same_boundary(x, before, free, 1e-13);
  std::vector<Index> barred = before;
  const FlipSettings bar{0.2, 3};
  const DelaunayRepairStats b = repair_delaunay(x, barred, bar);
  std::printf("[repair] with the bar 0.2: %ld flips, %ld failing left (%ld stuck beside a sliver); worst q %.4f -> %.4f\n", long(b.flips),
              long(b.failing_after), long(b.stuck), min_quality(x, before), min_quality(x, barred));
  EXPECT_GT(b.flips, 0);
  EXPECT_GE(min_quality(x, barred), std::min(bar.threshold, min_quality(x, before)) - 1e-12);
  EXPECT_LE(count_below(x, barred, 0.1), count_below(x, before, 0.1));
  expect_valid_and_same_boundary(x, before, barred, 1e-13);
  std::vector<Index> shuffled;
  for (std::size_t t = before.size() / 4; t-- > 0;)
    shuffled.insert(shuffled.end(), {before[4 * t + 1], before[4 * t + 2], before[4 * t], before[4 * t + 3]});
  repair_delaunay(x, shuffled, bar);
  EXPECT_EQ(sorted_tets(shuffled), sorted_tets(barred));
}

}  // namespace
}  // namespace loom
