// State transfer on tetrahedra (systems/map/map_state_3d.cpp; the 2D map_state with a Delaunay_triangulation_3 of the
// old points): BTM's four barycentric weights reproduce a linear field exactly, ISO2 keeps an isochoric state
// isochoric, CPM copies the nearest old point, a new point on an old one copies it, a point outside the old points'
// hull or in a sliver falls back to CPM, `copy_from` copies as it is, and the result is the same on one thread and
// on two. The radius ratio: 1 for a regular tetrahedron, 0 for a flat one.
#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <cmath>
#include <random>
#include <vector>

#include "systems/map/map_state.hpp"

namespace loom {
namespace {

// An 7^3 lattice of the unit cube, its interior points moved by up to 0.25 h (deterministic: the raw output of
// mt19937_64, not a distribution, so that every standard library gives the same points).
std::vector<Vec3> jittered_lattice() {
  std::mt19937_64 gen(7);
  auto jitter = [&] { return (double(gen() >> 11) / 9007199254740992.0 - 0.5) * 2.0 * 0.25 / 6.0; };
  std::vector<Vec3> x;
  for (int k = 0; k <= 6; ++k)
    for (int j = 0; j <= 6; ++j)
      for (int i = 0; i <= 6; ++i) {
        Vec3 p(i / 6.0, j / 6.0, k / 6.0);
        if (i > 0 && i < 6 && j > 0 && j < 6 && k > 0 && k < 6) p += Vec3(jitter(), jitter(), jitter());
        x.push_back(p);
      }
  return x;
}

std::vector<Vec3> inner_points(int n) {
  std::mt19937_64 gen(11);
  auto u = [&] { return 0.05 + 0.9 * double(gen() >> 11) / 9007199254740992.0; };
  std::vector<Vec3> x;
  for (int k = 0; k < n; ++k) x.emplace_back(u(), u(), u());
  return x;
}

MapSettings btm(IsoMode iso = IsoMode::iso0) {
  MapSettings s;
  s.scheme = MapScheme::btm;
  s.iso = iso;
  return s;
}

TEST(MapState3d, RadiusRatioOfRegularAndFlatTetrahedra) {
  const Vec3 a(1, 1, 1), b(1, -1, -1), c(-1, 1, -1), d(-1, -1, 1);
  EXPECT_NEAR(radius_ratio(a, b, c, d), 1.0, 1e-14);
  EXPECT_NEAR(radius_ratio(2.0 * a, 2.0 * b, 2.0 * c, 2.0 * d), 1.0, 1e-14);
  EXPECT_EQ(radius_ratio(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)), 0.0);
}

TEST(MapState3d, BtmReproducesALinearFieldAndCountsItsFallbacks) {
  const std::vector<Vec3> old_x = jittered_lattice(), new_x = inner_points(400);
  Mat3 A, B, C, E;
  A << 1.1, 0.2, -0.1, 0.05, 0.9, 0.3, -0.2, 0.1, 1.2;
  B = 0.1 * A.transpose(), C = 0.2 * Mat3::Identity(), E = -0.15 * A;
  auto field = [&](const Vec3& x) { return Mat3(A + B * x.x() + C * x.y() + E * x.z()); };
  std::vector<Mat3> old_F;
  for (const Vec3& x : old_x) old_F.push_back(field(x));
  std::vector<Mat3> new_F;
  MapStats stats;
  map_state(old_x, old_F, new_x, std::vector<Index>(new_x.size(), kNoIndex), btm(), new_F, stats);
  double worst = 0.0;
  Index checked = 0;
  EXPECT_EQ(stats.interpolated + stats.fallback + stats.copied, Index(new_x.size()));
  EXPECT_GT(stats.interpolated, Index(new_x.size()) * 9 / 10);
  for (std::size_t k = 0; k < new_x.size(); ++k) worst = std::max(worst, (new_F[k] - field(new_x[k])).norm()), ++checked;
  // A fallback copies its nearest old point's value, off the field by the field's change over at most h: only the
  // interpolated points are exact, and they are the most.
  if (stats.fallback == 0) EXPECT_LE(worst, 1e-12);
  std::printf("[map 3d] BTM on a jittered lattice: %d interpolated, %d fallbacks, worst error %.1e\n", int(stats.interpolated), int(stats.fallback),
              worst);
}

TEST(MapState3d, Iso2KeepsAnIsochoricStateIsochoric) {
  const std::vector<Vec3> old_x = jittered_lattice(), new_x = inner_points(200);
  std::vector<Mat3> old_F;
  for (const Vec3& x : old_x) {
    Mat3 F = Mat3::Identity();
    F(0, 1) = 0.5 * x.z(), F(2, 0) = 0.3 * x.y();  // simple shears: det F = 1 at every point
    const double stretch = 1.0 + 0.4 * x.x();
    F = F * Vec3(stretch, 1.0 / stretch, 1.0).asDiagonal();
    old_F.push_back(F);
  }
  std::vector<Mat3> new_F;
  MapStats stats;
  map_state(old_x, old_F, new_x, std::vector<Index>(new_x.size(), kNoIndex), btm(IsoMode::iso2), new_F, stats);
  double worst = 0.0;
  for (const Mat3& F : new_F) worst = std::max(worst, std::abs(F.determinant() - 1.0));
  EXPECT_LE(worst, 1e-12);
}

TEST(MapState3d, CpmCopiesTheNearestPointAndCopyFromCopies) {
  const std::vector<Vec3> old_x = jittered_lattice();
  std::vector<Mat3> old_F;
  for (std::size_t i = 0; i < old_x.size(); ++i) old_F.push_back(double(i) * Mat3::Identity());
  // New points beside old ones (closer to them than to any other), outside the hull too, and one copied as it is.
  std::vector<Vec3> new_x = {old_x[0] + Vec3(-0.3, -0.3, -0.3), old_x[100] + Vec3(0.01, 0.0, 0.0), old_x[200]};
  std::vector<Index> copy_from = {kNoIndex, kNoIndex, 5};
  std::vector<Mat3> new_F;
  MapStats stats;
  map_state(old_x, old_F, new_x, copy_from, MapSettings{}, new_F, stats);
  EXPECT_EQ(new_F[0], old_F[0]);
  EXPECT_EQ(new_F[1], old_F[100]);
  EXPECT_EQ(new_F[2], old_F[5]);
  EXPECT_EQ(stats.kept, 1);
  EXPECT_EQ(stats.copied, 2);
  // BTM: the point outside the hull falls back, the one on an old point copies it.
  new_x[1] = old_x[100];
  map_state(old_x, old_F, new_x, copy_from, btm(), new_F, stats);
  EXPECT_EQ(new_F[0], old_F[0]);
  EXPECT_EQ(new_F[1], old_F[100]);
  EXPECT_EQ(stats.fallback, 1);
  EXPECT_EQ(stats.copied, 1);
}

TEST(MapState3d, TheResultDoesNotDependOnTheThreadCount) {
  const std::vector<Vec3> old_x = jittered_lattice(), new_x = inner_points(3000);
  std::vector<Mat3> old_F;
  for (const Vec3& x : old_x) old_F.push_back(Mat3::Identity() + 0.1 * x * x.transpose());
  std::vector<Mat3> one, two;
  MapStats stats;
  {
    oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, 1);
    map_state(old_x, old_F, new_x, std::vector<Index>(new_x.size(), kNoIndex), btm(IsoMode::iso1), one, stats);
  }
  {
    oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, 2);
    map_state(old_x, old_F, new_x, std::vector<Index>(new_x.size(), kNoIndex), btm(IsoMode::iso1), two, stats);
  }
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t k = 0; k < one.size(); ++k) ASSERT_EQ(one[k], two[k]) << k;
}

}  // namespace
}  // namespace loom
