// es_pfem on tetrahedra, a whole flow (scenes/column_slump_es_3d.toml): a quarter column of Bingham paste (R0 = 5 cm,
// H0 = 10 cm, tau0 = 0.15 rho g H0) slumps on a stick ground between two frictionless symmetry walls, remeshed before
// every step, and stops. Pashias et al.'s slump of a cylinder, s' = 1 - 2 tau' (1 - ln 2 tau') = 0.339, gives a final
// height of 66.1 mm; the formula is quasi-static and approximate, so the acceptance is 10 %. Shown at every step: the
// mass kept to 1e-9 through the remeshes (the face domains' reference volumes shared out, domain_transfer.hpp), the
// volume within 2 % of the initial one (the u-p element's dilation); at the end: the height, the two fronts (x and y:
// the quarter stays symmetric) within one cell of each other, the paste nearly at rest and its weight on the ground.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "engine/scene/scene_loader.hpp"
#include "tests/support/test_support.hpp"
#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

TEST(ColumnSlump3d, StopsAtPashiasHeightWithItsMassAndVolume) {
  const SceneSpec scene = load_scene(verification::scene_path("column_slump_es_3d.toml"), {"output.every=0"});
  testing::TempDir dir("column_slump_3d");
  auto run = testing::make_fem_run<3>(scene, dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  const std::vector<double> mass = probes.column("mass"), volume = probes.column("volume"), changed = probes.column("changed");
  ASSERT_GT(mass.size(), 100u);
  double mass_drift = 0.0, volume_drift = 0.0, changes = 0.0;
  for (std::size_t k = 0; k < mass.size(); ++k) {
    mass_drift = std::max(mass_drift, std::abs(mass[k] / mass[0] - 1.0));
    volume_drift = std::max(volume_drift, std::abs(volume[k] / volume[0] - 1.0));
    changes += changed[k];
  }
  const double height = probes.column("height").back(), front_x = probes.column("front_x").back(),
               front_y = probes.column("front_y").back(), speed = probes.column("speed").back();
  const double rho = 2300.0, g = 9.81, H0 = 0.1, tau_prime = 338.4 / (rho * g * H0);
  const double slump = 1.0 - 2.0 * tau_prime * (1.0 - std::log(2.0 * tau_prime)), expected = H0 * (1.0 - slump);
  const double weight = mass.back() * g, ground = probes.column("ground_z").back();
  std::printf("[column slump 3D] %g remeshes changed the mesh; height %.2f mm (Pashias %.2f mm, %+.1f %%), fronts x %.2f y %.2f mm, "
              "max |m/m0 - 1| %.1e, max |V/V0 - 1| %.2f %%, final speed %.2e m/s, ground %.4f N (weight %.4f N)\n",
              changes, 1e3 * height, 1e3 * expected, 100.0 * (height / expected - 1.0), 1e3 * front_x, 1e3 * front_y, mass_drift,
              100.0 * volume_drift, speed, ground, weight);
  EXPECT_GT(changes, 50.0) << "the mesh must change for the test to mean anything";
  EXPECT_NEAR(height, expected, 0.1 * expected);
  EXPECT_LE(mass_drift, 1e-9);
  EXPECT_LT(volume_drift, 0.02);
  EXPECT_LT(std::abs(front_x - front_y), 0.01);  // one cell
  EXPECT_GT(front_x, 0.05 + 0.01);               // it spread
  EXPECT_LT(speed, 0.01);
  EXPECT_NEAR(ground, weight, 0.02 * weight);
}

}  // namespace
}  // namespace loom
