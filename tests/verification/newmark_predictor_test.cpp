// time.predictor = "constant_acceleration" (systems/update/update_iterate.hpp): Newton starts a Newmark step from
// u_n + dt v_n + dt^2 a_n / 2 instead of u_n. The start changes the path, not the answer:
//  - Free fall (a_0 from equilibrium): the predictor is the exact step (a_n+1 = a_n = g, a rigid translation has no
//    internal force), so every step converges with no Newton iteration, and u_z = -g t^2 / 2 at every node.
//  - A Neo-Hooke box set spinning (v_0 = omega (-y, x, 0), 0.2 rad per step): both starts converge to the same
//    states (the Newton tolerance apart), and the predictor, which already carries the centripetal acceleration,
//    needs fewer iterations.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "tests/support/test_support.hpp"

namespace loom {
namespace {

std::string scene_text(const std::string& time_extra, const std::string& body_extra, const std::string& probes) {
  return "[scene]\nname = \"predictor\"\nmethod = \"fem\"\ndimension = 3\n"
         "[time]\nintegrator = \"newmark\"\ndt = 0.05\nsteps = 20\n" + time_extra +
         "[solver]\nresidual_relative = 1e-12\nresidual_absolute = 1e-13\n"
         "[output]\nevery = 0\n"
         "[[material]]\nname = \"m\"\nmodel = \"neo_hooke\"\nE = 100.0\nnu = 0.3\ndensity = 2.0\n"
         "[[body]]\nname = \"box\"\nmaterial = \"m\"\nelement = \"p1\"\n"
         "mesh = { generator = \"box\", origin = [-0.5, -0.25, -0.25], size = [1.0, 0.5, 0.5], divisions = [6, 3, 3], distortion = 0.2 }\n" +
         body_extra + probes + "[[probe]]\nname = \"newton\"\nkind = \"newton\"\n";
}

std::string point_probes() {
  std::string s;
  for (const char* c : {"x", "y", "z"})
    s += std::string("[[probe]]\nname = \"u") + c + "\"\nkind = \"point\"\nat = [0.5, 0.25, 0.25]\ncomponent = \"" + c + "\"\n";
  return s;
}

TEST(NewmarkPredictor, FreeFallNeedsNoNewtonIteration) {
  std::string text = scene_text("initial_acceleration = \"equilibrium\"\npredictor = \"constant_acceleration\"\n", "",
                                "[body_force]\nz = -9.81\n" + point_probes());
  // The default tolerance (1e-8 of the weight): the predictor's residual is round-off in f_int of a translated box.
  text.replace(text.find("residual_relative = 1e-12"), 25, "residual_relative = 1e-8");
  RunSummary summary;
  const auto p = testing::run_for_probes(testing::scene_from_text(text), "predictor_fall", &summary);
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto t = p.column("time"), uz = p.column("uz"), newton = p.column("newton");
  for (std::size_t s = 0; s < t.size(); ++s) {
    EXPECT_NEAR(uz[s], -0.5 * 9.81 * t[s] * t[s], 1e-12) << "step " << s;
    EXPECT_EQ(newton[s], 0.0) << "step " << s;
  }
}

TEST(NewmarkPredictor, SpinningBoxSameStatesInFewerIterations) {
  const std::string spin = "initial_velocity = { x = \"-4.0 * y\", y = \"4.0 * x\" }\n";
  RunSummary from_last, from_predictor;
  const auto a = testing::run_for_probes(testing::scene_from_text(scene_text("", spin, point_probes())), "predictor_spin_last", &from_last);
  const auto b = testing::run_for_probes(
      testing::scene_from_text(scene_text("predictor = \"constant_acceleration\"\n", spin, point_probes())), "predictor_spin", &from_predictor);
  ASSERT_TRUE(from_last.converged) << from_last.failure;
  ASSERT_TRUE(from_predictor.converged) << from_predictor.failure;
  double worst = 0.0, largest = 0.0, iterations_last = 0.0, iterations_predictor = 0.0;
  for (const char* c : {"ux", "uy", "uz"}) {
    const auto ua = a.column(c), ub = b.column(c);
    ASSERT_EQ(ua.size(), ub.size());
    for (std::size_t s = 0; s < ua.size(); ++s) worst = std::max(worst, std::abs(ua[s] - ub[s])), largest = std::max(largest, std::abs(ua[s]));
  }
  for (double n : a.column("newton")) iterations_last += n;
  for (double n : b.column("newton")) iterations_predictor += n;
  std::printf("[newmark predictor] spinning box, 20 steps of 0.2 rad: Newton iterations %g (from u_n) and %g (predictor), "
              "largest |u| %.3f, largest difference %.1e\n", iterations_last, iterations_predictor, largest, worst);
  EXPECT_GT(largest, 0.3);  // the corner has turned through 4 rad
  EXPECT_LE(worst, 1e-8 * largest);
  EXPECT_LT(iterations_predictor, iterations_last);
}

}  // namespace
}  // namespace loom
