// Planar Bingham Poiseuille flow (scenes/bingham_poiseuille.toml; Reinold & Meschke 2021 §4.3): the
// velocity profile u / dt of the one-step steady state against the closed form (REFERENCES: Bingham plane
// Poiseuille), for tau0 = 20, 50, 80 Pa, with element es_up and hencky_perzyna, and the plug width
// against tau0 / F_x.
// Expected accuracy: the readings of the scene (G = 1e9 Pa, dt = 1e-4 s) leave an elastic part of about
// tau / (G dt v) = 1e-4 and a finite-strain part below 4e-4; the P1 profile is exact at the nodes of a 1D
// two-point problem up to the kink at the plug edge. Observed: 0.012-0.015 % at the centre (the issue asks
// for 0.5 %). Plug: rows of the mesh whose shear rate is below 0.1 1/s (200 1/s at the wall, 5e-4 1/s of
// elastic shear inside the plug, 1 1/s in a whole row just outside it); the
// detected half-width must be within one element (1 mm) of y0.
// The same flow run by the material point method (scenes/bingham_poiseuille_mpm.toml: b^e carried by each particle,
// elements p1 on the grid): every particle's velocity u / dt against the closed form at its height within 0.5 % of
// v_plug, the particles of the plug within 0.1 %, and the walls' reactions carrying the body force.
// And on the displacement elements p1 and tri6 of method fem (b^e at their quadrature points): every node within
// 0.5 % of v_plug, the centre within 0.1 %.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <tuple>

#include "engine/scene/scene_loader.hpp"
#include "tests/support/test_support.hpp"
#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

constexpr double kFx = 2e4, kMu = 10.0, kH = 0.1, kDt = 1e-4, kRow = 1e-3;

double exact_velocity(double y, double tau0) { return verification::bingham_poiseuille_velocity(y, tau0, kFx, kMu, kH); }

class BinghamPoiseuille : public ::testing::TestWithParam<double> {};

TEST_P(BinghamPoiseuille, VelocityProfileAndPlugMatchTheClosedForm) {
  const double tau0 = GetParam();
  const SceneSpec scene = load_scene(verification::scene_path("bingham_poiseuille.toml"),
                                     {"material[0].tau0=" + std::to_string(tau0), "output.every=0"});
  auto run = testing::make_fem_run(scene);
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const Nodes<2>& nodes = run->nodes();
  const double v_plug = exact_velocity(0.0, tau0);
  double worst = 0.0, v_centre = 0.0;
  // Nodes of the column x = 0, by row: the shear rate of each row interval.
  std::vector<std::pair<double, double>> column;  // (y, v)
  for (Index i = 0; i < nodes.size(); ++i) {
    const double y = nodes.X[i].y(), v = nodes.u_n[i].x() / kDt;
    worst = std::max(worst, std::abs(v - exact_velocity(y, tau0)) / v_plug);
    EXPECT_NEAR(nodes.u_n[i].y(), 0.0, 1e-15);
    if (std::abs(y) < 1e-12) v_centre = v;
    if (std::abs(nodes.X[i].x()) < 1e-12) column.emplace_back(y, v);
  }
  std::sort(column.begin(), column.end());
  double plug_low = 1.0, plug_high = -1.0;
  for (std::size_t k = 0; k + 1 < column.size(); ++k) {
    const double rate = std::abs(column[k + 1].second - column[k].second) / (column[k + 1].first - column[k].first);
    if (rate < 0.1) plug_low = std::min(plug_low, column[k].first), plug_high = std::max(plug_high, column[k + 1].first);
  }
  const double half_width = 0.5 * (plug_high - plug_low), y0 = tau0 / kFx;
  std::printf("[poiseuille] tau0 %g: v_centre %.5f (exact %.5f, %.3f %%), worst node %.3f %% of v_plug, plug half-width %.1f mm "
              "(y0 = %.1f mm), %lld Newton iterations\n",
              tau0, v_centre, v_plug, 100 * std::abs(v_centre / v_plug - 1), 100 * worst, 1e3 * half_width, 1e3 * y0,
              summary.newton_iterations);
  EXPECT_LT(worst, 5e-3);
  EXPECT_NEAR(v_centre, v_plug, 1e-3 * v_plug);
  ASSERT_LT(plug_low, plug_high) << "no plug found";
  EXPECT_NEAR(half_width, y0, kRow + 1e-12);
  EXPECT_NEAR(plug_low + plug_high, 0.0, 1e-12);  // symmetric
}

INSTANTIATE_TEST_SUITE_P(YieldStresses, BinghamPoiseuille, ::testing::Values(20.0, 50.0, 80.0));

class BinghamPoiseuilleMpm : public ::testing::TestWithParam<double> {};

