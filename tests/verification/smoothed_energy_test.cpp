// Energy of the smoothed elements (es_up, es_u, fem_up, fem_u) and of es_pfem's remeshes.
//
// 1. The energy probe on a fixed mesh: a free linear elastic block set vibrating by an initial velocity, integrated by
//    Newmark's average acceleration with the lumped mass. Geometrically linear, these elements are linear systems
//    (the mixed ones with a symmetric pressure coupling and pressure mass K_pp,K), whose energy
//    1/2 v^T M v + 1/2 u^T K_uu u (+ 1/2 p^T K_pp,K p) the rule conserves exactly: the probe's total must stay at its
//    first value to the Newton tolerance (systems/output/mesh_energy.cpp).
// 2. es_pfem remeshes an elastic cantilever under its weight before every step (L = 1, h = 0.1, E = 1e8, 1000 steps of
//    5 ms, more than 800 connectivity changes) and integrates it with undamped Newmark. Remeshing must not pump energy
//    into it: the new triangles' reference areas once moved mass between neighbouring patches of flipped triangles
//    (volume ratios off by up to 18 %), and Newmark kept the energy that injected (3-10 times the tip deflection,
//    exit 0). The total energy may lose what the transfer of b^e dissipates, never gain more than the round-off of
//    the measure; the tip deflection stays that of the same beam on a fixed mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "tests/support/test_support.hpp"

