// Adjacency of tetrahedral meshes found by bucketing on the smallest corner (engine/mesh/tet_adjacency.hpp) against
// the global sorts it replaces, on a lattice whose cells are shuffled and whose corners are permuted; the walk of
// PointInTets::contains_near against its buckets on a non-convex (L-shaped) mesh; the neighbours improve_by_flips
// gives back against those of its output.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <numeric>
#include <random>
#include <stdexcept>

#include "engine/mesh/tet_adjacency.hpp"
#include "engine/mesh/tet_generators.hpp"
#include "systems/remesh/point_in_tets.hpp"
#include "systems/remesh/tet_flips.hpp"

namespace loom {
namespace {

// A BCC box with its cells in random order and each cell's corners evenly permuted (the orientation kept).
std::vector<Index> shuffled_cells(const std::vector<Index>& tets, unsigned seed) {
  std::mt19937 gen(seed);
  std::vector<std::size_t> order(tets.size() / 4);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), gen);
  static constexpr int kEven[4][4] = {{0, 1, 2, 3}, {1, 0, 3, 2}, {2, 3, 0, 1}, {3, 2, 1, 0}};
  std::vector<Index> out;
  for (std::size_t t : order) {
    const int* p = kEven[gen() % 4];
    for (int k = 0; k < 4; ++k) out.push_back(tets[4 * t + std::size_t(p[k])]);
  }
  return out;
}

// The neighbours by a global sort of (sorted face, tet, local face).
std::vector<std::array<Index, 4>> neighbours_by_sorting(const std::vector<Index>& tets) {
  std::vector<std::pair<std::array<Index, 3>, Index>> faces;
  for (std::size_t t = 0; t < tets.size() / 4; ++t)
    for (int f = 0; f < 4; ++f) {
      std::array<Index, 3> s{tets[4 * t + std::size_t(kTetFaces[f][0])], tets[4 * t + std::size_t(kTetFaces[f][1])],
                             tets[4 * t + std::size_t(kTetFaces[f][2])]};
      std::sort(s.begin(), s.end());
      faces.emplace_back(s, Index(4 * t + std::size_t(f)));
    }
  std::sort(faces.begin(), faces.end());
  std::vector<std::array<Index, 4>> nbr(tets.size() / 4, {kNoIndex, kNoIndex, kNoIndex, kNoIndex});
  for (std::size_t i = 0; i + 1 < faces.size(); ++i)
    if (faces[i].first == faces[i + 1].first) {
      const Index p = faces[i].second, q = faces[i + 1].second;
      nbr[std::size_t(p / 4)][std::size_t(p % 4)] = q / 4, nbr[std::size_t(q / 4)][std::size_t(q % 4)] = p / 4;
    }
  return nbr;
}

TEST(TetAdjacency, FaceNeighboursAndSurfaceEqualAGlobalSort) {
  const TetMeshData box = generate_bcc_box({Vec3::Zero(), Vec3(2.0, 1.0, 1.0), 6, 3, 4});
  const std::vector<Index> tets = shuffled_cells(box.tets, 7);
  const auto nbr = tet_face_neighbours(tets);
  EXPECT_EQ(nbr, neighbours_by_sorting(tets));
  std::size_t surface = 0;
  for (const auto& n : nbr) surface += std::size_t(std::count(n.begin(), n.end(), kNoIndex));
  EXPECT_EQ(boundary_faces(tets).size(), surface);
  // Two faces per square of the box's surface: 2 (6 x 3 + 6 x 4 + 3 x 4) squares.
  EXPECT_EQ(surface, std::size_t(2 * 2 * (6 * 3 + 6 * 4 + 3 * 4)));
}

TEST(TetAdjacency, AFaceInThreeTetsIsMarkedAndRefusedAsASurface) {
  // Three apexes over the triangle (0, 1, 2).
  const std::vector<Index> tets = {0, 1, 2, 3, 0, 2, 1, 4, 0, 1, 2, 5};
  const auto nbr = tet_face_neighbours(tets);
  for (std::size_t t = 0; t < 3; ++t) EXPECT_EQ(nbr[t][3], kNonManifold) << t;  // the face opposite corner 3
  EXPECT_THROW(boundary_faces(tets), std::runtime_error);
}

TEST(TetAdjacency, EdgesEqualASortedUniqueList) {
  const TetMeshData box = generate_bcc_box({Vec3::Zero(), Vec3::Ones(), 4, 3, 5});
  const std::vector<Index> tets = shuffled_cells(box.tets, 11);
  std::vector<std::pair<Index, Index>> expected;
  for (std::size_t t = 0; t + 3 < tets.size(); t += 4)
    for (std::size_t i = 0; i < 4; ++i)
      for (std::size_t j = i + 1; j < 4; ++j) expected.emplace_back(std::min(tets[t + i], tets[t + j]), std::max(tets[t + i], tets[t + j]));
  std::sort(expected.begin(), expected.end());
  expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
  EXPECT_EQ(tet_edges(tets), expected);
}

