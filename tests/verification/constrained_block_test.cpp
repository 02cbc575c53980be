// Highly constrained rubber block, FEM (scenes/constrained_block_fem.toml; seed 000 §5.1, Figs 8-10).
// A 2 x 1 mm Neo-Hooke block (K = 1e5 MPa, G = 2 MPa, nu = 0.49999) enclosed at both sides, on a
// frictionless floor, indented by u_pre = 0.2 mm on the left half of its top in 200 steps; the probe
// `reaction` is the indenter force (negative: compression), `pressure_jump` the mean |p_1 - p_2| across
// interior edges. Mesh: 4x8 (rows x columns of element edges as in the paper: divisions [8, 4]), shifted
// rows (Fig 7b). Each 4x8 run takes about 0.2 s; meshes 8x16 and 16x32 are divisions [16, 8] and [32, 16].
//
// What the paper shows, and what we observe (the curves: docs/constrained_block/, made by
// tools/constrained_block_study.py; F = -reaction at u_pre = 0.2 mm):
//  - Reference: about 6.5 N ([3, 21] of the seed), met by p1p1_uphi with alpha_s = K/10: 6.498 N.
//  - Fig 8, alpha_s = 1, 10, 100, 1e3, 1e4, 1e5 MPa: 7.441, 7.438, 7.408, 7.118, 6.498, 5.691 N. The paper
//    says 1 ... 100 "quasi coincide" and 1e3 ... 1e5 soften increasingly. Ours: the curves 1, 10, 100 stay
//    within 0.8 % of each other over the whole path (they cross at 1e-4 relative, so no order is asserted
//    among them), and each decade from 100 on lowers the force at every step, by a growing amount at the
//    end: 0.003, 0.030, 0.29, 0.62, 0.81 N per decade. "Coincide" is asserted as: the band {1, 10, 100} is
//    at most 1 % wide at every step and narrower at the end than any later single-decade drop.
//  - Fig 9: the final pressure jump is 2.73 MPa at alpha_s = 1 against 0.464 MPa at 1e4 (5.9 x; at least
//    4.1 x at every step), and it falls monotonically with alpha_s at every step.
//  - p1 locks: 4.35 x the force of p1p1_uphi at u_pre = 0.132 mm, at least 1.46 x at every step; its
//    locked cells then distort until Newton fails (step 133).
//  (Numbers for the shifted mesh whose end trapezoids are cut by their Delaunay diagonal, so that a PFEM
//  remesh keeps the generated cells; the earlier diagonal gave 6.504 N and 7.75 ... 5.70 N.)
//  - Fig 10 says tri6 (FEM) is "slightly stiffer" than p1p1_uphi with K/10. We observe the opposite on the
//    paper's 4x8 mesh: tri6 is 5-7 % softer at every step (ratio 0.926 ... 0.949; 6.096 N at the end). This
//    is asserted as it is, not tuned. The refinement evidence says the 4x8 forces are far from converged and
//    that the ordering is a coarse-mesh effect: on 8x16, p1p1_uphi drops to 5.732 N (-12 %) and tri6 to
//    5.881 N (-3.5 %), so tri6 ends 2.6 % stiffer (it is the softer one, by up to 3.6 %, up to
//    u_pre = 0.186 mm; then the p1p1_uphi curve bends down: its slope falls from 0.031 to 0.022 N per step
//    over the last 40 steps).
//    On 16x32, tri6 gives 5.675 N; p1p1_uphi stops at u_pre = 0.155 mm with a 2-degree cell at the
//    indenter edge (see docs/constrained_block/README.md). At the same nodes (tri6 on 4x8 has the node set
//    of p1p1_uphi on 8x16) tri6 is within -1 ... +6 % of p1p1_uphi. The
//    6.5 N of the references is thus a coarse-mesh value that the stiffer coarse p1p1_uphi happens to
//    match. By the seed (§5.1), its FEM-TRI6 is its PFEM code without remeshing, with the eq-24 ties of
//    the boundary mid-nodes that method fem does not apply: with them tri6 ends 6.6 % stiffer than
//    p1p1_uphi on 4x8 (6.927 N), though still softer before u_pre = 0.14 mm (constrained_block_pfem_test.cpp,
//    Tri6WithEq24TiesAndNoRemeshingCrossesP1P1UPhiAndEndsStiffer). The plain tri6 here is verified on its
//    own (tri6_cell_test, patch_test, cooks_membrane_nearly_incompressible_test; the edge-midpoint
//    three-point rule instead of the interior one gives 6.197 N, still softer).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "tests/support/test_support.hpp"
#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

constexpr double kReferenceForce = 6.5;  // N, seed 000 §5.1
constexpr int kSteps = 200;

struct Curve {
  std::vector<double> force, jump;  // per step 0 .. kSteps: -reaction (N) and pressure_jump (MPa)
  RunSummary summary;
  double seconds = 0.0;
  double final_force() const { return force.back(); }
};

