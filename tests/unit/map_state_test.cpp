// State transfer between meshes (systems/map/map_state; seed 000 §3.2, eqs 19-21): CPM, BTM with its
// copy at coinciding points and its CPM fallback (outside the hull, radius ratio below 0.005), and the
// `copy_from` shortcut the recipe uses for cells that kept their corners.
#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "engine/core/errors.hpp"
#include "systems/map/map_state.hpp"

namespace loom {
namespace {

// Old points: an 11 x 11 grid on the unit square with its interior nodes moved at random by up to 0.25 h
// (no sliver: the tests see no fallback), so the hull is the unit square.
std::vector<Vec2> jittered_grid(std::mt19937_64& gen) {
  std::uniform_real_distribution<double> jitter(-0.025, 0.025);
  std::vector<Vec2> x;
  for (int j = 0; j <= 10; ++j)
    for (int i = 0; i <= 10; ++i) {
      Vec2 p(0.1 * i, 0.1 * j);
      if (i > 0 && i < 10 && j > 0 && j < 10) p += Vec2(jitter(gen), jitter(gen));
      x.push_back(p);
    }
  return x;
}

std::vector<Vec2> random_points(std::mt19937_64& gen, int n) {
  std::uniform_real_distribution<double> u(0.001, 0.999);
  std::vector<Vec2> x;
  for (int k = 0; k < n; ++k) x.emplace_back(u(gen), u(gen));
  return x;
}

// A field whose every component is linear in x: F(x) = A + B x + C y.
struct LinearField {
  Mat3 A, B, C;
  Mat3 operator()(const Vec2& x) const { return A + B * x.x() + C * x.y(); }
};

MapSettings btm(IsoMode iso = IsoMode::iso0) {
  MapSettings s;
  s.scheme = MapScheme::btm;
  s.iso = iso;
  return s;
}

// eqs 19-20: linear shape functions on the background triangle reproduce a linear field exactly, whatever
// the triangle (no fallback happens here: every point is inside the hull and every background triangle
// is well shaped). Tolerance 1e-13 on values of order 1: the barycentric solve's round-off.
TEST(MapState, BtmReproducesAnyLinearFieldInsideTheHull) {
  std::mt19937_64 gen(42);
  const std::vector<Vec2> old_x = jittered_grid(gen), new_x = random_points(gen, 500);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int field = 0; field < 5; ++field) {
    LinearField f;
    f.A = Mat3::NullaryExpr([&] { return u(gen); });
    f.B = Mat3::NullaryExpr([&] { return u(gen); });
    f.C = Mat3::NullaryExpr([&] { return u(gen); });
    std::vector<Mat3> old_F;
    for (const Vec2& p : old_x) old_F.push_back(f(p));
    std::vector<Mat3> new_F;
    MapStats stats;
    map_state(old_x, old_F, new_x, std::vector<Index>(new_x.size(), kNoIndex), btm(), new_F, stats);
    EXPECT_EQ(stats.interpolated, Index(new_x.size()));
    EXPECT_EQ(stats.fallback, 0);
    EXPECT_EQ(stats.copied, 0);
    double worst = 0.0;
    for (std::size_t k = 0; k < new_x.size(); ++k) worst = std::max(worst, (new_F[k] - f(new_x[k])).cwiseAbs().maxCoeff());
    EXPECT_LE(worst, 1e-13) << "field " << field;
  }
  // CPM is not exact for the same field (the fixture can tell the two apart).
  LinearField f{Mat3::Identity(), Mat3::Identity(), Mat3::Zero()};
  std::vector<Mat3> old_F, new_F;
  for (const Vec2& p : old_x) old_F.push_back(f(p));
  MapStats stats;
  map_state(old_x, old_F, new_x, std::vector<Index>(new_x.size(), kNoIndex), MapSettings{}, new_F, stats);
  double worst = 0.0;
  for (std::size_t k = 0; k < new_x.size(); ++k) worst = std::max(worst, (new_F[k] - f(new_x[k])).cwiseAbs().maxCoeff());
  EXPECT_GT(worst, 0.01);
}

// CPM copies the value of the nearest old point (checked by brute force), bit for bit.
TEST(MapState, CpmCopiesTheNearestOldPoint) {
  std::mt19937_64 gen(7);
  const std::vector<Vec2> old_x = jittered_grid(gen), new_x = random_points(gen, 300);
  std::vector<Mat3> old_F;
  for (std::size_t i = 0; i < old_x.size(); ++i) old_F.push_back(Mat3::Constant(double(i)));
  std::vector<Mat3> new_F;
  MapStats stats;
  map_state(old_x, old_F, new_x, std::vector<Index>(new_x.size(), kNoIndex), MapSettings{}, new_F, stats);
  EXPECT_EQ(stats.copied, Index(new_x.size()));
  for (std::size_t k = 0; k < new_x.size(); ++k) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < old_x.size(); ++i)
      if ((old_x[i] - new_x[k]).norm() < (old_x[best] - new_x[k]).norm()) best = i;
    EXPECT_EQ(new_F[k], old_F[best]) << "new point " << k;
  }
}

