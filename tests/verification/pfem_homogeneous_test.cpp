// A homogeneous finite deformation through 50 PFEM remeshes (method pfem on
// scenes/homogeneous_compression.toml): every element (p1, tri6, p1p1_uphi) with every transfer (CPM,
// BTM-ISO0, BTM-ISO1, BTM-ISO2) must stay on the closed-form state at every step, although the
// connectivity changes at most steps.
//
// Set-up: the scene's Neo-Hooke block between rollers (see homogeneous_compression_test.cpp for the
// closed form), refined to 16 x 8 squares with alternating diagonals and the scene's random node
// distortion (0.25, seed 7), and compressed to 50 % of its height in 50 steps. An affine map does not keep a
// Delaunay triangulation Delaunay: as the block flattens, edges flip (33 of the 50 steps change the
// connectivity, the `remesh` probe says; the first remesh also changes the generated mesh, which is not
// Delaunay). alpha = 100 keeps every triangle (the alpha test is not under test here).
//
// Why it must be exact: F_n is the same at every quadrature point, so CPM copies it, BTM's weights sum to
// one (ISO0 and ISO1 give F to round-off) and ISO2's log/exp round trip is exact to round-off; TRI6
// mid-nodes re-created at straight midpoints carry the affine displacement exactly; the nodal dilatation
// of p1p1_uphi is the constant J. Tolerances as in homogeneous_compression_test.cpp: 1e-8 relative on the
// probes (Newton to |r| <= 1e-12 |r_0|; probes with 15 digits), 1e-10 on fields of order 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "tests/support/test_support.hpp"
#include "tests/verification/homogeneous_compression_exact.hpp"
#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

constexpr double kE = 10.0, kNu = 0.3, kW = 2.0, kH = 1.0, kDepth = 0.5;
constexpr int kSteps = 50;

// Plane-strain Neo-Hooke with a free right edge (homogeneous_compression_test.cpp has the derivation).
verification::HomogeneousCompression exact_state(double d) { return verification::homogeneous_compression_exact(kE, kNu, kW, kH, d); }

std::string pfem_scene_text() {
  std::string text = testing::read_text(verification::scene_path("homogeneous_compression.toml"));
  text +=
      "\n[remesh]\nalpha = 100.0\nlchar = 1.0\n"
      "\n[map]\nscheme = \"cpm\"\n"
      "\n[[probe]]\nname = \"changed\"\nkind = \"remesh\"\nquantity = \"changed\"\n"
      "\n[[probe]]\nname = \"area_change\"\nkind = \"remesh\"\nquantity = \"area_change\"\n"
      "\n[[probe]]\nname = \"volume\"\nkind = \"volume\"\n";
  return text;
}