Curve run_block(const std::string& element, const std::string& alpha_s, const std::string& divisions = "[8,4]") {
  std::vector<std::string> overrides = {"output.every=0", "body[0].element=" + element, "body[0].mesh.divisions=" + divisions};
  if (!alpha_s.empty()) overrides.push_back("body[0].alpha_s=" + alpha_s);
  const SceneSpec scene = load_scene(verification::scene_path("constrained_block_fem.toml"), overrides);
  testing::TempDir dir("constrained_block_" + element + "_" + alpha_s);
  const auto start = std::chrono::steady_clock::now();
  auto run = testing::make_fem_run(scene, dir.path());
  Curve c;
  c.summary = run->run();
  c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  for (double r : probes.column("reaction")) c.force.push_back(-r);
  c.jump = probes.column("pressure_jump");
  std::printf("[constrained block] %-9s alpha_s %-4s %s: F = %.4f N, pressure jump %.4f MPa, %lld Newton iterations, %.2f s\n",
              element.c_str(), alpha_s.empty() ? "-" : alpha_s.c_str(), divisions.c_str(), c.force.back(), c.jump.back(),
              c.summary.newton_iterations, c.seconds);
  return c;
}

// Runs are made on first use and shared by the tests of one process (ctest runs each test in its own
// process, so each test asks only for the runs it needs: 0.2 ... 4.5 s per test, about 8 s in all).
const std::vector<std::string> kAlphas = {"1", "10", "100", "1e3", "1e4", "1e5"};

const Curve& uphi(const std::string& alpha_s) {
  static std::map<std::string, Curve> runs;
  auto it = runs.find(alpha_s);
  if (it == runs.end()) it = runs.emplace(alpha_s, run_block("p1p1_uphi", alpha_s)).first;
  return it->second;
}
const Curve& k_over_10() { return uphi("1e4"); }  // K / 10 = 1e4 MPa (checked below)
const Curve& tri6_4x8() {
  static const Curve c = run_block("tri6", "");
  return c;
}
const Curve& p1_4x8() {
  static const Curve c = run_block("p1", "");
  return c;
}

class ConstrainedBlock : public ::testing::Test {
 protected:
  static void expect_complete(const Curve& c) {
    ASSERT_TRUE(c.summary.converged) << c.summary.failure;
    ASSERT_EQ(c.force.size(), std::size_t(kSteps) + 1);
  }
};

TEST_F(ConstrainedBlock, CommittedSceneIsP1P1UPhiWithKOver10AndEndsWithinFivePercentOfTheReference) {
  const SceneSpec scene = load_scene(verification::scene_path("constrained_block_fem.toml"), {"output.every=0"});
  ASSERT_EQ(scene.bodies.size(), 1u);
  EXPECT_EQ(scene.bodies[0].element, Formulation::p1p1_uphi);
  EXPECT_DOUBLE_EQ(scene.bodies[0].alpha_s, 1e4);  // the default "K/10" with K = 1e5 MPa
  EXPECT_EQ(scene.time.steps, kSteps);
  const auto run = verification::run_scene(scene);
  ASSERT_TRUE(run.summary.converged) << run.summary.failure;
  const double force = -run.probes.at("reaction");
  std::printf("[constrained block] committed scene: F = %.4f N (%+.2f %% from %.1f N)\n", force,
              100 * (force - kReferenceForce) / kReferenceForce, kReferenceForce);
  EXPECT_LE(verification::relative_error(force, kReferenceForce), 0.05);  // the 5 %; observed -0.03 %
  // The explicit alpha_s = 1e4 of the sweep is the same run.
  EXPECT_NEAR(k_over_10().final_force(), force, 1e-9 * force);
  // Newton: 2 iterations per step observed (400 in all); a broken tangent would need many more.
  EXPECT_LE(run.summary.newton_iterations, 3 * kSteps);
}

TEST_F(ConstrainedBlock, StabilisationSweepCoincidesUpTo100MPaThenSoftensMonotonically) {
  for (const auto& a : kAlphas) expect_complete(uphi(a));
  // 1. Softening from 100 MPa on: each decade gives a smaller force at every step.
  for (std::size_t k = 2; k + 1 < kAlphas.size(); ++k)
    for (int s = 1; s <= kSteps; ++s)
      ASSERT_LT(uphi(kAlphas[k + 1]).force[s], uphi(kAlphas[k]).force[s]) << kAlphas[k + 1] << " vs " << kAlphas[k] << ", step " << s;
  // 2. The curves 1, 10, 100 MPa coincide: their band is at most 1 % of the force at every step (observed
  //    0.78 %)...
  double band = 0.0;
  for (int s = 1; s <= kSteps; ++s) {
    const double f[3] = {uphi("1").force[s], uphi("10").force[s], uphi("100").force[s]};
    const double hi = *std::max_element(f, f + 3), lo = *std::min_element(f, f + 3);
    band = std::max(band, (hi - lo) / hi);
  }
  EXPECT_LE(band, 0.01);
  // ...and at the end narrower than any single decade beyond (observed 0.033 N against 0.29, 0.62, 0.81 N),
  // while the drop per decade grows all along (0.003, 0.030, 0.29, 0.62, 0.81 N).
  const double band_final = std::max(uphi("1").final_force(), uphi("10").final_force()) - uphi("100").final_force();
  std::vector<double> drop;
  for (std::size_t k = 0; k + 1 < kAlphas.size(); ++k) drop.push_back(uphi(kAlphas[k]).final_force() - uphi(kAlphas[k + 1]).final_force());
  for (std::size_t k = 2; k < drop.size(); ++k) EXPECT_GT(drop[k], band_final) << "decade " << kAlphas[k] << " -> " << kAlphas[k + 1];
  for (std::size_t k = 1; k < drop.size(); ++k) EXPECT_GT(drop[k], drop[k - 1]) << "decade " << kAlphas[k] << " -> " << kAlphas[k + 1];
  // The softest curve departs clearly: more than 20 % below alpha_s = 1 at the end (observed 24 %).
  EXPECT_LT(uphi("1e5").final_force(), 0.8 * uphi("1").final_force());
  std::printf("[constrained block] band 1-100 MPa: %.2f %% (final %.3f N); decade drops:", 100 * band, band_final);
  for (double d : drop) std::printf(" %.3f", d);
  std::printf(" N\n");
}