TEST_P(BinghamPoiseuilleMpm, ParticleVelocitiesMatchTheClosedForm) {
  const double tau0 = GetParam();
  const SceneSpec scene = load_scene(verification::scene_path("bingham_poiseuille_mpm.toml"),
                                     {"material[0].tau0=" + std::to_string(tau0), "output.every=0"});
  auto run = testing::make_mpm_run(scene);
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const Points<2>& particles = run->model().particles;
  const double v_plug = exact_velocity(0.0, tau0), y0 = tau0 / kFx;
  double worst = 0.0, worst_plug = 0.0;
  int in_plug = 0, yielded_rows = 0;
  for (Index p = 0; p < particles.X.size(); ++p) {
    const double y = particles.X[p].y(), v = particles.u[p].x() / kDt;
    EXPECT_NEAR(particles.u[p].y(), 0.0, 1e-15);
    worst = std::max(worst, std::abs(v - exact_velocity(y, tau0)) / v_plug);
    if (std::abs(y) < y0) worst_plug = std::max(worst_plug, std::abs(v / v_plug - 1)), ++in_plug;
    // The flowing particles carry a plastic b^e: det b^e = J^2 (isochoric flow), b^e != F F^T.
    EXPECT_NEAR(particles.be[p].determinant(), std::pow(particles.F[p].determinant(), 2), 1e-12);
    yielded_rows += (particles.be[p] - particles.F[p] * particles.F[p].transpose()).norm() > 1e-9;
  }
  const double wall_x = run->probe_values()[2], load = 1000.0 * 20.0 * 0.004 * 0.2;
  std::printf("[poiseuille mpm] tau0 %g: worst particle %.3f %% of v_plug, plug (%d particles) %.4f %%, %d of %lld particles yielded, "
              "wall force %.6f of %.6f, %lld Newton iterations\n",
              tau0, 100 * worst, in_plug, 100 * worst_plug, yielded_rows, (long long)particles.X.size(), -wall_x, 0.5 * load,
              summary.newton_iterations);
  EXPECT_LT(worst, 5e-3);
  ASSERT_GT(in_plug, 0);
  EXPECT_LT(worst_plug, 1e-3);
  EXPECT_GT(yielded_rows, particles.X.size() / 2);  // the flow outside the plug is plastic
  EXPECT_NEAR(-wall_x, 0.5 * load, 1e-8 * load);  // each wall carries half of rho F_x V (the flow is symmetric)
}

INSTANTIATE_TEST_SUITE_P(YieldStresses, BinghamPoiseuilleMpm, ::testing::Values(20.0, 50.0, 80.0));

// The es_up scene with another element: its alpha_stab line dropped.
std::string scene_with_element(const std::string& element) {
  std::ifstream in(verification::scene_path("bingham_poiseuille.toml"));
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const std::string stab = "alpha_stab = 200.0\n", es = "element = \"es_up\"";
  EXPECT_NE(text.find(stab), std::string::npos);
  EXPECT_NE(text.find(es), std::string::npos);
  text.erase(text.find(stab), stab.size());
  text.replace(text.find(es), es.size(), "element = \"" + element + "\"");
  return text;
}

class BinghamPoiseuilleFem : public ::testing::TestWithParam<std::tuple<std::string, double>> {};

TEST_P(BinghamPoiseuilleFem, NodalVelocitiesMatchTheClosedForm) {
  const auto& [element, tau0] = GetParam();
  const SceneSpec scene = testing::scene_from_text(scene_with_element(element), {"material[0].tau0=" + std::to_string(tau0), "output.every=0"});
  auto run = testing::make_fem_run(scene);
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const Nodes<2>& nodes = run->nodes();
  const double v_plug = exact_velocity(0.0, tau0);
  double worst = 0.0, v_centre = 0.0;
  for (Index i = 0; i < nodes.size(); ++i) {
    const double y = nodes.X[i].y(), v = nodes.u_n[i].x() / kDt;
    worst = std::max(worst, std::abs(v - exact_velocity(y, tau0)) / v_plug);
    if (std::abs(y) < 1e-12) v_centre = v;
  }
  std::printf("[poiseuille %s] tau0 %g: v_centre %.5f (exact %.5f, %.3f %%), worst node %.3f %% of v_plug, %lld Newton iterations\n",
              element.c_str(), tau0, v_centre, v_plug, 100 * std::abs(v_centre / v_plug - 1), 100 * worst, summary.newton_iterations);
  EXPECT_LT(worst, 5e-3);
  EXPECT_NEAR(v_centre, v_plug, 1e-3 * v_plug);
}

INSTANTIATE_TEST_SUITE_P(Elements, BinghamPoiseuilleFem,
                         ::testing::Combine(::testing::Values("p1", "tri6"), ::testing::Values(20.0, 50.0, 80.0)));

}  // namespace
}  // namespace loom
