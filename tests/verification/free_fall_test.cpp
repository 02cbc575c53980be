// Euler backward (seed 000 eq 12) on a free body under a constant body force: the discrete solution is
// known in closed form and the engine must follow it to round-off, with the lumped and with the
// consistent mass.
//
// Derivation. Seed 000 eq 12: a_{n+1} = (u_{n+1} - u_n) / dt^2 - v_n / dt, v_{n+1} = (u_{n+1} - u_n) / dt.
// Try a rigid translation u(X) = u_n for every node. Then F = I, P = 0 and f_int = 0, and the momentum
// balance M a_{n+1} = f_ext with f_ext^A = int rho_0 N^A g dV_0 reads, for the consistent mass
// M_AB = int rho_0 N^A N^B dV_0: sum_B M_AB a = (int rho_0 N^A dV_0) g = m_A g, and for the lumped mass
// m_A a = m_A g: in both cases a_{n+1} = g at every node, so the rigid translation is the (unique: the
// tangent M / dt^2 + K is positive definite) discrete solution. Then v_{n+1} = v_n + g dt, v_0 = 0 gives
// v_n = n g dt, and u_{n+1} = u_n + dt v_{n+1} = u_n + (n + 1) g dt^2 gives
//   u_n = g dt^2 (1 + 2 + ... + n) = g dt^2 n (n + 1) / 2,   v_n = n g dt.
// (The continuous answer is g t^2 / 2 = g dt^2 n^2 / 2: the extra g dt^2 n / 2 is Euler backward's
// first-order error, so an engine integrating the wrong scheme, e.g. trapezoidal, fails by O(dt).)
//
// Tolerance 1e-10 relative to |u_N| (observed ~1e-15): one Newton iteration solves the step exactly up to
// round-off, and probes.csv holds 15 significant digits.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "tests/support/test_support.hpp"

