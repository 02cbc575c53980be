// Method mpm, displacement-only grid with Newmark (beta = 1/4, gamma = 1/2, seed 003 §3.3): a free block under
// a constant body force falls across many grid cells, and every particle follows the discrete solution in
// closed form to round-off.
//
// Derivation. A rigid translation has F = I and f_int = 0 on the grid, so Newton's solve gives every node
// a = g (lumped mass: m_I a_I = m_I g), and the particles take a_p = sum N_I g = g. Newmark then gives
//   v_(n+1) = v_n + dt/2 (a_n + g),  u_(n+1) = u_n + dt v_n + dt^2/4 (a_n + g).
// With the equilibrium initial acceleration a_0 = g this is exact: u_n = g (n dt)^2 / 2, v_n = g n dt
// (REFERENCES.md: "exact for Newmark with gamma = 1/2, beta = 1/4 under constant acceleration").
// With a_0 = 0 (seed 003 Algorithm 1 sets no acceleration): u_1 = g dt^2/4, v_1 = g dt/2, then a = g, so
//   v_n = g dt (n - 1/2),  u_n = g dt^2 (1/4 + n (n - 1) / 2)   (n >= 1).
// Tolerance 1e-10 relative to |u_N| (probes.csv holds 15 digits; one Newton iteration per step).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/support/test_support.hpp"

namespace loom {
namespace {

constexpr double kGx = 3.0, kGy = -9.81, kDt = 0.05;
constexpr int kSteps = 20;

std::string scene_text(const std::string& initial) {
  return "[scene]\nname = \"mpm-free-fall\"\nmethod = \"mpm\"\n"
         "[time]\nintegrator = \"newmark\"\ndt = 0.05\nsteps = 20\ninitial_acceleration = \"" + initial + "\"\n"
         "[solver]\nresidual_relative = 1e-12\n"
         "[[material]]\nname = \"m\"\nmodel = \"neo_hooke\"\nE = 100.0\nnu = 0.3\ndensity = 2.0\n"
         "[[body]]\nname = \"block\"\nmaterial = \"m\"\nparticles_per_cell = 6\n"
         "mesh = { generator = \"rectangle\", origin = [1.0, 2.0], size = [1.0, 0.5], divisions = [6, 3], pattern = \"alternating\" }\n"
         "[grid]\ngenerator = \"rectangle\"\norigin = [0.0, -3.0]\nsize = [6.0, 6.0]\ndivisions = [24, 24]\npattern = \"alternating\"\n"
         "[body_force]\nx = 3.0\ny = -9.81\n"
         "[[probe]]\nname = \"ux\"\nkind = \"point\"\nat = [1.0, 2.0]\ncomponent = \"x\"\n"
         "[[probe]]\nname = \"uy\"\nkind = \"point\"\nat = [2.0, 2.5]\ncomponent = \"y\"\n"
         "[output]\nevery = 0\n";
}

// Displacement and velocity factors of g after n steps.
double u_factor(const std::string& initial, int n) {
  if (initial == "equilibrium" || n == 0) return 0.5 * kDt * kDt * n * n;
  return kDt * kDt * (0.25 + 0.5 * n * (n - 1));
}
double v_factor(const std::string& initial, int n) { return initial == "equilibrium" ? kDt * n : kDt * (n - 0.5); }

void check_free_fall(const std::string& initial) {
  SCOPED_TRACE("initial acceleration " + initial);
  const SceneSpec scene = testing::scene_from_text(scene_text(initial));
  testing::TempDir dir("mpm_free_fall_" + initial);
  auto run = testing::make_mpm_run(scene, dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  ASSERT_EQ(probes.rows.size(), std::size_t(kSteps) + 1);
  const auto ux = probes.column("ux"), uy = probes.column("uy");
  const Vec2 g(kGx, kGy);
  const double scale = g.norm() * u_factor(initial, kSteps);
  double worst = 0.0;
  for (int n = 0; n <= kSteps; ++n) {
    const double s = u_factor(initial, n);
    worst = std::max(worst, std::max(std::abs(ux[std::size_t(n)] - kGx * s), std::abs(uy[std::size_t(n)] - kGy * s)) / scale);
  }
  EXPECT_LE(worst, 1e-10);
  // Every particle, displacement and velocity, at the end; the block crossed many grid cells.
  const Points<2>& particles = run->model().particles;
  const Vec2 u_exact = g * u_factor(initial, kSteps), v_exact = g * v_factor(initial, kSteps);
  double worst_u = 0.0, worst_v = 0.0;
  for (Index p = 0; p < particles.X.size(); ++p) {
    worst_u = std::max(worst_u, (particles.u[p] - u_exact).norm() / u_exact.norm());
    worst_v = std::max(worst_v, (particles.v[p] - v_exact).norm() / v_exact.norm());
    EXPECT_LE((particles.F[p] - Mat3::Identity()).norm(), 1e-12);
  }
  EXPECT_LE(worst_u, 1e-10);
  EXPECT_LE(worst_v, 1e-10);
  EXPECT_GT(u_exact.norm() / 0.25, 10.0);  // travelled more than ten grid cells
  std::printf("[mpm free fall] a_0 %-11s: probes worst rel err %.1e; all %d particles: u %.1e, v %.1e; Newton %lld\n", initial.c_str(),
              worst, int(particles.X.size()), worst_u, worst_v, summary.newton_iterations);
}

TEST(MpmFreeFall, FollowsNewmarksExactSolutionWithTheEquilibriumInitialAcceleration) { check_free_fall("equilibrium"); }

TEST(MpmFreeFall, FollowsTheClosedFormWithZeroInitialAcceleration) { check_free_fall("zero"); }

}  // namespace
}  // namespace loom