void check(const std::string& element, const std::string& scheme, int iso) {
  const std::string name = element + " " + scheme + (scheme == "btm" ? "-iso" + std::to_string(iso) : "");
  SCOPED_TRACE(name);
  const SceneSpec scene = testing::scene_from_text(
      pfem_scene_text(), {"scene.method=pfem", "output.every=0", "body[0].element=" + element, "body[0].mesh.divisions=[16,8]",
                          "time.steps=" + std::to_string(kSteps), "time.dt=" + std::to_string(1.0 / kSteps),
                          "boundary[top].displacement.y=\"-0.5 * t\"", "map.scheme=" + scheme, "map.iso=" + std::to_string(iso)});
  ASSERT_EQ(scene.scene.method, Method::pfem);
  EXPECT_DOUBLE_EQ(scene.materials[0].E, kE);
  EXPECT_DOUBLE_EQ(scene.materials[0].nu, kNu);
  EXPECT_GT(scene.bodies[0].mesh.distortion, 0.0);

  testing::TempDir dir("pfem_homogeneous_" + element + "_" + scheme + std::to_string(iso));
  auto run = testing::make_fem_run(scene, dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;

  const auto probes = testing::read_probes(dir.file("probes.csv"));
  ASSERT_EQ(probes.rows.size(), std::size_t(kSteps) + 1);
  const auto time = probes.column("time"), reaction = probes.column("reaction_top_y"), ux = probes.column("ux_right");
  const auto newton = probes.column("newton"), changed = probes.column("changed"), area_change = probes.column("area_change");
  const auto volume = probes.column("volume");
  int n_changed = 0;
  double worst_reaction = 0.0, worst_ux = 0.0, worst_area = 0.0;
  for (int n = 1; n <= kSteps; ++n) {
    const auto k = std::size_t(n);
    const auto s = exact_state(kDepth * kH * time[k]);
    const double er = verification::relative_error(reaction[k], s.reaction), eu = verification::relative_error(ux[k], s.ux_right);
    EXPECT_LE(er, 1e-8) << "step " << n;
    EXPECT_LE(eu, 1e-8) << "step " << n;
    EXPECT_LE(newton[k], 5) << "step " << n;  // quadratic convergence, as on the fixed mesh (3 observed)
    // The remesh of a convex body with alpha = 100 neither adds nor removes area (round-off of a sum of
    // 256 triangle areas of order 1e-2), and the body's area is the exact l1 l2 W H.
    EXPECT_LE(std::abs(area_change[k]), 1e-12);
    EXPECT_NEAR(volume[k], s.l1 * s.l2 * kW * kH, 1e-10) << "step " << n;
    n_changed += changed[k] == 1.0;
    worst_reaction = std::max(worst_reaction, er), worst_ux = std::max(worst_ux, eu);
    worst_area = std::max(worst_area, std::abs(area_change[k]));
  }
  // The connectivity really changes, at most steps (33 observed, the same for every element and scheme:
  // the particles follow the same exact motion).
  EXPECT_GE(n_changed, 25);
  EXPECT_EQ(changed[std::size_t(kSteps)], 1.0);  // and at the last step, so the last remesh transferred something:
  const MapStats& map = run->last_remesh().map;
  if (scheme == "cpm") {
    EXPECT_GT(map.copied, 0);
    EXPECT_EQ(map.interpolated, 0);
  } else {
    EXPECT_GT(map.interpolated, 0);
  }

  // The whole final state: displacements of every node, F_n of every quadrature point, nodal phi.
  const auto last = exact_state(kDepth * kH);
  double max_u = 0.0, max_F = 0.0, max_phi = 0.0;
  for (Index i = 0; i < run->nodes().size(); ++i) {
    const Vec2 X = run->nodes().X[i];
    max_u = std::max(max_u, (run->nodes().u_n[i] - Vec2((last.l1 - 1.0) * X.x(), (last.l2 - 1.0) * X.y())).norm());
    if (run->nodes().phi_n.used()) max_phi = std::max(max_phi, std::abs(run->nodes().phi_n[i] - last.l1 * last.l2));
  }
  const Mat3 F_exact = Vec3(last.l1, last.l2, 1.0).asDiagonal();
  for (const auto& q : run->quad_points())
    for (Index p = 0; p < q.size(); ++p) max_F = std::max(max_F, (q.F_n[p] - F_exact).cwiseAbs().maxCoeff());
  EXPECT_LE(max_u, 1e-10);
  EXPECT_LE(max_F, 1e-10);
  EXPECT_LE(max_phi, 1e-10);
  std::printf("[pfem homogeneous] %-9s %-8s: %d of %d steps changed the connectivity (last remesh: %d kept, %d copied, %d interpolated, "
              "%d fallback points); worst relative error reaction %.1e, u_x %.1e; |area change| <= %.1e; final max |u - u_exact| %.1e, "
              "|F_n - F| %.1e, |phi - J| %.1e\n",
              element.c_str(), (scheme + (scheme == "btm" ? "-iso" + std::to_string(iso) : "")).c_str(), n_changed, kSteps, int(map.kept),
              int(map.copied), int(map.interpolated), int(map.fallback), worst_reaction, worst_ux, worst_area, max_u, max_F, max_phi);
}

class PfemHomogeneous : public ::testing::TestWithParam<const char*> {};

TEST_P(PfemHomogeneous, StaysExactThrough50RemeshesWithCpm) { check(GetParam(), "cpm", 0); }
TEST_P(PfemHomogeneous, StaysExactThrough50RemeshesWithBtmIso0) { check(GetParam(), "btm", 0); }
TEST_P(PfemHomogeneous, StaysExactThrough50RemeshesWithBtmIso1) { check(GetParam(), "btm", 1); }
TEST_P(PfemHomogeneous, StaysExactThrough50RemeshesWithBtmIso2) { check(GetParam(), "btm", 2); }

INSTANTIATE_TEST_SUITE_P(Elements, PfemHomogeneous, ::testing::Values("p1", "tri6", "p1p1_uphi"));

// remesh.every = 2: the odd steps do not remesh, and their `remesh` probes say so (0 changed, 0 area change)
// instead of repeating the previous step's remesh; the even steps still change the connectivity.
TEST(PfemHomogeneousEvery2, RemeshProbesReportNoRemeshOnTheStepsBetween) {
  const SceneSpec scene = testing::scene_from_text(
      pfem_scene_text(), {"scene.method=pfem", "output.every=0", "body[0].mesh.divisions=[16,8]", "time.steps=" + std::to_string(kSteps),
                          "time.dt=" + std::to_string(1.0 / kSteps), "boundary[top].displacement.y=\"-0.5 * t\"", "remesh.every=2"});
  testing::TempDir dir("pfem_homogeneous_every2");
  auto run = testing::make_fem_run(scene, dir.path());
  ASSERT_TRUE(run->run().converged);
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  const auto changed = probes.column("changed"), area_change = probes.column("area_change"), reaction = probes.column("reaction_top_y");
  int even_changes = 0;
  for (int n = 1; n <= kSteps; ++n) {
    const auto k = std::size_t(n);
    if (n % 2 == 1) {
      EXPECT_EQ(changed[k], 0.0) << "step " << n;
      EXPECT_EQ(area_change[k], 0.0) << "step " << n;
    } else {
      even_changes += changed[k] == 1.0;
    }
    EXPECT_LE(verification::relative_error(reaction[k], exact_state(kDepth * kH * n / kSteps).reaction), 1e-8) << "step " << n;
  }
  EXPECT_GE(even_changes, 10);  // 20 of the 25 remeshes observed
  std::printf("[pfem homogeneous] remesh every 2 steps: %d of %d remeshes changed the connectivity\n", even_changes, kSteps / 2);
}

}  // namespace
}  // namespace loom
