// 3D concrete printing (scenes/concrete_printing_es_3d.toml, the extrusion benchmark of Reinold and Meschke): a nozzle
// of radius r = 28 mm moving along x at v_print = 0.05 m/s, 24 mm above a stick ground, pushes a Bingham mortar out at
// v_in = 0.03447 m/s; half model on a frictionless symmetry wall, 9.3 mm cells. Run for 2 s (the nozzle 10 cm along,
// the section at x = 4 cm more than a nozzle diameter behind it):
//  - the mass balance: the layer at rest behind the nozzle has the section pi r^2 v_in / v_print / 2 = 8.49 cm^2 (5 %,
//    the spec's CI tolerance), a half width between the rectangle's 3.54 and the rounded corners' 3.80 cm (within half
//    a cell) and the nozzle's height (within half a cell);
//  - mass: it changes only when a layer is added (to round-off through every remesh); the volume and the mass
//    downstream of the moving disc are V_0 + v_in A t within 2 % (A the pattern's area, read from the mass of one
//    layer, rho A h): the cells between the driven layer and the deposit are sheared as the nozzle moves on, and a
//    cell's part below the disc, counted by its volume, is then not the part its mass has crossed (exact where the
//    layers move rigidly: inflow_3d_test); a layer crosses the disc every h / v_in;
//  - nothing left behind: the section does not change over the last half second.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "engine/scene/scene_loader.hpp"
#include "tests/support/test_support.hpp"
#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

TEST(ConcretePrinting3d, TheLayerHasTheSectionOfTheMassBalance) {
  const SceneSpec scene = load_scene(verification::scene_path("concrete_printing_es_3d.toml"), {"output.every=0", "time.steps=400"});
  testing::TempDir dir("concrete_printing_3d");
  auto run = testing::make_fem_run<3>(scene, dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  const auto t = probes.column("time"), area = probes.column("section_area"), half_width = probes.column("half_width"),
             height = probes.column("layer_height"), poured = probes.column("poured"), poured_mass = probes.column("poured_mass"),
             mass = probes.column("mass"), inserted = probes.column("inserted");
  constexpr double r = 0.028, v_in = 0.03447, v_print = 0.05, h = 0.0093, rho = 2078.0;
  const double target = M_PI * r * r * v_in / v_print / 2.0;
  // One layer's mass (a later one: the first is shorter) gives the pattern's area.
  double layer_mass = 0.0;
  int layers = 0;
  for (std::size_t k = 1; k < t.size(); ++k)
    if (inserted[k] > 0 && ++layers == 2) layer_mass = mass[k] - mass[k - 1];
  const double A = layer_mass / (rho * h);
  double worst_volume = 0.0, worst_mass = 0.0, mass_drift = 0.0;
  for (std::size_t k = 1; k < t.size(); ++k) {
    const double expected = poured[0] + v_in * A * t[k];
    worst_volume = std::max(worst_volume, std::abs(poured[k] / expected - 1.0));
    worst_mass = std::max(worst_mass, std::abs(poured_mass[k] / (rho * expected) - 1.0));
    if (inserted[k] == 0.0) mass_drift = std::max(mass_drift, std::abs(mass[k] / mass[k - 1] - 1.0));
  }
  const std::size_t last = t.size() - 1, earlier = last - 100;  // 0.5 s before
  std::printf("[concrete printing 3D] t = %.3f s: section %.4f cm^2 (mass balance %.4f, %+.2f %%), half width %.3f cm, height %.3f cm; "
              "%d layers of %.3f cm^2 (the half disc %.3f); poured volume within %.2f %%, mass within %.2f %% of v_in A t; mass "
              "between layers kept to %.1e; section 0.5 s earlier %.4f cm^2\n",
              t[last], 1e4 * area[last], 1e4 * target, 100.0 * (area[last] / target - 1.0), 1e2 * half_width[last], 1e2 * height[last], layers,
              1e4 * A, 1e4 * M_PI * r * r / 2.0, 100.0 * worst_volume, 100.0 * worst_mass, mass_drift, 1e4 * area[earlier]);
  EXPECT_NEAR(t[last], 2.0, 1e-9);
  EXPECT_NEAR(area[last], target, 0.05 * target);
  EXPECT_GT(half_width[last], 0.0354 - h / 2.0);
  EXPECT_LT(half_width[last], 0.0380 + h / 2.0);
  EXPECT_LT(height[last], 0.024 + h / 2.0);
  EXPECT_GT(height[last], 0.024 - h / 2.0);
  // The first layer is h_1 = v_in T - (round(v_in T / h) - 1) h upstream (T = 3 s: the last crosses the disc at T), the
  // next ones h apart: by t, 2 + floor((v_in t - h_1) / h) of them (the first at t = 0, one as each crosses).
  const double T = 3.0, h_1 = v_in * T - (std::round(v_in * T / h) - 1.0) * h;
  EXPECT_EQ(layers, 2 + int(std::floor((v_in * t[last] - h_1) / h)));
  EXPECT_GT(A, 0.95 * M_PI * r * r / 2.0);  // the pattern is the half disc's polygon
  EXPECT_LT(A, M_PI * r * r / 2.0);
  EXPECT_LT(mass_drift, 1e-12);
  EXPECT_LT(worst_volume, 0.02);
  EXPECT_LT(worst_mass, 0.02);
  EXPECT_NEAR(area[earlier], area[last], 0.01 * area[last]);
}

}  // namespace
}  // namespace loom
