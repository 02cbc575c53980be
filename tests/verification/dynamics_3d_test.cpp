// Dynamics of the 3D fem (Newmark's average-acceleration rule, beta = 1/4, gamma = 1/2, lumped mass):
//  - Free fall: a free tetrahedral box under gravity g_z, a_0 from equilibrium (time.initial_acceleration): the
//    rule integrates a constant acceleration exactly. tet4: u_z = -g t^2 / 2 at every node. tet10: the body force
//    is integrated consistently (int rho N^A g dV: negative at the corners, -V/20 each) but the mass is HRZ-lumped
//    (positive everywhere), so the nodes do not share one acceleration and the box vibrates as it falls; the sum of
//    the nodal equations still gives sum m_A a_A = M g (internal forces sum to zero), and the centre of mass
//    sum m_A u_A / M falls exactly.
//  - Free linear vibration of a cube set moving by an initial velocity field in x, y, z: for M a + K u = 0 the rule
//    conserves E = 1/2 v^T M v + 1/2 u^T K u exactly, and the energy probe's kinetic + elastic parts are that E
//    (psi is quadratic in the gradient, integrated exactly by tet4's one point and tet10's four): the total
//    stays at its first value to the Newton tolerance while energy moves into the body.
//  - Angular momentum of a free Neo-Hooke box set spinning about z (v_0 = omega (-y, x, 0)): the probes' L starts at
//    sum m X x v_0 exactly, and drifts like dt^2 (Newmark evaluates the internal force at t_n+1, not at the
//    midpoint, so L is not conserved exactly; the same holds in 2D, tests/verification/angular_momentum_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "tests/support/test_support.hpp"