namespace loom {
namespace {

std::string vibrating_block(const std::string& element) {
  const bool mixed = element == "es_up" || element == "fem_up";
  return "[scene]\nname = \"vibrating-block\"\nmethod = \"fem\"\n"
         "[time]\nintegrator = \"newmark\"\ndt = 0.02\nsteps = 60\n"
         "[solver]\nresidual_relative = 1e-13\nresidual_absolute = 1e-14\n"
         "[[material]]\nname = \"m\"\nmodel = \"linear_elastic\"\nE = 100.0\nnu = 0.3\ndensity = 2.0\n"
         "[[body]]\nname = \"block\"\nmaterial = \"m\"\nelement = \"" + element + "\"\n" + (mixed ? "alpha_stab = 0.0\n" : "") +
         "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [2.0, 0.5], divisions = [12, 4], pattern = \"alternating\", distortion = 0.2 }\n"
         "initial_velocity = { x = \"0.3 * (y - 0.25)\", y = \"0.2 * sin(3.14159 * x / 2)\" }\n"
         "[[probe]]\nname = \"elastic\"\nkind = \"energy\"\nenergy = \"elastic\"\n"
         "[[probe]]\nname = \"total\"\nkind = \"energy\"\nenergy = \"total\"\n"
         "[output]\nevery = 0\n";
}

TEST(SmoothedEnergy, FreeLinearVibrationKeepsItsEnergyOnAFixedMesh) {
  for (const char* element : {"es_u", "fem_u", "es_up", "fem_up"}) {
    SCOPED_TRACE(element);
    RunSummary summary;
    const auto probes = testing::run_for_probes(testing::scene_from_text(vibrating_block(element)), std::string("smoothed_energy_") + element, &summary);
    ASSERT_TRUE(summary.converged) << summary.failure;
    const auto elastic = probes.column("elastic"), total = probes.column("total");
    EXPECT_EQ(elastic[0], 0.0);
    double worst = 0.0, most_elastic = 0.0;
    for (std::size_t s = 0; s < total.size(); ++s) {
      worst = std::max(worst, std::abs(total[s] - total[0]) / total[0]);
      most_elastic = std::max(most_elastic, elastic[s] / total[0]);
    }
    EXPECT_GT(most_elastic, 0.1);  // the energy does move into the body
    EXPECT_LE(worst, 1e-9);
    std::printf("[smoothed energy] %s: largest elastic share %.2f, worst |E - E_0| / E_0 %.1e\n", element, most_elastic, worst);
  }
}

std::string sagging_cantilever(const std::string& method) {
  return "[scene]\nname = \"sagging-cantilever\"\nmethod = \"" + method + "\"\n"
         "[time]\nintegrator = \"newmark\"\ndt = 5e-3\nsteps = 1000\n"
         "[solver]\nresidual_relative = 1e-9\n"
         "[[material]]\nname = \"m\"\nmodel = \"hencky_perzyna\"\nE = 1.0e8\nnu = 0.3\ndensity = 1000.0\n"
         "[[body]]\nname = \"beam\"\nmaterial = \"m\"\nelement = \"es_up\"\nalpha_stab = 0.0\n"
         "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [1.0, 0.1], divisions = [40, 4], pattern = \"alternating\" }\n"
         "body_force = { y = -9.81 }\n"
         "[[boundary]]\nname = \"clamped\"\nregion = { box = [[0.0, 0.0], [0.0, 0.1]] }\ndisplacement = { x = 0.0, y = 0.0 }\n"
         "[[probe]]\nname = \"uy_tip\"\nkind = \"point\"\nat = [1.0, 0.05]\ncomponent = \"y\"\n"
         "[[probe]]\nname = \"mechanical\"\nkind = \"energy\"\nenergy = \"mechanical\"\n"
         "[[probe]]\nname = \"elastic\"\nkind = \"energy\"\nenergy = \"elastic\"\n" +
         (method == "es_pfem" ? "[[probe]]\nname = \"changed\"\nkind = \"remesh\"\nquantity = \"changed\"\n" : "") + "[output]\nevery = 0\n";
}

TEST(SmoothedEnergy, RemeshingAnElasticCantileverAddsNoEnergyUnderNewmark) {
  RunSummary remeshed_summary, fixed_summary;
  const auto remeshed = testing::run_for_probes(testing::scene_from_text(sagging_cantilever("es_pfem")), "smoothed_energy_es_pfem", &remeshed_summary);
  ASSERT_TRUE(remeshed_summary.converged) << remeshed_summary.failure;
  const auto fixed = testing::run_for_probes(testing::scene_from_text(sagging_cantilever("fem"), {"time.steps=300"}), "smoothed_energy_fem",
                                             &fixed_summary);
  ASSERT_TRUE(fixed_summary.converged) << fixed_summary.failure;

  const auto changed = remeshed.column("changed");
  EXPECT_GT(std::count(changed.begin(), changed.end(), 1.0), 800) << "the remeshes do not change the mesh: the test no longer tests them";
  // The scale: the elastic energy at the first largest deflection.
  const auto elastic = remeshed.column("elastic"), mechanical = remeshed.column("mechanical");
  const double scale = *std::max_element(elastic.begin(), elastic.end());
  double gain = 0.0;
  for (double e : mechanical) gain = std::max(gain, e - mechanical[0]);
  EXPECT_LT(gain, 1e-3 * scale) << "the remeshes add energy";
  const double loss = mechanical[0] - mechanical.back();
  EXPECT_LT(loss, 0.05 * scale) << "the remeshes dissipate more than expected";
  // The deflection: that of the fixed mesh (its largest over three swings), not a growing swing.
  const auto tip = remeshed.column("uy_tip"), fixed_tip = fixed.column("uy_tip");
  const double fixed_most = -*std::min_element(fixed_tip.begin(), fixed_tip.end());
  double most = 0.0;
  for (double u : tip) most = std::max(most, std::abs(u));
  EXPECT_NEAR(most, fixed_most, 0.1 * fixed_most);
  std::printf("[es_pfem energy] %.0f connectivity changes in %zu steps: largest gain %.1e, loss %.1e of the elastic peak %.4g J; "
              "largest |u_y(tip)| %.5f m (fixed mesh %.5f m)\n",
              double(std::count(changed.begin(), changed.end(), 1.0)), tip.size() - 1, gain / scale, loss / scale, scale, most, fixed_most);
}

}  // namespace
}  // namespace loom