namespace loom {
namespace {

constexpr double kGx = 3.0, kGy = -9.81, kDt = 0.05;
constexpr int kSteps = 20;

std::string scene_text(const std::string& mass, const std::string& element = "p1") {
  const std::string pattern = element == "quad9" ? "" : "pattern = \"alternating\", ";
  return "[scene]\nname = \"free-fall\"\n"
         "[time]\nintegrator = \"euler_backward\"\ndt = 0.05\nsteps = 20\nmass = \"" + mass + "\"\n"
         "[solver]\nresidual_relative = 1e-12\n"
         "[[material]]\nname = \"m\"\nmodel = \"neo_hooke\"\nE = 100.0\nnu = 0.3\ndensity = 2.0\n"
         "[[body]]\nname = \"block\"\nmaterial = \"m\"\nelement = \"" + element + "\"\n"
         "mesh = { generator = \"rectangle\", origin = [1.0, 2.0], size = [1.0, 0.5], divisions = [6, 3], " + pattern + "distortion = 0.25 }\n"
         "[body_force]\nx = 3.0\ny = -9.81\n"
         "[[probe]]\nname = \"ux\"\nkind = \"point\"\nat = [1.0, 2.0]\ncomponent = \"x\"\n"
         "[[probe]]\nname = \"uy\"\nkind = \"point\"\nat = [2.0, 2.5]\ncomponent = \"y\"\n"
         "[output]\nevery = 0\n";
}

void check_free_fall(const std::string& mass, const std::string& element = "p1") {
  SCOPED_TRACE(mass + " mass, " + element);
  const SceneSpec scene = testing::scene_from_text(scene_text(mass, element));
  testing::TempDir dir("free_fall_" + mass);
  auto run = testing::make_fem_run(scene, dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  ASSERT_EQ(probes.rows.size(), std::size_t(kSteps) + 1);
  const auto ux = probes.column("ux"), uy = probes.column("uy");
  const double scale = std::hypot(kGx, kGy) * kDt * kDt * kSteps * (kSteps + 1) / 2.0;  // |u_N|
  double worst = 0.0;
  for (int n = 0; n <= kSteps; ++n) {
    const double s = kDt * kDt * n * (n + 1) / 2.0;
    const double e = std::max(std::abs(ux[std::size_t(n)] - kGx * s), std::abs(uy[std::size_t(n)] - kGy * s)) / scale;
    worst = std::max(worst, e);
    EXPECT_LE(e, 1e-10) << "step " << n << ": u = (" << ux[std::size_t(n)] << ", " << uy[std::size_t(n)] << "), exact ("
                        << kGx * s << ", " << kGy * s << ")";
  }
  // Every node, displacement and velocity, at the end.
  const Vec2 g(kGx, kGy);
  const Vec2 u_exact = g * kDt * kDt * kSteps * (kSteps + 1) / 2.0, v_exact = g * kDt * kSteps;
  double worst_u = 0.0, worst_v = 0.0;
  for (Index i = 0; i < run->nodes().size(); ++i) {
    worst_u = std::max(worst_u, (run->nodes().u_n[i] - u_exact).norm() / u_exact.norm());
    worst_v = std::max(worst_v, (run->nodes().v_n[i] - v_exact).norm() / v_exact.norm());
  }
  EXPECT_LE(worst_u, 1e-10);
  EXPECT_LE(worst_v, 1e-10);
  std::printf("[free fall] %-5s %-10s mass: probes worst rel err %.1e; all nodes at step %d: u %.1e, v %.1e; Newton %lld\n",
              element.c_str(), mass.c_str(), worst, kSteps, worst_u, worst_v, summary.newton_iterations);
}

TEST(EulerBackwardFreeFall, FollowsTheDiscreteExactSolutionWithLumpedMass) { check_free_fall("lumped"); }

TEST(EulerBackwardFreeFall, FollowsTheDiscreteExactSolutionWithConsistentMass) { check_free_fall("consistent"); }

// quad9: the row sums of its consistent mass and its body force are the same Gauss sums of N^A (element_mass.hpp).
TEST(EulerBackwardFreeFall, Quad9FollowsTheDiscreteExactSolutionWithBothMasses) {
  check_free_fall("lumped", "quad9");
  check_free_fall("consistent", "quad9");
}

}  // namespace
}  // namespace loom

// alpha-Bossak (and Newmark, alpha = 0) from the equilibrium a_0 = g: a constant acceleration is integrated
// exactly, u = g t^2 / 2 and v = g t at every node and step (time_integrator.hpp), with the smoothed
// u-p element and Hencky as well as the neo_hooke p1 block (a rigid translation: no stress in either). Not tri6: its
// HRZ-lumped mass is not proportional to its consistent body-force vector (corner loads 0, corner masses not), so
// no start makes its free fall exact.
namespace loom {
namespace {

void check_bossak_free_fall(const std::string& integrator, double alpha, const std::string& body) {
  SCOPED_TRACE(integrator + " alpha " + std::to_string(alpha) + " " + body);
  std::string text = scene_text("lumped");
  auto replace = [&](const std::string& a, const std::string& b) {
    const auto at = text.find(a);
    ASSERT_NE(at, std::string::npos) << a;
    text.replace(at, a.size(), b);
  };
  replace("integrator = \"euler_backward\"", "integrator = \"" + integrator + "\"\ninitial_acceleration = \"equilibrium\"" +
                                                 (integrator == "bossak" ? "\nalpha = " + std::to_string(alpha) : std::string()));
  if (body == "es_up") {
    replace("model = \"neo_hooke\"", "model = \"hencky_perzyna\"\ntau0 = 1.0\nviscosity = 0.5");
    replace("element = \"p1\"\n", "element = \"es_up\"\nalpha_stab = 0.5\n");
  }
  const SceneSpec scene = testing::scene_from_text(text);
  testing::TempDir dir("free_fall_bossak");
  auto run = testing::make_fem_run(scene, dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  const auto ux = probes.column("ux"), uy = probes.column("uy");
  const double scale = std::hypot(kGx, kGy) * 0.5 * std::pow(kDt * kSteps, 2);
  double worst = 0.0;
  for (int n = 0; n <= kSteps; ++n) {
    const double s = 0.5 * std::pow(kDt * n, 2);
    worst = std::max(worst, std::max(std::abs(ux[std::size_t(n)] - kGx * s), std::abs(uy[std::size_t(n)] - kGy * s)) / scale);
  }
  const Vec2 g(kGx, kGy), v_exact = g * kDt * kSteps;
  double worst_v = 0.0;
  for (Index i = 0; i < run->nodes().size(); ++i) worst_v = std::max(worst_v, (run->nodes().v_n[i] - v_exact).norm() / v_exact.norm());
  EXPECT_LE(worst, 1e-10);
  EXPECT_LE(worst_v, 1e-10);
  std::printf("[free fall] %-7s alpha %5.2f %-6s: u worst rel err %.1e, v %.1e\n", integrator.c_str(), alpha, body.c_str(), worst, worst_v);
}

TEST(BossakFreeFall, IsExactFromTheEquilibriumAcceleration) {
  check_bossak_free_fall("newmark", 0.0, "p1");
  for (const double alpha : {0.0, -0.1, -0.3}) {
    check_bossak_free_fall("bossak", alpha, "p1");
    check_bossak_free_fall("bossak", alpha, "es_up");
  }
}

}  // namespace
}  // namespace loom
