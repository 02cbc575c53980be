// Plane-strain compression of a Neo-Hooke block between rollers (scenes/homogeneous_compression.toml)
// against the closed-form homogeneous solution, at every step, for each element formulation (p1, tri6,
// p1p1_uphi: --set body[0].element=...).
//
// Reference: with rollers u_x = 0 on x = 0, u_y = 0 on y = 0, the top y = H moved by u_y = -d and the right
// edge free, the homogeneous state F = diag(l1, l2, 1), l2 = 1 - d / H, solves the continuous and (P1 being
// exact for affine fields) the discrete problem. With the Neo-Hooke stress of seed 000 eq 51,
//   P = mu F + (lambda ln J - mu) F^-T,  J = l1 l2,
// the free right edge needs P11 = mu l1 + (lambda ln(l1 l2) - mu) / l1 = 0, i.e.
//   f(l1) = mu l1^2 + lambda ln(l1 l2) - mu = 0,   f'(l1) = 2 mu l1 + lambda / l1 > 0,
// solved here by Newton from l1 = 1 (f is increasing on l1 > 0: the root is unique). The top reaction per unit thickness is P22 W with P22 = mu l2 + (lambda ln J - mu) / l2
// (the probe sums f_int = int P22 N^A dA over the top nodes: the sum of N^A is 1), and the right edge moves
// by u_x = (l1 - 1) W. The homogeneous state is a discrete solution of every element here: tri6 integrates
// grad N^A exactly with its three points; p1p1_uphi reproduces it with phi = J = l1 l2 at every node (then
// F~ = F and the dilatation residual vanishes, see patch_test.cpp), which the test checks too.
//
// Tolerance 1e-8 relative (the figure): the scene asks Newton for |r| <= 1e-12 |r_0| and the
// probes are written with 15 significant digits; the observed error is ~1e-14.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <string>

#include "tests/support/test_support.hpp"
#include "tests/verification/homogeneous_compression_exact.hpp"
#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

// The scene's set-up (kept in one place; the test checks the loaded scene agrees with it).
constexpr double kE = 10.0, kNu = 0.3, kW = 2.0, kH = 1.0, kDepth = 0.3;  // final top displacement 0.3 H

verification::HomogeneousCompression exact_state(double d) {
  const auto s = verification::homogeneous_compression_exact(kE, kNu, kW, kH, d);
  EXPECT_LT(std::abs(s.p11), 1e-13);  // P11 = 0 really holds
  return s;
}

void check_compression(const std::string& element) {
  SCOPED_TRACE("element " + element);
  const SceneSpec scene = load_scene(verification::scene_path("homogeneous_compression.toml"),
                                     {"output.every=0", "body[0].element=" + element});
  // The scene is the set-up the reference assumes.
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[0].model, MaterialModel::neo_hooke);
  EXPECT_DOUBLE_EQ(scene.materials[0].E, kE);
  EXPECT_DOUBLE_EQ(scene.materials[0].nu, kNu);
  EXPECT_EQ(scene.bodies[0].mesh.size, Vec2(kW, kH));
  EXPECT_GT(scene.bodies[0].mesh.distortion, 0.0);
  const int steps = scene.time.steps;
  EXPECT_EQ(steps, 10);

  testing::TempDir dir("homogeneous_compression_" + element);
  auto run = testing::make_fem_run(scene, dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;

  const auto probes = testing::read_probes(dir.file("probes.csv"));
  ASSERT_EQ(probes.rows.size(), std::size_t(steps) + 1);  // step 0 and every step
  const auto time = probes.column("time"), reaction = probes.column("reaction_top_y"), ux = probes.column("ux_right");
  const auto newton = probes.column("newton");
  EXPECT_EQ(reaction[0], 0.0);
  EXPECT_EQ(ux[0], 0.0);
  double worst_reaction = 0.0, worst_ux = 0.0;
  for (int n = 1; n <= steps; ++n) {
    const double d = kDepth * kH * time[std::size_t(n)];  // the scene's u_y = -0.3 t on the top
    const auto s = exact_state(d);
    const double er = verification::relative_error(reaction[std::size_t(n)], s.reaction);
    const double eu = verification::relative_error(ux[std::size_t(n)], s.ux_right);
    EXPECT_LE(er, 1e-8) << "step " << n << ": reaction " << reaction[std::size_t(n)] << ", exact " << s.reaction;
    EXPECT_LE(eu, 1e-8) << "step " << n << ": u_x " << ux[std::size_t(n)] << ", exact " << s.ux_right;
    EXPECT_LE(newton[std::size_t(n)], 5) << "step " << n;  // quadratic convergence: 3 iterations observed
    worst_reaction = std::max(worst_reaction, er), worst_ux = std::max(worst_ux, eu);
    std::printf("[compression] %-9s step %2d: d = %.2f  l1 = %.12f  reaction %.12f (exact %.12f, rel err %.1e)  u_x %.12f (rel err %.1e)  Newton %g\n",
                element.c_str(), n, d, s.l1, reaction[std::size_t(n)], s.reaction, er, ux[std::size_t(n)], eu, newton[std::size_t(n)]);
  }
  std::printf("[compression] %-9s worst relative error: reaction %.2e, lateral displacement %.2e\n", element.c_str(),
              worst_reaction, worst_ux);

  // The whole field is the homogeneous one (a patch test with a traction-free edge on a distorted mesh).
  const auto last = exact_state(kDepth * kH);
  double max_error = 0.0;
  for (Index i = 0; i < run->nodes().size(); ++i) {
    const Vec2 X = run->nodes().X[i];
    const Vec2 exact((last.l1 - 1.0) * X.x(), (last.l2 - 1.0) * X.y());
    max_error = std::max(max_error, (run->nodes().u_n[i] - exact).norm());
  }
  EXPECT_LE(max_error, 1e-10);
  std::printf("[compression] %-9s final max |u - u_exact| over all nodes: %.2e\n", element.c_str(), max_error);

  // p1p1_uphi: the nodal dilatation is the exact J = l1 l2 (1e-10: the round-off budget of u).
  if (element == "p1p1_uphi") {
    ASSERT_TRUE(run->nodes().phi_n.used());
    double max_phi_error = 0.0;
    for (Index i = 0; i < run->nodes().size(); ++i)
      max_phi_error = std::max(max_phi_error, std::abs(run->nodes().phi_n[i] - last.l1 * last.l2));
    EXPECT_LE(max_phi_error, 1e-10);
    std::printf("[compression] %-9s final max |phi - l1 l2| over all nodes: %.2e (J = %.12f)\n", element.c_str(), max_phi_error,
                last.l1 * last.l2);
  }
}

TEST(HomogeneousCompression, P1MatchesTheAnalyticNeoHookeStateAtEveryStep) { check_compression("p1"); }
TEST(HomogeneousCompression, Tri6MatchesTheAnalyticNeoHookeStateAtEveryStep) { check_compression("tri6"); }
TEST(HomogeneousCompression, P1P1UPhiMatchesTheAnalyticNeoHookeStateWithNodalPhiEqualToJ) { check_compression("p1p1_uphi"); }

}  // namespace
}  // namespace loom
