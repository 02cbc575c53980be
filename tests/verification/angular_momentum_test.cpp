// The angular_momentum probe: sum m (r x v) of the lumped nodal masses (fem) or the particles (mpm), r from the
// probe's `at`. A free Neo-Hooke block spun by an initial velocity omega (-y, x) about its centre starts with
// L_0 = omega sum m |X|^2 exactly. Newmark's average-acceleration rule with the internal force at t_{n+1} (not
// at the midpoint) does not conserve angular momentum exactly: after one second its drift falls with the
// square of dt (observed 4.7e-4, 8.2e-5, 2.1e-5 at dt = 0.05, 0.025, 0.0125: rates 2.5, 2.0), which the test
// asserts, together with the size of the finest drift.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "tests/support/test_support.hpp"

namespace loom {
namespace {

constexpr double kOmega = 1.0;

std::string spinning_block(const std::string& method, double dt) {
  std::string s = "[scene]\nname = \"spin\"\nmethod = \"" + method + "\"\n"
                  "[time]\nintegrator = \"newmark\"\ndt = " + std::to_string(dt) + "\nsteps = " + std::to_string(int(std::lround(1.0 / dt))) + "\n"
                  "[solver]\nresidual_relative = 1e-12\n"
                  "[[material]]\nname = \"m\"\nmodel = \"neo_hooke\"\nE = 50.0\nnu = 0.3\ndensity = 1.0\n"
                  "[[body]]\nname = \"block\"\nmaterial = \"m\"\nelement = \"p1\"\n"
                  "mesh = { generator = \"rectangle\", origin = [-1.0, -0.25], size = [2.0, 0.5], divisions = [16, 4], pattern = \"alternating\" }\n"
                  "initial_velocity = { x = \"-1.0 * y\", y = \"1.0 * x\" }\n"
                  "[[probe]]\nname = \"L\"\nkind = \"angular_momentum\"\n"
                  "[output]\nevery = 0\n";
  if (method == "mpm") s += "[grid]\ngenerator = \"rectangle\"\norigin = [-2.0, -2.0]\nsize = [4.0, 4.0]\ndivisions = [16, 16]\npattern = \"right\"\n";
  return s;
}

}  // namespace

TEST(AngularMomentumProbe, StartsAtOmegaSumMR2AndDriftsAsDtSquaredUnderNewmark) {
  std::vector<double> drift;
  for (double dt : {0.05, 0.025, 0.0125}) {
    const SceneSpec scene = testing::scene_from_text(spinning_block("fem", dt));
    RunSummary summary;
    const auto probes = testing::run_for_probes(scene, "angular_momentum", &summary);
    ASSERT_TRUE(summary.converged) << summary.failure;
    const auto L = probes.column("L");
    auto run = testing::make_fem_run(scene);
    double L0 = 0.0;
    for (Index i = 0; i < run->nodes().size(); ++i) L0 += run->nodes().lumped_mass[i] * kOmega * run->nodes().X[i].squaredNorm();
    EXPECT_NEAR(L.front(), L0, 1e-14 * L0);
    drift.push_back(std::abs(L.back() - L.front()) / L.front());
  }
  const double rate = std::log2(drift[1] / drift[2]);
  std::printf("[angular momentum] drift after 1 s at dt = 0.05, 0.025, 0.0125: %.2e %.2e %.2e (rate %.2f)\n", drift[0], drift[1], drift[2], rate);
  EXPECT_GT(rate, 1.8);
  EXPECT_LT(drift[2], 5e-5);
}

TEST(AngularMomentumProbe, OfTheParticlesInMpm) {
  const SceneSpec scene = testing::scene_from_text(spinning_block("mpm", 0.05));
  auto run = testing::make_mpm_run(scene);
  double L0 = 0.0;
  const auto& p = run->model().particles;
  for (Index k = 0; k < p.X.size(); ++k) L0 += p.mass[k] * kOmega * p.X[k].squaredNorm();
  ASSERT_GT(L0, 0.0);
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  // probe_values() holds the last step's: recompute it from the particles and compare.
  double L = 0.0;
  for (Index k = 0; k < p.X.size(); ++k) {
    const Vec2 r = p.position(k);
    L += p.mass[k] * (r.x() * p.v[k].y() - r.y() * p.v[k].x());
  }
  EXPECT_NEAR(run->probe_values().at(0), L, 1e-12 * L0);
  std::printf("[angular momentum] mpm, grid Newmark, 20 steps of 0.05: L / L_0 = %.6f\n", L / L0);
  // A sanity bound: the transfers through a grid of two cells across the block lose some in one second. The
  // projection of a linear field to the lumped grid mass is the field at each node's particle centroid, not at the
  // node, so PIC/FLIP transfers do not conserve angular momentum: 5.5 % lost here (3.5 % when the particles
  // took their own old acceleration, the form that gained energy without bound: docs/mpm/velocity_update.md).
  EXPECT_LT(std::abs(L - L0) / L0, 0.06);
}

}  // namespace loom