TEST(TetAdjacency, CellSetFindsACellByItsCornersInAnyOrderAndSortsThem) {
  const TetMeshData box = generate_bcc_box({Vec3::Zero(), Vec3::Ones(), 3, 3, 3});
  const std::vector<Index> tets = shuffled_cells(box.tets, 3);
  const TetCellSet cells(tets);
  for (std::size_t t = 0; t < tets.size() / 4; ++t) {
    const Index odd[4] = {tets[4 * t + 3], tets[4 * t + 1], tets[4 * t], tets[4 * t + 2]};
    EXPECT_EQ(cells.find(odd), Index(t));
  }
  // Quadruples that are no cell: a cell with one corner replaced by a point of the cell after it.
  int absent = 0;
  for (std::size_t t = 0; t + 1 < tets.size() / 4; ++t) {
    Index v[4] = {tets[4 * t], tets[4 * t + 1], tets[4 * t + 2], tets[4 * t + 3]};
    std::array<Index, 4> s{v[0], v[1], v[2], tets[4 * t + 4]};
    if (std::count(v, v + 3, s[3]) > 0) continue;
    std::sort(s.begin(), s.end());
    bool is_cell = false;
    for (std::size_t o = 0; o < tets.size() / 4; ++o) {
      std::array<Index, 4> c{tets[4 * o], tets[4 * o + 1], tets[4 * o + 2], tets[4 * o + 3]};
      std::sort(c.begin(), c.end());
      is_cell = is_cell || c == s;
    }
    v[3] = tets[4 * t + 4];
    EXPECT_EQ(cells.contains(v), is_cell);
    absent += !is_cell;
  }
  EXPECT_GT(absent, 10);
  const Index beyond[4] = {0, 1, 2, Index(box.X.size()) + 5};
  EXPECT_FALSE(cells.contains(beyond));
  // The order of the sorted corners.
  std::vector<std::array<Index, 4>> sorted(tets.size() / 4);
  for (std::size_t t = 0; t < sorted.size(); ++t) {
    sorted[t] = {tets[4 * t], tets[4 * t + 1], tets[4 * t + 2], tets[4 * t + 3]};
    std::sort(sorted[t].begin(), sorted[t].end());
  }
  const std::vector<Index> order = tet_sorted_order(tets);
  ASSERT_EQ(order.size(), sorted.size());
  for (std::size_t i = 1; i < order.size(); ++i) EXPECT_LT(sorted[std::size_t(order[i - 1])], sorted[std::size_t(order[i])]);
}

TEST(PointInTets, TheWalkAnswersAsTheBucketsOnANonConvexMesh) {
  // An L-shaped block: the BCC box without the cells whose centroid lies in x > 0.5, y > 0.5.
  const TetMeshData box = generate_bcc_box({Vec3::Zero(), Vec3::Ones(), 6, 6, 3});
  std::vector<Index> tets;
  for (std::size_t t = 0; t + 3 < box.tets.size(); t += 4) {
    Vec3 c = Vec3::Zero();
    for (std::size_t k = 0; k < 4; ++k) c += box.X[std::size_t(box.tets[t + k])] / 4.0;
    if (!(c.x() > 0.5 && c.y() > 0.5)) tets.insert(tets.end(), box.tets.begin() + long(t), box.tets.begin() + long(t + 4));
  }
  const auto nbr = tet_face_neighbours(tets);
  const PointInTets walk(box.X, tets, &nbr), buckets(box.X, tets);
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  std::uniform_int_distribution<Index> start(0, Index(box.X.size()) - 1);
  int inside = 0, outside = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 p(u(gen), u(gen), u(gen));
    const bool expected = buckets.contains(p);
    EXPECT_EQ(walk.contains_near(p, start(gen)), expected) << p.transpose();
    (expected ? inside : outside) += 1;
  }
  // Points on faces, edges and corners count as in, from any start.
  for (Index v = 0; v < Index(box.X.size()); v += 7) {
    const Vec3 mid = 0.5 * (box.X[std::size_t(v)] + box.X[std::size_t((v * 13) % Index(box.X.size()))]);
    EXPECT_EQ(walk.contains_near(mid, start(gen)), buckets.contains(mid));
    EXPECT_EQ(walk.contains_near(box.X[std::size_t(v)], v), buckets.contains(box.X[std::size_t(v)]));
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 1000);
}

TEST(TetFlips, TheNeighboursGivenBackAreThoseOfTheOutput) {
  // A jittered BCC lattice has slivers for the flips to remove.
  TetMeshData box = generate_bcc_box({Vec3::Zero(), Vec3::Ones(), 5, 5, 5});
  std::mt19937 gen(9);
  std::uniform_real_distribution<double> u(-0.04, 0.04);
  for (Vec3& p : box.X) p += Vec3(u(gen), u(gen), u(gen));
  std::vector<Index> tets;
  for (std::size_t t = 0; t + 3 < box.tets.size(); t += 4) {
    Index v[4] = {box.tets[t], box.tets[t + 1], box.tets[t + 2], box.tets[t + 3]};
    if (tet_volume(box.X[std::size_t(v[0])], box.X[std::size_t(v[1])], box.X[std::size_t(v[2])], box.X[std::size_t(v[3])]) < 0) std::swap(v[2], v[3]);
    tets.insert(tets.end(), v, v + 4);
  }
  std::vector<Index> plain = tets, given = tets, origin;
  std::vector<std::array<Index, 4>> nbr = tet_face_neighbours(tets);
  const FlipSettings settings{0.5, 3};
  const FlipStats a = improve_by_flips(box.X, plain, settings);
  const FlipStats b = improve_by_flips(box.X, given, settings, &origin, &nbr);
  ASSERT_GT(a.flips23 + a.flips32 + a.edge_removals, 0);
  EXPECT_EQ(b.flips23 + b.flips32 + b.edge_removals, a.flips23 + a.flips32 + a.edge_removals);
  EXPECT_EQ(given, plain);
  EXPECT_EQ(nbr, tet_face_neighbours(given));
  ASSERT_EQ(origin.size(), given.size() / 4);
  for (std::size_t t = 0; t < origin.size(); ++t) {
    if (origin[t] == kNoIndex) continue;
    for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(given[4 * t + k], tets[4 * std::size_t(origin[t]) + k]);
  }
}

}  // namespace
}  // namespace loom
