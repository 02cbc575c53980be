// Energy of the grid-Newmark material point method (method mpm, [Moreno et al.] §3.3), on the elastic cantilever
// of scenes/cantilever_dynamic_mpm.toml (L = 2, h = 0.5, E = 4 GPa, nu = 0.32, rho = 1450, p1p1_up on a 32 x 8
// beam, clamped through the grid nodes on x = 0):
//  - free vibration from a bending velocity field large enough that the particles cross grid cells (tip
//    amplitude about two cells): kinetic + elastic energy never rises above its start. Newmark (beta = 1/4,
//    gamma = 1/2) conserves a linear grid's energy; the projection to the grid and the cell crossings only
//    dissipate. The particles' velocity update takes the grid's velocity increment (FLIP); with the particle's
//    own old acceleration in it instead, the energy of this run passed its start at step 731 and rose 93-fold by step 1500
//    (docs/mpm/velocity_update.md);
//  - the energy probe's potential of a traction (a dead load, -f . u): Clapeyron's theorem, for a linear elastic
//    body (p1, linear_elastic: the discrete energy is sum V_p psi, so u^T K u = f . u exactly) in static
//    equilibrium under a dead load the stored energy is half the load's work, potential = -2 E_el to round-off.
//    (p1p1_up's probe is not its discrete energy: it has no term for the stabilisation and takes the grid's
//    smoothed pressure; on this beam it reads 14 % low.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "engine/scene/scene_loader.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

std::string beam_text(const std::string& time, const std::string& model, const std::string& element, const std::string& body_extra,
                      const std::string& load) {
  return "[scene]\nname = \"beam\"\nmethod = \"mpm\"\n" + time +
         "[solver]\nresidual_relative = 1e-10\n"
         "[[material]]\nname = \"polymer\"\nmodel = \"" + model + "\"\nE = 4.0e9\nnu = 0.32\ndensity = 1450.0\n"
         "[[body]]\nname = \"beam\"\nmaterial = \"polymer\"\nelement = \"" + element + "\"\nparticles_per_cell = 3\n"
         "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [2.0, 0.5], divisions = [32, 8], pattern = \"alternating\" }\n" +
         body_extra +
         "[grid]\ngenerator = \"rectangle\"\norigin = [0.0, -0.25]\nsize = [2.25, 1.0]\ndivisions = [36, 16]\npattern = \"alternating\"\n"
         "[[boundary]]\nname = \"clamped\"\nregion = { box = [[0.0, -0.25], [0.0, 0.75]] }\ndisplacement = { x = 0.0, y = 0.0 }\n" +
         load +
         "[[probe]]\nname = \"uy_tip\"\nkind = \"point\"\nat = [2.0, 0.25]\ncomponent = \"y\"\n"
         "[[probe]]\nname = \"total\"\nkind = \"energy\"\nenergy = \"total\"\n"
         "[[probe]]\nname = \"elastic\"\nkind = \"energy\"\nenergy = \"elastic\"\n"
         "[[probe]]\nname = \"potential\"\nkind = \"energy\"\nenergy = \"potential\"\n"
         "[output]\nevery = 0\n";
}

testing::ProbeTable run_beam(const std::string& text, const std::string& name) {
  testing::TempDir dir(name);
  auto run = testing::make_mpm_run(testing::scene_from_text(text), dir.path());
  const RunSummary summary = run->run();
  EXPECT_TRUE(summary.converged) << summary.failure;
  return testing::read_probes(dir.file("probes.csv"));
}

TEST(MpmEnergy, GridNewmarkNeverGainsEnergyWhileParticlesCrossCells) {
  const auto probes = run_beam(beam_text("[time]\nintegrator = \"newmark\"\ndt = 1e-3\nsteps = 1000\n", "neo_hooke_split", "p1p1_up",
                                         "initial_velocity = { y = \"20.0 * (x / 2.0)^2\" }\n", ""),
                               "mpm_energy_free");
  const auto total = probes.column("total"), uy = probes.column("uy_tip");
  ASSERT_EQ(total.size(), 1001u);
  const double E0 = total.front();
  double amplitude = 0.0;
  for (std::size_t k = 0; k < total.size(); ++k) {
    EXPECT_LE(total[k], E0 * (1.0 + 1e-9)) << "step " << k;
    amplitude = std::max(amplitude, std::abs(uy[k]));
  }
  EXPECT_GT(amplitude, 0.0625);  // the tip crosses rows of cells (h = 0.0625): the case that grew
  EXPECT_GT(total.back(), 0.25 * E0);  // and the beam still vibrates: dissipated, not stopped
  std::printf("[mpm free vibration, 32 x 8] tip amplitude %.3f m, energy kept %.3f after 1000 steps\n", amplitude,
              total.back() / E0);
}

TEST(MpmEnergy, TractionPotentialIsTwiceTheStoredEnergyInStaticEquilibrium) {
  const auto probes = run_beam(beam_text("[time]\nintegrator = \"static\"\ndt = 1.0\nsteps = 1\n", "linear_elastic", "p1", "",
                                         "[[boundary]]\nname = \"loaded\"\nregion = { box = [[2.0, 0.0], [2.0, 0.5]] }\n"
                                         "traction = { y = 1.0e6 }\n"),
                               "mpm_energy_static");
  const double elastic = probes.column("elastic").back(), potential = probes.column("potential").back();
  ASSERT_GT(elastic, 0.0);
  EXPECT_NEAR(potential / elastic, -2.0, 1e-9);
  std::printf("[mpm static beam, 32 x 8] E_el %.1f J, potential %.1f J, ratio %.5f\n", elastic, potential, potential / elastic);
}

}  // namespace
}  // namespace loom
