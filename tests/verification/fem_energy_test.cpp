// The energy probe of the mesh-based methods (systems/output/mesh_energy.hpp). A free linear elastic body set
// vibrating by an initial velocity field, integrated with Newmark's average-acceleration rule (beta = 1/4,
// gamma = 1/2) and the lumped mass: for a linear system M a + K u = 0 this rule conserves
// E = 1/2 v^T M v + 1/2 u^T K u exactly (the discrete energy identity of the trapezoidal rule), and the probe's
// kinetic + elastic energy is that E (the elastic part integrates psi(eps) = 1/2 eps : C : eps, i.e.
// 1/2 u^T K u, exactly for P1). So the total stays at its first value to the Newton tolerance while energy
// flows between its parts; at t = 0 the kinetic part is 1/2 sum m_A |v_0(X_A)|^2 and the elastic part 0.
// The consistent mass exits 2 naming the probe (last test).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "engine/core/errors.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

std::string vibrating_block(const std::string& element = "p1", const std::string& model = "linear_elastic") {
  return "[scene]\nname = \"vibrating-block\"\nmethod = \"fem\"\n"
         "[time]\nintegrator = \"newmark\"\ndt = 0.02\nsteps = 60\n"
         "[solver]\nresidual_relative = 1e-13\nresidual_absolute = 1e-14\n"
         "[[material]]\nname = \"m\"\nmodel = \"" + model + "\"\nE = 100.0\nnu = 0.3\ndensity = 2.0\n"
         "[[body]]\nname = \"block\"\nmaterial = \"m\"\nelement = \"" + element + "\"\n"
         "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [2.0, 0.5], divisions = [12, 4], pattern = \"alternating\", distortion = 0.2 }\n"
         "initial_velocity = { x = \"0.3 * (y - 0.25)\", y = \"0.2 * sin(3.14159 * x / 2)\" }\n"
         "[[probe]]\nname = \"kinetic\"\nkind = \"energy\"\nenergy = \"kinetic\"\n"
         "[[probe]]\nname = \"elastic\"\nkind = \"energy\"\nenergy = \"elastic\"\n"
         "[[probe]]\nname = \"total\"\nkind = \"energy\"\nenergy = \"total\"\n"
         "[output]\nevery = 0\n";
}

}  // namespace

TEST(FemEnergyProbe, FreeLinearVibrationKeepsItsEnergyUnderAverageAcceleration) {
  const SceneSpec scene = testing::scene_from_text(vibrating_block());
  RunSummary summary;
  const auto probes = testing::run_for_probes(scene, "fem_energy", &summary);
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto kinetic = probes.column("kinetic"), elastic = probes.column("elastic"), total = probes.column("total");
  // t = 0: the kinetic energy of the lumped masses at the initial velocity, nothing stored.
  auto run = testing::make_fem_run(scene);
  const Nodes<2>& n = run->nodes();
  double k0 = 0.0;
  for (Index i = 0; i < n.size(); ++i) {
    const Vec2 X = n.X[i];
    k0 += 0.5 * n.lumped_mass[i] * Vec2(0.3 * (X.y() - 0.25), 0.2 * std::sin(3.14159 * X.x() / 2)).squaredNorm();
  }
  EXPECT_NEAR(kinetic[0], k0, 1e-13 * k0);
  EXPECT_EQ(elastic[0], 0.0);
  double worst = 0.0, most_elastic = 0.0;
  for (std::size_t s = 0; s < total.size(); ++s) {
    worst = std::max(worst, std::abs(total[s] - total[0]) / total[0]);
    most_elastic = std::max(most_elastic, elastic[s] / total[0]);
  }
  EXPECT_GT(most_elastic, 0.1);  // the energy does move into the body
  EXPECT_LE(worst, 1e-9);
  std::printf("[fem energy] free linear vibration, %zu steps: E_0 = %.6g, largest elastic share %.2f, worst |E - E_0| / E_0 %.1e\n",
              total.size() - 1, total[0], most_elastic, worst);
}

TEST(FemEnergyProbe, RefusedWhereItIsNotImplemented) {
  // The consistent mass (the kinetic part is the lumped mass's). (The smoothed elements have their own:
  // smoothed_energy_test.)
  std::string consistent = vibrating_block();
  consistent.replace(consistent.find("steps = 60"), 10, "steps = 60\nmass = \"consistent\"");
  for (const std::string& text : {consistent}) {
    try {
      testing::scene_from_text(text);
      ADD_FAILURE() << "the energy probe was taken";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("probe[0].kind"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("method fem"), std::string::npos) << e.what();
    }
  }
}

}  // namespace loom
