// drucker_prager at the points that carry its history b^e from step to step (history_point.hpp), in a run:
//  - fem (p1, tri6) and pfem (p1, remeshed before every step): a square whose boundary follows the homogeneous
//    plane-strain deformation of the element test (x -> exp(e1 t) x, y -> exp(e2 t) y; compressed and sheared), 7
//    static steps that cross the yield time inside a step: every quadrature point's Kirchhoff stress tau(b^e_n) on
//    the closed form (tests/support/drucker_prager_path.hpp) to 1e-9, the stress probe reading tau / J, for
//    associated and non-associated flow (UMFPACK: the tangent of the latter is unsymmetric);
//  - mpm, p1: the block of tests/scenes/mpm_bingham_block.toml made of a frictional material resting on a stick
//    ground carries rho g V to 1e-10, elastically with a large cohesion and with particles yielding with a small
//    one. Cohesionless, it would collapse: the granular column of scenes/granular_collapse_mpm.toml.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "engine/scene/scene_loader.hpp"
#include "systems/assemble/materials/material.hpp"
#include "tests/support/drucker_prager_path.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

constexpr double kE1 = -0.002, kE2 = 0.0008;  // log strain rates of the element test

std::string element_test_scene(const std::string& method, const std::string& element, double dilatancy) {
  std::ostringstream s;
  s << "[scene]\nname = \"dp-element\"\nmethod = \"" << method << "\"\n"
    << "[time]\nintegrator = \"static\"\ndt = 1.0\nsteps = 7\n"
    << "[solver]\nresidual_relative = 1e-12\n"
    << "[[material]]\nname = \"sand\"\nmodel = \"drucker_prager\"\nK = 5.0e6\nG = 3.0e6\nfriction_angle = 30.0\n"
    << "dilatancy_angle = " << dilatancy << "\ncohesion = 2.0e3\n"
    << "[[body]]\nname = \"block\"\nmaterial = \"sand\"\nelement = \"" << element << "\"\n"
    << "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [1.0, 1.0], divisions = [3, 3], pattern = \"alternating\" }\n";
  const std::string ux = "(exp(" + std::to_string(kE1) + " * t) - 1) * x", uy = "(exp(" + std::to_string(kE2) + " * t) - 1) * y";
  int k = 0;
  for (const char* side : {"[[0.0, 0.0], [1.0, 0.0]]", "[[0.0, 1.0], [1.0, 1.0]]", "[[0.0, 0.0], [0.0, 1.0]]", "[[1.0, 0.0], [1.0, 1.0]]"})
    s << "[[boundary]]\nname = \"side" << k++ << "\"\nregion = { box = " << side << " }\n"
      << "displacement = { x = \"" << ux << "\", y = \"" << uy << "\" }\n";
  s << "[[probe]]\nname = \"sxx\"\nkind = \"stress\"\nat = [0.4, 0.6]\ncomponent = \"xx\"\n"
    << "[[probe]]\nname = \"szz\"\nkind = \"stress\"\nat = [0.4, 0.6]\ncomponent = \"zz\"\n"
    << "[output]\nevery = 0\n";
  return s.str();
}

TEST(DruckerPragerPoints, ElementTestFollowsTheClosedFormAtEveryPoint) {
  for (const auto& [method, element] : {std::pair{"fem", "p1"}, std::pair{"fem", "tri6"}, std::pair{"pfem", "p1"}})
    for (const double psi : {0.0, 30.0}) {
      SCOPED_TRACE(std::string(method) + " " + element);
      SceneSpec scene = testing::scene_from_text(element_test_scene(method, element, psi));
      const HenckyPerzyna model = std::get<HenckyPerzyna>(make_material(scene.materials[0]));
      const testing::RadialStrainPath path{model, Vec3(kE1, kE2, 0.0)};
      // Seven steps to three times the yield time, t_y falling inside a step.
      scene.time.dt = 3.0 * path.yield_time() / 7.0;
      auto run = testing::make_fem_run(scene);
      const RunSummary summary = run->run();
      ASSERT_TRUE(summary.converged) << summary.failure;
      EXPECT_EQ(run->model().linear_solver, psi == 30.0 ? LinearSolverKind::automatic : LinearSolverKind::umfpack);
      const double t = 7.0 * scene.time.dt;
      const Vec3 expected = path.stress(t);
      const QuadPoints<2>& q = run->model().quad[0];
      ASSERT_TRUE(q.be_n.used());
      double worst = 0.0;
      for (Index p = 0; p < q.size(); ++p) {
        const Mat3 tau = model.kirchhoff(q.be_n[p]);
        worst = std::max(worst, (tau - Mat3(expected.asDiagonal())).norm() / expected.norm());
      }
      const double J = std::exp((kE1 + kE2) * t);
      std::printf("[drucker-prager] %s %s, psi %.0f: tau_xx %.6f kPa (closed form %.6f), worst point %.1e\n", method, element, psi,
                  model.kirchhoff(q.be_n[0])(0, 0) / 1e3, expected[0] / 1e3, worst);
      EXPECT_LT(worst, 1e-9) << "psi " << psi;
      EXPECT_NEAR(run->probe_values()[0], expected[0] / J, 1e-9 * expected.norm());
      EXPECT_NEAR(run->probe_values()[1], expected[2] / J, 1e-9 * expected.norm());
      EXPECT_GT(path.stress(t).norm(), 1.5 * path.stress(path.yield_time()).norm());  // well past yield
    }
}

struct Block {
  RunSummary summary;
  double ground_force = 0.0;
  int yielded = 0;
};

Block resting_block(double cohesion) {
  std::string text = testing::read_text(std::string(LOOM_SOURCE_DIR) + "/tests/scenes/mpm_bingham_block.toml");
  const std::string bingham = "model = \"hencky_perzyna\"\nE = 1e7\nnu = 0.3\ntau0 = 1e5\nviscosity = 10.0\n";
  EXPECT_NE(text.find(bingham), std::string::npos);
  text.replace(text.find(bingham), bingham.size(),
               "model = \"drucker_prager\"\nE = 1e7\nnu = 0.3\nfriction_angle = 30.0\ncohesion = " + std::to_string(cohesion) + "\n");
  const SceneSpec scene = testing::scene_from_text(text, {"time.steps=3"});
  auto run = testing::make_mpm_run(scene);
  Block b;
  b.summary = run->run();
  b.ground_force = run->probe_values()[0];
  const Points<2>& particles = run->model().particles;
  for (Index p = 0; p < particles.X.size(); ++p) b.yielded += (particles.be[p] - particles.F[p] * particles.F[p].transpose()).norm() > 1e-9;
  return b;
}

TEST(DruckerPragerPoints, MpmBlockRestsOnTheGroundElasticallyAndYielding) {
  constexpr double kWeight = 2000.0 * 9.81 * 1.0;
  const Block strong = resting_block(2e4), weak = resting_block(5e3);
  ASSERT_TRUE(strong.summary.converged) << strong.summary.failure;
  ASSERT_TRUE(weak.summary.converged) << weak.summary.failure;
  std::printf("[drucker-prager] mpm block: ground %.10f and %.10f of %.10f N, %d particles yielded with c = 5 kPa\n", strong.ground_force,
              weak.ground_force, kWeight, weak.yielded);
  EXPECT_NEAR(strong.ground_force, kWeight, 1e-10 * kWeight);
  EXPECT_NEAR(weak.ground_force, kWeight, 1e-10 * kWeight);
  EXPECT_EQ(strong.yielded, 0);
  EXPECT_GT(weak.yielded, 0);
}

}  // namespace
}  // namespace loom