// Many queries (20000: several hundred chunks of Hilbert-sorted points, each walking from the previous one,
// run in parallel): CPM still finds the nearest old point (brute force), and CPM and BTM-ISO2 give the same
// bits on one thread and on all cores (the walk's start never depends on the thread count).
TEST(MapState, ManyQueriesAreExactAndIndependentOfTheThreadCount) {
  std::mt19937_64 gen(11);
  const std::vector<Vec2> old_x = jittered_grid(gen), new_x = random_points(gen, 20000);
  std::vector<Mat3> old_F;
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (std::size_t i = 0; i < old_x.size(); ++i) old_F.push_back(Mat3::Identity() + Mat3::NullaryExpr([&] { return u(gen); }));
  const std::vector<Index> none(new_x.size(), kNoIndex);
  for (MapSettings s : {MapSettings{}, btm(IsoMode::iso2)}) {
    std::vector<Mat3> serial, parallel;
    MapStats stats;
    {
      oneapi::tbb::global_control one(oneapi::tbb::global_control::max_allowed_parallelism, 1);
      map_state(old_x, old_F, new_x, none, s, serial, stats);
    }
    map_state(old_x, old_F, new_x, none, s, parallel, stats);
    for (std::size_t k = 0; k < new_x.size(); ++k) ASSERT_EQ(serial[k], parallel[k]) << "point " << k;
    if (s.scheme != MapScheme::cpm) continue;
    for (std::size_t k = 0; k < new_x.size(); ++k) {
      std::size_t best = 0;
      for (std::size_t i = 1; i < old_x.size(); ++i)
        if ((old_x[i] - new_x[k]).squaredNorm() < (old_x[best] - new_x[k]).squaredNorm()) best = i;
      ASSERT_EQ(serial[k], old_F[best]) << "new point " << k;
    }
  }
}

// Where a new point coincides with an old one, CPM and BTM (every ISO mode) copy its value unchanged:
// bitwise, although ISO2's log/exp round trip would otherwise change the last bits.
TEST(MapState, CpmAndBtmCopyExactlyWhereThePointsCoincide) {
  std::mt19937_64 gen(3);
  const std::vector<Vec2> old_x = jittered_grid(gen);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  std::vector<Mat3> old_F;
  for (std::size_t i = 0; i < old_x.size(); ++i) {
    Mat3 F = Mat3::Identity() + Mat3::NullaryExpr([&] { return u(gen); });
    F(0, 2) = F(1, 2) = F(2, 0) = F(2, 1) = 0.0, F(2, 2) = 1.0;  // plane strain, det > 0 for |u| <= 0.3
    old_F.push_back(F);
  }
  std::vector<Vec2> new_x;
  std::vector<std::size_t> source;
  for (std::size_t i = 0; i < old_x.size(); i += 3) new_x.push_back(old_x[i]), source.push_back(i);
  for (MapSettings s : {MapSettings{}, btm(IsoMode::iso0), btm(IsoMode::iso1), btm(IsoMode::iso2)}) {
    std::vector<Mat3> new_F;
    MapStats stats;
    map_state(old_x, old_F, new_x, std::vector<Index>(new_x.size(), kNoIndex), s, new_F, stats);
    EXPECT_EQ(stats.copied, Index(new_x.size()));
    EXPECT_EQ(stats.interpolated, 0);
    for (std::size_t k = 0; k < new_x.size(); ++k) EXPECT_EQ(new_F[k], old_F[source[k]]);
  }
  // Just off a point (1e-6 of the box, far above the coincidence tolerance 1e-12), BTM interpolates.
  std::vector<Vec2> moved = new_x;
  for (auto& p : moved) p += Vec2(1e-6, 0.5e-6);
  std::vector<Mat3> new_F;
  MapStats stats;
  map_state(old_x, old_F, moved, std::vector<Index>(moved.size(), kNoIndex), btm(IsoMode::iso2), new_F, stats);
  EXPECT_GT(stats.interpolated + stats.fallback, Index(moved.size()) / 2);
}