namespace loom {
namespace {

std::string box(const std::string& element, const std::string& model, const std::string& size, const std::string& divisions) {
  return "[[material]]\nname = \"m\"\nmodel = \"" + model + "\"\nE = 100.0\nnu = 0.3\ndensity = 2.0\n"
         "[[body]]\nname = \"box\"\nmaterial = \"m\"\nelement = \"" + element + "\"\n"
         "mesh = { generator = \"box\", origin = [-0.5, -0.25, -0.25], size = " + size + ", divisions = " + divisions + ", distortion = 0.2 }\n";
}

std::string header(const std::string& dt, int steps) {
  return "[scene]\nname = \"dyn3d\"\nmethod = \"fem\"\ndimension = 3\n"
         "[time]\nintegrator = \"newmark\"\ndt = " + dt + "\nsteps = " + std::to_string(steps) + "\n"
         "[solver]\nresidual_relative = 1e-13\nresidual_absolute = 1e-14\n"
         "[output]\nevery = 0\n";
}

std::string falling_box(const std::string& element, int steps) {
  std::string text = header("0.05", steps) + box(element, "neo_hooke", "[1.0, 0.5, 0.5]", "[4, 2, 2]") +
                     "[body_force]\nz = -9.81\n"
                     "[[probe]]\nname = \"uz\"\nkind = \"point\"\nat = [0.5, 0.25, 0.25]\ncomponent = \"z\"\n"
                     "[[probe]]\nname = \"ux\"\nkind = \"point\"\nat = [0.5, 0.25, 0.25]\ncomponent = \"x\"\n";
  text.replace(text.find("steps = " + std::to_string(steps)), 8 + std::to_string(steps).size(),
               "steps = " + std::to_string(steps) + "\ninitial_acceleration = \"equilibrium\"");
  return text;
}

TEST(Dynamics3d, FreeFallOfTet4IsExactAtEveryNode) {
  const SceneSpec scene = testing::scene_from_text(falling_box("p1", 20));
  RunSummary summary;
  const auto p = testing::run_for_probes(scene, "free_fall_3d", &summary);
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto t = p.column("time"), uz = p.column("uz"), ux = p.column("ux");
  double worst = 0.0;
  for (std::size_t s = 0; s < t.size(); ++s) {
    const double exact = -0.5 * 9.81 * t[s] * t[s];
    worst = std::max(worst, std::abs(uz[s] - exact));
    EXPECT_NEAR(uz[s], exact, 1e-10) << "step " << s;
    EXPECT_NEAR(ux[s], 0.0, 1e-12) << "step " << s;
  }
  std::printf("[dynamics 3d] free fall, tet4, 20 steps: worst |u_z - g t^2 / 2| = %.1e (u_z(1 s) = %.12f)\n", worst, uz.back());
}

TEST(Dynamics3d, FreeFallOfTet10MovesTheCentreOfMassExactly) {
  for (const int steps : {1, 7, 20}) {
    const SceneSpec scene = testing::scene_from_text(falling_box("tet10", steps));
    auto run = testing::make_fem_run<3>(scene);
    ASSERT_TRUE(run->run().converged);
    const Nodes<3>& n = run->nodes();
    double mass = 0.0;
    Vec3 moment = Vec3::Zero();
    for (Index i = 0; i < n.size(); ++i) mass += n.lumped_mass[i], moment += n.lumped_mass[i] * n.u_n[i];
    const double t = 0.05 * steps, exact = -0.5 * 9.81 * t * t;
    std::printf("[dynamics 3d] free fall, tet10, %2d steps: centre of mass u = (%.1e, %.1e, %.12f), exact u_z %.12f\n", steps,
                moment.x() / mass, moment.y() / mass, moment.z() / mass, exact);
    EXPECT_NEAR(moment.z() / mass, exact, 1e-10) << steps;
    EXPECT_NEAR(moment.x() / mass, 0.0, 1e-12) << steps;
    EXPECT_NEAR(moment.y() / mass, 0.0, 1e-12) << steps;
  }
}

TEST(Dynamics3d, FreeLinearVibrationKeepsItsEnergy) {
  for (const std::string element : {"p1", "tet10"}) {
    const std::string text = header("0.02", 60) + box(element, "linear_elastic", "[1.0, 0.5, 0.5]", "[6, 3, 3]") +
                             "initial_velocity = { x = \"0.3 * y\", y = \"0.2 * sin(3.14159 * x)\", z = \"0.1 * x * z\" }\n"
                             "[[probe]]\nname = \"kinetic\"\nkind = \"energy\"\nenergy = \"kinetic\"\n"
                             "[[probe]]\nname = \"elastic\"\nkind = \"energy\"\nenergy = \"elastic\"\n"
                             "[[probe]]\nname = \"total\"\nkind = \"energy\"\nenergy = \"total\"\n";
    const SceneSpec scene = testing::scene_from_text(text);
    RunSummary summary;
    const auto p = testing::run_for_probes(scene, "energy_3d_" + element, &summary);
    ASSERT_TRUE(summary.converged) << summary.failure;
    auto run = testing::make_fem_run<3>(scene);
    const Nodes<3>& n = run->nodes();
    double k0 = 0.0;
    for (Index i = 0; i < n.size(); ++i) {
      const Vec3 X = n.X[i];
      k0 += 0.5 * n.lumped_mass[i] * Vec3(0.3 * X.y(), 0.2 * std::sin(3.14159 * X.x()), 0.1 * X.x() * X.z()).squaredNorm();
    }
    const auto kinetic = p.column("kinetic"), elastic = p.column("elastic"), total = p.column("total");
    EXPECT_NEAR(kinetic[0], k0, 1e-13 * k0) << element;
    EXPECT_EQ(elastic[0], 0.0) << element;
    double worst = 0.0, most_elastic = 0.0;
    for (std::size_t s = 0; s < total.size(); ++s) {
      worst = std::max(worst, std::abs(total[s] - total[0]) / total[0]);
      most_elastic = std::max(most_elastic, elastic[s] / total[0]);
    }
    EXPECT_GT(most_elastic, 0.1) << element;
    EXPECT_LE(worst, 1e-9) << element;
    std::printf("[dynamics 3d] free vibration, %-5s 60 steps: E_0 = %.6g, largest elastic share %.2f, worst |E - E_0| / E_0 %.1e\n",
                element.c_str(), total[0], most_elastic, worst);
  }
}

TEST(Dynamics3d, SpinningBoxAngularMomentum) {
  std::vector<double> drift;
  for (const double dt : {0.05, 0.025, 0.0125}) {
    std::string text = header(std::to_string(dt), int(std::lround(1.0 / dt))) +
                       box("p1", "neo_hooke", "[1.0, 0.5, 0.5]", "[8, 4, 2]") + "initial_velocity = { x = \"-1.0 * y\", y = \"1.0 * x\" }\n";
    for (const char* c : {"x", "y", "z"})
      text += std::string("[[probe]]\nname = \"L") + c + "\"\nkind = \"angular_momentum\"\ncomponent = \"" + c + "\"\n";
    const SceneSpec scene = testing::scene_from_text(text);
    RunSummary summary;
    const auto p = testing::run_for_probes(scene, "spin_3d", &summary);
    ASSERT_TRUE(summary.converged) << summary.failure;
    // L_0 = sum m X x (omega e_z x X): (-sum m x z, -sum m y z, sum m (x^2 + y^2)) for omega = 1 (the distorted Kuhn
    // box is not symmetric: its products of inertia do not vanish).
    auto run = testing::make_fem_run<3>(scene);
    Vec3 L0 = Vec3::Zero();
    for (Index i = 0; i < run->nodes().size(); ++i) {
      const Vec3& X = run->nodes().X[i];
      L0 += run->nodes().lumped_mass[i] * Vec3(-X.x() * X.z(), -X.y() * X.z(), X.x() * X.x() + X.y() * X.y());
    }
    const auto Lx = p.column("Lx"), Ly = p.column("Ly"), Lz = p.column("Lz");
    EXPECT_NEAR(Lx.front(), L0.x(), 1e-14 * L0.norm());
    EXPECT_NEAR(Ly.front(), L0.y(), 1e-14 * L0.norm());
    EXPECT_NEAR(Lz.front(), L0.z(), 1e-14 * L0.norm());
    double worst = 0.0;
    for (std::size_t s = 0; s < Lz.size(); ++s) worst = std::max(worst, (Vec3(Lx[s], Ly[s], Lz[s]) - L0).norm() / L0.norm());
    drift.push_back(worst);
  }
  const double rate = std::log2(drift[1] / drift[2]);
  std::printf("[dynamics 3d] spinning box: largest |L - L_0| / |L_0| over 1 s at dt = 0.05, 0.025, 0.0125: %.2e %.2e %.2e (rate %.2f)\n",
              drift[0], drift[1], drift[2], rate);
  EXPECT_GT(rate, 1.8);
  EXPECT_LT(drift[2], 1e-4);
}

}  // namespace
}  // namespace loom