TEST_F(ConstrainedBlock, PressureJumpIsMuchLargerAtAlpha1ThanAtKOver10) {
  // Fig 9: pressure oscillations at alpha_s = 1 MPa, none to speak of at K/10. Observed final 2.73 against
  // 0.464 MPa (5.9 x), at least 4.1 x at every step. 3.5 x keeps a margin below the observed minimum; a
  // stabilisation that did not act on the pressure field would give about 1 x.
  for (int s = 1; s <= kSteps; ++s) {
    ASSERT_GT(uphi("1").jump[s], 3.5 * k_over_10().jump[s]) << "step " << s;
    for (std::size_t k = 0; k + 1 < kAlphas.size(); ++k)
      ASSERT_LT(uphi(kAlphas[k + 1]).jump[s], uphi(kAlphas[k]).jump[s]) << kAlphas[k + 1] << ", step " << s;
  }
  std::printf("[constrained block] final pressure jump:");
  for (const auto& a : kAlphas) std::printf(" %s: %.3f", a.c_str(), uphi(a).jump.back());
  std::printf(" MPa; ratio 1 / 1e4 = %.2f\n", uphi("1").jump.back() / k_over_10().jump.back());
}

TEST_F(ConstrainedBlock, P1LocksFarStifferThanTheMixedElement) {
  const Curve& p1 = p1_4x8();
  // The locked cells distort until Newton gives up (observed at step 133, exit code 1 with the last
  // converged step); up to there: 1.46 x at the start, 4.35 x at step 132.
  ASSERT_GE(p1.force.size(), std::size_t(121)) << p1.summary.failure;
  for (std::size_t s = 1; s < p1.force.size(); ++s) ASSERT_GT(p1.force[s], 1.3 * k_over_10().force[s]) << "step " << s;
  EXPECT_GT(p1.force[120], 3.0 * k_over_10().force[120]);
}

TEST_F(ConstrainedBlock, Tri6IsSofterThanP1P1UPhiOnThe4x8MeshAndStifferOnceRefined) {
  // Not what Fig 10 shows on 4x8 (the paper's tri6 carries the eq-24 ties): see the header.
  const Curve& tri6 = tri6_4x8();
  const Curve uphi_8x16 = run_block("p1p1_uphi", "", "[16,8]"), tri6_8x16 = run_block("tri6", "", "[16,8]");
  expect_complete(tri6);
  expect_complete(uphi_8x16);
  expect_complete(tri6_8x16);
  // 1. 4x8: tri6 is 5-7 % softer all along (observed ratio 0.926 ... 0.949); 0.90 and 0.97 bracket it.
  for (int s = 1; s <= kSteps; ++s) {
    const double ratio = tri6.force[s] / k_over_10().force[s];
    ASSERT_GT(ratio, 0.90) << "step " << s;
    ASSERT_LT(ratio, 0.97) << "step " << s;
  }
  // 2. 8x16: both forces fall, the mixed element's much more (observed -11.9 % and -3.5 %), and tri6 ends
  //    stiffer (observed 5.881 against 5.732 N).
  EXPECT_LT(uphi_8x16.final_force(), 0.92 * k_over_10().final_force());
  EXPECT_LT(tri6_8x16.final_force(), 0.99 * tri6.final_force());
  EXPECT_GT(tri6_8x16.final_force(), 0.94 * tri6.final_force());
  EXPECT_GT(tri6_8x16.final_force(), uphi_8x16.final_force());
  // ...after crossing over late: at u_pre = 0.1 mm tri6 is still the softer (observed 0.979).
  EXPECT_LT(tri6_8x16.force[100], uphi_8x16.force[100]);
  std::printf("[constrained block] final F: 4x8 p1p1_uphi %.4f, tri6 %.4f (ratio %.3f); 8x16 p1p1_uphi %.4f, tri6 %.4f (ratio %.3f)\n",
              k_over_10().final_force(), tri6.final_force(), tri6.final_force() / k_over_10().final_force(),
              uphi_8x16.final_force(), tri6_8x16.final_force(), tri6_8x16.final_force() / uphi_8x16.final_force());
}

}  // namespace
}  // namespace loom