// copy_from >= 0 takes the given old point as it is and builds no background triangulation at all (here
// there is none to build: no old positions), which is how an unchanged cell transfers nothing.
TEST(MapState, KeepsTheValuesOfPointsListedInCopyFrom) {
  const std::vector<Mat3> old_F = {Mat3::Constant(1.0), Mat3::Constant(2.0), Mat3::Constant(3.0)};
  const std::vector<Vec2> new_x = {{5, 5}, {6, 6}, {7, 7}};
  std::vector<Mat3> new_F;
  MapStats stats;
  map_state({{0, 0}, {1, 0}, {0, 1}}, old_F, new_x, {2, 0, 1}, btm(IsoMode::iso2), new_F, stats);
  EXPECT_EQ(stats.kept, 3);
  EXPECT_EQ(stats.copied + stats.interpolated + stats.fallback, 0);
  EXPECT_EQ(new_F[0], old_F[2]);
  EXPECT_EQ(new_F[1], old_F[0]);
  EXPECT_EQ(new_F[2], old_F[1]);
}

// eq 21: a sliver background triangle (radius ratio 1.6e-5 < 0.005) is not used for interpolation, the
// nearest old point is copied instead; a well-shaped triangle is. With the threshold set to 0 the sliver
// interpolates (the fallback is what the threshold decides). A point outside the hull also falls back.
TEST(MapState, BtmFallsBackToTheNearestPointOnASliverOrOutsideTheHull) {
  const std::vector<Vec2> sliver = {{0.0, 0.0}, {1.0, 0.0}, {0.5, 0.002}};
  EXPECT_LT(radius_ratio(sliver[0], sliver[1], sliver[2]), 0.005);
  const std::vector<Mat3> F = {Mat3::Constant(1.0), Mat3::Constant(2.0), Mat3::Constant(4.0)};
  const std::vector<Vec2> inside = {{0.45, 0.0005}};  // nearest old point: (0.5, 0.002)
  std::vector<Mat3> out;
  MapStats stats;
  map_state(sliver, F, inside, {kNoIndex}, btm(), out, stats);
  EXPECT_EQ(stats.fallback, 1);
  EXPECT_EQ(out[0], F[2]);

  MapSettings no_threshold = btm();
  no_threshold.min_radius_ratio = 0.0;
  map_state(sliver, F, inside, {kNoIndex}, no_threshold, out, stats);
  EXPECT_EQ(stats.interpolated, 1);
  EXPECT_NE(out[0], F[2]);

  const std::vector<Vec2> good = {{0.0, 0.0}, {1.0, 0.0}, {0.5, 0.8}};
  map_state(good, F, {{0.45, 0.2}}, {kNoIndex}, btm(), out, stats);
  EXPECT_EQ(stats.interpolated, 1);

  map_state(good, F, {{2.0, 2.0}}, {kNoIndex}, btm(), out, stats);  // outside: nearest is (0.5, 0.8)
  EXPECT_EQ(stats.fallback, 1);
  EXPECT_EQ(out[0], F[2]);
}

TEST(RadiusRatio, IsOneHalfForAnEquilateralTriangleAndZeroForADegenerateOne) {
  EXPECT_NEAR(radius_ratio({0, 0}, {1, 0}, {0.5, std::sqrt(3.0) / 2}), 0.5, 1e-15);
  EXPECT_NEAR(radius_ratio({0, 0}, {1, 0}, {0, 1}), std::sqrt(2.0) - 1.0, 1e-15);  // right isosceles: 1/(1+sqrt 2)
  EXPECT_EQ(radius_ratio({0, 0}, {1, 0}, {2, 0}), 0.0);
}

TEST(MapState, RefusesToInterpolateFromNoPoints) {
  std::vector<Mat3> out;
  MapStats stats;
  EXPECT_THROW(map_state(std::vector<Vec2>{}, {}, {{0, 0}}, {kNoIndex}, MapSettings{}, out, stats), RunError);
}

}  // namespace
}  // namespace loom