// alpha-Bossak from the equilibrium a_0 = g on a BCC block of face-smoothed mixed tetrahedra (es_up, Hencky-Perzyna):
// a rigid translation has no stress, the lumped mass V/4 per corner matches the body force's share, so u_z = -g t^2 / 2
// at every step to round-off, as for the 2D smoothed element (tests/verification/free_fall_test.cpp).
namespace loom {
namespace {

TEST(Dynamics3d, BossakFreeFallOfFaceSmoothedBlockIsExact) {
  for (const double alpha : {0.0, -0.1, -0.3}) {
    std::string text = falling_box("es_up", 20);
    const auto replace = [&](const std::string& a, const std::string& b) {
      const auto at = text.find(a);
      ASSERT_NE(at, std::string::npos) << a;
      text.replace(at, a.size(), b);
    };
    replace("integrator = \"newmark\"", "integrator = \"bossak\"\nalpha = " + std::to_string(alpha));
    replace("model = \"neo_hooke\"", "model = \"hencky_perzyna\"\ntau0 = 1.0\nviscosity = 0.5");
    replace("element = \"es_up\"\n", "element = \"es_up\"\nalpha_stab = 0.5\n");
    replace("distortion = 0.2", "lattice = \"bcc\", distortion = 0.2");
    const SceneSpec scene = testing::scene_from_text(text);
    RunSummary summary;
    const auto p = testing::run_for_probes(scene, "free_fall_es_3d", &summary);
    ASSERT_TRUE(summary.converged) << summary.failure;
    const auto t = p.column("time"), uz = p.column("uz"), ux = p.column("ux");
    double worst = 0.0;
    for (std::size_t s = 0; s < t.size(); ++s) {
      const double exact = -0.5 * 9.81 * t[s] * t[s];
      worst = std::max(worst, std::abs(uz[s] - exact));
      EXPECT_NEAR(uz[s], exact, 1e-10) << "alpha " << alpha << " step " << s;
      EXPECT_NEAR(ux[s], 0.0, 1e-12) << "alpha " << alpha << " step " << s;
    }
    std::printf("[dynamics 3d] Bossak alpha %5.2f free fall, es_up BCC block: worst |u_z - g t^2 / 2| = %.1e\n", alpha, worst);
  }
}

}  // namespace
}  // namespace loom
