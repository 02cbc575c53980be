// The 3D remesh (systems/remesh/remesh_3d.hpp; spec 3d-free-surface §3 and stage 1 of §9) on body-centred cubic
// lattices (engine/mesh/tet_generators.hpp: generate_bcc_box):
//  - a resting box keeps its mesh as it is (R3.7) and a full remesh of it gives the same interior cells and volume;
//    a resting cylinder and frustum (trimmed lattices) are remeshed into the mesh they have;
//  - an L-shaped block keeps its notch (the Delaunay cells that fill it lie outside the previous mesh);
//  - two blocks 0.3 h apart merge across the gap, 3 h apart they do not;
//  - a block stretched to twice its length with the local l_char does not tear; pulled apart by 8 h, half a spacing per remesh, it opens;
//  - a rigid rotation by 90 degrees in 10 steps changes nothing;
//  - the result does not depend on the order of the points.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>

#include <oneapi/tbb/global_control.h>

#include "engine/mesh/tet_adjacency.hpp"
#include "engine/mesh/tet_generators.hpp"
#include "systems/remesh/remesh_3d.hpp"

namespace loom {
namespace {

double volume_of(const std::vector<Vec3>& x, const std::vector<Index>& tets) {
  double v = 0.0;
  for (std::size_t t = 0; t + 3 < tets.size(); t += 4)
    v += tet_volume(x[std::size_t(tets[t])], x[std::size_t(tets[t + 1])], x[std::size_t(tets[t + 2])], x[std::size_t(tets[t + 3])]);
  return v;
}

std::vector<std::array<Index, 4>> sorted_cells(const std::vector<Index>& tets) {
  std::vector<std::array<Index, 4>> cells;
  for (std::size_t t = 0; t + 3 < tets.size(); t += 4) {
    std::array<Index, 4> q{tets[t], tets[t + 1], tets[t + 2], tets[t + 3]};
    std::sort(q.begin(), q.end());
    cells.push_back(q);
  }
  std::sort(cells.begin(), cells.end());
  return cells;
}

Remesh3dSettings local_alpha(double alpha = 1.3) {
  Remesh3dSettings s;
  s.alpha = alpha;
  s.local = true;
  return s;
}

Remesh3dResult remesh(const std::vector<Vec3>& x, const std::vector<Index>& previous, Remesh3dSettings s) {
  std::vector<double> h;
  average_neighbour_distance_3d(x, previous, h);
  Remesh3dResult r;
  remesh_points_3d(x, previous, s, h, r);
  // The neighbours and the surface it reads from the triangulation and the flips are those of its cells.
  EXPECT_EQ(r.neighbours, tet_face_neighbours(r.tets));
  EXPECT_EQ(r.surface, surface_of(r.tets));
  // Given the previous mesh's neighbours, it gives the same mesh.
  Remesh3dResult given;
  const std::vector<std::array<Index, 4>> previous_neighbours = tet_face_neighbours(previous);
  remesh_points_3d(x, previous, s, h, given, &previous_neighbours);
  EXPECT_EQ(given.tets, r.tets);
  EXPECT_EQ(given.merged_cell, r.merged_cell);
  return r;
}

TEST(Remesh3d, ABcc3dBoxAtRestKeepsItsMesh) {
  const TetMeshData box = generate_bcc_box({Vec3::Zero(), Vec3(1.0, 0.6, 0.8), 5, 3, 4});
  const Remesh3dResult kept = remesh(box.X, box.tets, local_alpha());
  EXPECT_TRUE(kept.kept_previous);
  EXPECT_EQ(kept.tets, box.tets);
  EXPECT_NEAR(kept.volume, 0.48, 1e-14 * 0.48);
  EXPECT_EQ(kept.isolated, 0);
  // A full remesh (R3.7 off): the Delaunay cells. Those of the interior are the lattice's; only the cospherical
  // surface pyramids may be cut the other way. The volume is the box's.
  Remesh3dSettings full = local_alpha();
  full.keep_delaunay = false;
  full.flip_quality = 0.0;
  const Remesh3dResult r = remesh(box.X, box.tets, full);
  EXPECT_FALSE(r.kept_previous);
  EXPECT_NEAR(r.volume, 0.48, 1e-14 * 0.48);
  EXPECT_EQ(r.rejected, 0);
  EXPECT_EQ(r.merged, 0);
  EXPECT_EQ(r.tets.size(), box.tets.size());
  const auto before = sorted_cells(box.tets), after = sorted_cells(r.tets);
  std::vector<std::array<Index, 4>> common;
  std::set_intersection(before.begin(), before.end(), after.begin(), after.end(), std::back_inserter(common));
  const Index surface_pyramid_cells = 2 * 2 * (5 * 3 + 3 * 4 + 5 * 4);  // two per box face square
  EXPECT_GE(Index(common.size()), Index(before.size()) - surface_pyramid_cells);
  std::printf("[remesh 3d] BCC box: %zu cells, %zu kept by a full remesh (the rest surface pyramids cut the other way)\n", before.size(),
              common.size());
}

TEST(Remesh3d, AnLShapedBlockKeepsItsNotch) {
  const TetMeshData box = generate_bcc_box({Vec3::Zero(), Vec3(1.0, 1.0, 0.5), 8, 8, 4});
  std::vector<Index> l_shape;
  for (std::size_t t = 0; t + 3 < box.tets.size(); t += 4) {
    Vec3 c = Vec3::Zero();
    for (std::size_t k = 0; k < 4; ++k) c += box.X[std::size_t(box.tets[t + k])] / 4.0;
    if (!(c.x() > 0.5 && c.y() > 0.5)) l_shape.insert(l_shape.end(), box.tets.begin() + long(t), box.tets.begin() + long(t) + 4);
  }
  // The points of the notch's interior are not part of the L: keep only those of its cells (renumbered).
  std::vector<Index> index(box.X.size(), kNoIndex);
  std::vector<Vec3> x;
  for (Index& v : l_shape) {
    if (index[std::size_t(v)] == kNoIndex) index[std::size_t(v)] = Index(x.size()), x.push_back(box.X[std::size_t(v)]);
    v = index[std::size_t(v)];
  }
  // The L's own volume: the box's 0.5 less the notch's quarter, give or take the octahedra across the notch's
  // faces (BCC cells are shared by two cubes).
  const double v0 = volume_of(x, l_shape);
  ASSERT_LT(v0, 0.8 * 0.5);
  Remesh3dSettings full = local_alpha();
  full.keep_delaunay = false;
  const Remesh3dResult r = remesh(x, l_shape, full);
  EXPECT_NEAR(r.volume, v0, 1e-13);  // nothing of the notch filled
  EXPECT_EQ(r.merged, 0);
  std::printf("[remesh 3d] L-shaped block: volume %.15g against its own %.15g (the box: 0.5), %d cells dropped as caps\n", r.volume, v0,
              int(r.capped));
}

// The points of a BCC lattice of spacing 0.1 inside a frustum of axis z (radius r0 at z = 0, r1 at z = height;
// a cylinder when r0 = r1), meshed afresh (no previous mesh: the alpha test with l_char = the spacing).
std::pair<std::vector<Vec3>, std::vector<Index>> bcc_frustum(double r0, double r1, double height) {
  const double r = std::max(r0, r1), h = 0.1;
  const int n = int(std::lround(2 * r / h)), nz = int(std::lround(height / h));
  const TetMeshData box = generate_bcc_box({Vec3(-r, -r, 0.0), Vec3(2 * r, 2 * r, height), n, n, nz});
  std::vector<Vec3> x;
  for (const Vec3& p : box.X) {
    const double radius = r0 + (r1 - r0) * p.z() / height;
    if (p.head<2>().norm() <= radius + 1e-12) x.push_back(p);
  }
  Remesh3dSettings first;
  first.alpha = 1.3;
  first.l_char = h;
  Remesh3dResult r_first;
  remesh_points_3d(x, {}, first, {}, r_first);
  return {x, r_first.tets};
}

// Stage 1's identity: a resting cylinder and a resting frustum (trimmed lattices, their surfaces jagged) are
// remeshed into the mesh they have, 10 times over.
TEST(Remesh3d, ARestingCylinderAndFrustumKeepTheirMeshes) {
  for (const double r1 : {0.3, 0.15}) {
    SCOPED_TRACE(r1 == 0.3 ? "cylinder" : "frustum");
    const auto [x, first] = bcc_frustum(0.3, r1, 0.4);
    ASSERT_FALSE(first.empty());
    const double v0 = volume_of(x, first);
    std::vector<Index> tets = first;
    int changes = 0, kept = 0;
    for (int step = 0; step < 10; ++step) {
      const Remesh3dResult r = remesh(x, tets, local_alpha());
      changes += sorted_cells(r.tets) != sorted_cells(tets);
      kept += r.kept_previous;
      EXPECT_NEAR(r.volume, v0, 1e-14 * v0);
      EXPECT_EQ(r.rejected, 0);
      EXPECT_EQ(r.merged, 0);
      tets = r.tets;
    }
    EXPECT_EQ(changes, 0);
    std::printf("[remesh 3d] resting %s: %zu points, %zu cells, volume %.6g, 10 remeshes: %d changes, %d kept by R3.7\n",
                r1 == 0.3 ? "cylinder" : "frustum", x.size(), first.size() / 4, v0, changes, kept);
  }
}

// Two blocks side by side along x, `gap` apart (in units of the lattice spacing h).
std::pair<std::vector<Vec3>, std::vector<Index>> two_blocks(double gap) {
  const double h = 0.1;
  TetMeshData a = generate_bcc_box({Vec3::Zero(), Vec3(0.4, 0.4, 0.4), 4, 4, 4});
  const TetMeshData b = generate_bcc_box({Vec3(0.4 + gap * h, 0.0, 0.0), Vec3(0.4, 0.4, 0.4), 4, 4, 4});
  const Index offset = Index(a.X.size());
  a.X.insert(a.X.end(), b.X.begin(), b.X.end());
  for (Index v : b.tets) a.tets.push_back(v + offset);
  return {a.X, a.tets};
}

TEST(Remesh3d, TwoBlocksMergeAcrossANarrowGapOnly) {
  for (const double gap : {0.3, 3.0}) {
    SCOPED_TRACE(gap);
    const auto [x, tets] = two_blocks(gap);
    const Remesh3dResult r = remesh(x, tets, local_alpha());
    if (gap < 1.0) {
      EXPECT_FALSE(r.kept_previous);
      EXPECT_GT(r.merged, 0);
      EXPECT_GT(r.volume, 2 * 0.064);
    } else {
      EXPECT_EQ(r.merged, 0);
      EXPECT_NEAR(r.volume, 2 * 0.064, 1e-14);
    }
    std::printf("[remesh 3d] two blocks %.1f h apart: %d cells merged, volume %.6g\n", gap, int(r.merged), r.volume);
  }
}

TEST(Remesh3d, AStretchedBlockDoesNotTearAPulledApartOneOpens) {
  const TetMeshData box = generate_bcc_box({Vec3::Zero(), Vec3(0.5, 0.3, 0.3), 5, 3, 3});
  // Stretched to twice its length, step by step: the local l_char grows with the cells.
  std::vector<Vec3> x = box.X;
  std::vector<Index> tets = box.tets;
  for (int step = 1; step <= 10; ++step) {
    for (std::size_t i = 0; i < x.size(); ++i) x[i].x() = box.X[i].x() * (1.0 + 0.1 * step);
    Remesh3dSettings s = local_alpha();
    const Remesh3dResult r = remesh(x, tets, s);
    ASSERT_EQ(r.rejected, 0) << "step " << step;
    ASSERT_NEAR(r.volume, 0.045 * (1.0 + 0.1 * step), 1e-12) << "step " << step;
    tets = r.tets;
  }
  // Pulled apart at its middle, half a spacing per remesh up to 8 h: the cells across the opening stretch, fail the
  // alpha test and go, the last at 6.5 h (observed). At once by 3 h it does not open: the local l_char is measured on
  // the previous mesh at the new positions, whose edges across the opening are that long too (eq 17, as in 2D).
  std::vector<Index> pulled = box.tets;
  Index torn = 0;
  Remesh3dResult r;
  for (int step = 1; step <= 16; ++step) {
    std::vector<Vec3> y = box.X;
    for (Vec3& p : y)
      if (p.x() > 0.26) p.x() += 0.05 * step;
    r = remesh(y, pulled, local_alpha());
    torn += r.rejected;
    pulled = r.tets;
  }
  EXPECT_GT(torn, 0);
  EXPECT_LT(r.volume, 0.045 + 1e-12);
  for (std::size_t t = 0; t + 3 < r.tets.size(); t += 4) {  // no cell joins the halves
    int left = 0;
    for (std::size_t k = 0; k < 4; ++k) left += box.X[std::size_t(r.tets[t + k])].x() < 0.26;
    EXPECT_TRUE(left == 0 || left == 4) << "cell " << t / 4;
  }
  std::printf("[remesh 3d] pulled apart by 8 h in 16 remeshes: %d cells torn out, volume %.6g (0.045 before)\n", int(torn), r.volume);
}

TEST(Remesh3d, ARigidRotationChangesNothing) {
  const TetMeshData box = generate_bcc_box({Vec3(-0.2, -0.1, -0.15), Vec3(0.4, 0.2, 0.3), 4, 2, 3});
  std::vector<Index> tets = box.tets;
  int changes = 0;
  for (int step = 1; step <= 10; ++step) {
    const double angle = 0.5 * M_PI * step / 10.0;
    const Mat3 R = Eigen::AngleAxisd(angle, Vec3(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
    std::vector<Vec3> x;
    for (const Vec3& p : box.X) x.push_back(R * p);
    const Remesh3dResult r = remesh(x, tets, local_alpha());
    changes += sorted_cells(r.tets) != sorted_cells(tets);
    EXPECT_NEAR(r.volume, 0.4 * 0.2 * 0.3, 1e-14);
    tets = r.tets;
  }
  EXPECT_EQ(changes, 0);
}

TEST(Remesh3d, TheResultDoesNotDependOnThePointOrder) {
  const auto [x, tets] = two_blocks(0.3);
  Remesh3dSettings s = local_alpha();
  s.keep_delaunay = false;
  const Remesh3dResult a = remesh(x, tets, s);
  // The same points in reverse order.
  const Index n = Index(x.size());
  std::vector<Vec3> y(x.rbegin(), x.rend());
  std::vector<Index> reversed;
  for (Index v : tets) reversed.push_back(n - 1 - v);
  const Remesh3dResult b = remesh(y, reversed, s);
  std::vector<Index> back;
  for (Index v : b.tets) back.push_back(n - 1 - v);
  EXPECT_EQ(sorted_cells(back), sorted_cells(a.tets));
  EXPECT_EQ(a.merged, b.merged);
}

// The cells are classified in parallel and the flips' quality pass runs in parallel: a first mesh of a jittered
// block of 2.6e4 points, then a step of it, are byte-identical on one and on two threads.
TEST(Remesh3d, OneAndTwoThreadsGiveTheSameMesh) {
  TetMeshData box = generate_bcc_box({Vec3::Zero(), Vec3::Ones(), 23, 23, 23});
  ASSERT_GT(box.X.size(), std::size_t(20000));
  std::mt19937_64 gen(11);
  const double h = 1.0 / 23;
  std::uniform_real_distribution<double> jitter(-0.15 * h, 0.15 * h), step(-0.03 * h, 0.03 * h);
  for (Vec3& p : box.X) p += Vec3(jitter(gen), jitter(gen), jitter(gen));
  std::vector<Vec3> moved = box.X;
  for (Vec3& p : moved) p += Vec3(step(gen), step(gen), step(gen));
  auto run = [&](int threads, Remesh3dResult& first, Remesh3dResult& next) {
    oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    Remesh3dSettings s = local_alpha();
    std::vector<double> h_first, h_next;
    average_neighbour_distance_3d(box.X, box.tets, h_first);
    remesh_points_3d(box.X, {}, s, h_first, first);
    average_neighbour_distance_3d(moved, first.tets, h_next);
    remesh_points_3d(moved, first.tets, s, h_next, next, &first.neighbours);
  };
  Remesh3dResult one_first, one_next, two_first, two_next;
  run(1, one_first, one_next);
  run(2, two_first, two_next);
  for (const auto& [a, b] : {std::pair{&one_first, &two_first}, std::pair{&one_next, &two_next}}) {
    EXPECT_EQ(a->tets, b->tets);
    EXPECT_EQ(a->surface, b->surface);
    EXPECT_EQ(a->neighbours, b->neighbours);
    EXPECT_EQ(a->merged_cell, b->merged_cell);
    EXPECT_EQ(a->flipped, b->flipped);
    EXPECT_EQ(a->rejected, b->rejected);
    EXPECT_EQ(a->merged, b->merged);
    EXPECT_EQ(a->capped, b->capped);
    EXPECT_EQ(a->volume, b->volume);
  }
  EXPECT_FALSE(one_next.kept_previous);  // a full remesh, with the previous mesh's classification
  EXPECT_GT(one_first.flipped, 0);
  EXPECT_EQ(one_next.neighbours, tet_face_neighbours(one_next.tets));
}

TEST(Remesh3d, CanonicalCornersKeepTheOrientation) {
  const std::vector<Vec3> x = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 1)};
  const std::array<Index, 4> t{3, 1, 2, 0};  // a permutation of a positive cell
  std::array<Index, 4> positive = t;
  if (tet_volume(x[3], x[1], x[2], x[0]) < 0) std::swap(positive[2], positive[3]);
  const auto c = canonical_tet(positive);
  EXPECT_EQ(c[0], 0);
  EXPECT_GT(tet_volume(x[std::size_t(c[0])], x[std::size_t(c[1])], x[std::size_t(c[2])], x[std::size_t(c[3])]), 0.0);
  EXPECT_EQ(canonical_tet(c), c);
}

// R3.8: a BCC block whose points have moved a little (a random 10 % of the spacing) is no longer Delaunay at a few
// faces; the repair flips them instead of triangulating it again: most cells keep their corners, the volume is the
// previous mesh's at the new positions exactly (flips keep it), and the repaired mesh is kept as it is by the next
// remesh at the same positions (no churn). Without the repair the body is triangulated again.
TEST(Remesh3d, AMeshThatIsNearlyDelaunayIsRepairedByFlips) {
  const TetMeshData box = generate_bcc_box({Vec3::Zero(), Vec3(1.0, 0.6, 0.8), 10, 6, 8});
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.1 * 0.1, 0.1 * 0.1);
  std::vector<Vec3> x = box.X;
  for (Vec3& p : x)
    for (int c = 0; c < 3; ++c) p[c] += jitter(rng);
  Remesh3dSettings repair = local_alpha();
  repair.repair = true;
  const Remesh3dResult r = remesh(x, box.tets, repair);
  EXPECT_FALSE(r.kept_previous);
  EXPECT_GT(r.repaired, 0);
  EXPECT_EQ(r.merged, 0);
  EXPECT_EQ(r.rejected, 0);
  EXPECT_NEAR(r.volume, volume_of(x, box.tets), 1e-14);
  const auto before = sorted_cells(box.tets), after = sorted_cells(r.tets);
  std::vector<std::array<Index, 4>> common;
  std::set_intersection(before.begin(), before.end(), after.begin(), after.end(), std::back_inserter(common));
  std::printf("[remesh 3d] BCC block moved by 10 %% of h: %ld repair flips, %ld sliver flips, %zu of %zu cells kept\n", long(r.repaired),
              long(r.flipped), common.size(), before.size());
  EXPECT_GT(10 * common.size(), 9 * before.size());
  const Remesh3dResult again = remesh(x, r.tets, repair);
  EXPECT_TRUE(again.kept_previous);
  EXPECT_EQ(again.tets, r.tets);
  const Remesh3dResult full = remesh(x, box.tets, local_alpha());  // the default: no repair
  EXPECT_EQ(full.repaired, 0);
  EXPECT_FALSE(full.kept_previous);
  std::printf("[remesh 3d] the same without the repair: volume %.6f against the previous mesh's %.6f (surface cells recut)\n", full.volume,
              r.volume);
}

}  // namespace
}  // namespace loom
