// Hencky-Perzyna (systems/assemble/materials/hencky_perzyna.hpp, seed 001 §2): the return map against the
// recurrences that hold exactly at finite strain (relaxation at fixed deformation, the rate-independent cap,
// isochoric flow), the simple-shear recurrence of small-strain Bingham viscoplasticity (to O(tau/G), and that
// order checked), Hencky's closed form in a plane-strain stretch, objectivity, and every tangent against
// central finite differences of P = tau f^-T at random elastic and plastic states. The step at an MPM particle
// (history_point.hpp: F total, F_n and b^e_n fixed) against the same differences of its P(F), and its elastic
// limit against Hencky's P(F).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "systems/assemble/materials/first_piola.hpp"
#include "systems/assemble/materials/hencky_perzyna.hpp"
#include "systems/assemble/materials/history_point.hpp"
#include "systems/output/elastic_energy.hpp"
#include "tests/support/stress_derivative.hpp"

namespace loom {
namespace {

Mat3 unit(int k, int l) {
  Mat3 E = Mat3::Zero();
  E(k, l) = 1.0;
  return E;
}

Mat3 shear(double gamma) {
  Mat3 f = Mat3::Identity();
  f(0, 1) = gamma;
  return f;
}

HistoryResponse respond(const HenckyPerzyna& m, const Mat3& f, const Mat3& be_n, double dt, bool deviatoric) {
  HistoryResponse r;
  EXPECT_TRUE(m.update(f, be_n, dt, deviatoric, true, r));
  return r;
}

TEST(HenckyPerzyna, PlaneStrainStretchMatchesHenckyClosedForm) {
  const HenckyPerzyna m{7.0, 3.0};
  const double lx = 0.9, ly = 1.3;
  const Mat3 f = Vec3(lx, ly, 1.0).asDiagonal();
  const HistoryResponse r = respond(m, f, Mat3::Identity(), 1.0, false);
  const double ex = std::log(lx), ey = std::log(ly), th = ex + ey;
  EXPECT_NEAR(r.tau(0, 0), 2 * 3.0 * (ex - th / 3) + 7.0 * th, 1e-14);
  EXPECT_NEAR(r.tau(1, 1), 2 * 3.0 * (ey - th / 3) + 7.0 * th, 1e-14);
  EXPECT_NEAR(r.tau(2, 2), 2 * 3.0 * (0 - th / 3) + 7.0 * th, 1e-14);
  EXPECT_NEAR(r.tau(0, 1), 0.0, 1e-14);
  EXPECT_NEAR(r.J, lx * ly, 1e-15);
  EXPECT_FALSE(r.plastic);
}

// At a fixed deformation (f = I) the trial state is the converged one, and the closed form gives
// tau_eq,n+1 - tau0 = (tau_eq,n - tau0) / (1 + G dt / mu) exactly, at any strain.
TEST(HenckyPerzyna, RelaxationAtFixedDeformationIsExact) {
  const HenckyPerzyna m{3000.0, 1000.0, 5.0, 10.0};
  const double dt = 1e-3;
  Mat3 be = respond(HenckyPerzyna{3000.0, 1000.0}, shear(0.2), Mat3::Identity(), dt, true).be;  // elastic prestress
  HistoryResponse r = respond(HenckyPerzyna{3000.0, 1000.0}, Mat3::Identity(), be, dt, true);
  double tau_eq = r.tau_eq;
  ASSERT_GT(tau_eq, 50.0);
  for (int n = 0; n < 200; ++n) {
    r = respond(m, Mat3::Identity(), be, dt, true);
    const double expected = m.tau0 + (tau_eq - m.tau0) / (1.0 + m.G * dt / m.viscosity);
    EXPECT_NEAR(r.tau_eq, expected, 1e-12 * tau_eq) << "step " << n;
    const double check = std::sqrt(0.5 * (r.tau - r.tau.trace() / 3 * Mat3::Identity()).squaredNorm());
    EXPECT_NEAR(check, r.tau_eq, 1e-12 * tau_eq);
    EXPECT_NEAR(be.determinant(), r.be.determinant(), 1e-14);  // isochoric flow
    tau_eq = r.tau_eq, be = r.be;
  }
  EXPECT_NEAR(tau_eq, m.tau0, 1e-5);  // (1.1)^-200 of the initial overstress
}

// mu -> 0: the rate-independent radial return caps tau_eq at tau0 exactly, whatever the step.
TEST(HenckyPerzyna, InviscidLimitCapsAtYieldStress) {
  const HenckyPerzyna m{3000.0, 1000.0, 5.0, 0.0};
  Mat3 be = Mat3::Identity();
  for (int n = 0; n < 50; ++n) {
    const HistoryResponse r = respond(m, shear(0.01), be, 1e-3, true);
    if (n > 0) {
      EXPECT_TRUE(r.plastic);
      EXPECT_NEAR(r.tau_eq, 5.0, 1e-12);
    }
    be = r.be;
  }
}

// Steady simple shear at rate gdot. Small-strain backward-Euler Bingham recurrence (spec §5.3):
//   tau_tr = tau_n + G gdot dt; above yield tau_n+1 = (tau_tr + r tau0) / (1 + r), r = G dt / mu.
// The finite-strain map differs by O((tau / G)^2) relative (normal stresses of the objective update feed back
// into tau_xy), down to a floor of about 1e-6 relative set by the O(dgamma^2) terms of the step's finite
// kinematics (dgamma = 2e-3 here): 0.015, 2.7e-4 and 1.7e-5 at G = 1e3, 1e4, 1e6 (tau = 25).
double shear_recurrence_gap(double G) {
  const HenckyPerzyna m{3.0 * G, G, 5.0, 10.0};
  const double dt = 1e-3, gdot = 2.0;
  Mat3 be = Mat3::Identity();
  double tau_r = 0.0, gap = 0.0;
  for (int n = 0; n < 3000; ++n) {
    const HistoryResponse r = respond(m, shear(gdot * dt), be, dt, true);
    const double tr = tau_r + G * gdot * dt;
    const double ratio = tr > m.tau0 ? G * dt / m.viscosity : 0.0;
    tau_r = (tr + ratio * m.tau0) / (1.0 + ratio);
    gap = std::max(gap, std::abs(r.tau(0, 1) - tau_r));
    be = r.be;
  }
  EXPECT_NEAR(tau_r, 5.0 + 10.0 * 2.0, 1e-6);  // steady Bingham: tau0 + mu gdot
  return gap;
}

TEST(HenckyPerzyna, SimpleShearFollowsBinghamRecurrence) {
  const double gap3 = shear_recurrence_gap(1e3), gap4 = shear_recurrence_gap(1e4), gap6 = shear_recurrence_gap(1e6);
  EXPECT_LT(gap3, 25.0 * 0.025 * 0.025 * 2);
  EXPECT_GT(gap3 / gap4, 30.0);  // faster than first order in tau / G
  EXPECT_LT(gap6, 25.0 * 1e-6);
}

TEST(HenckyPerzyna, ObjectiveUnderRotation) {
  const HenckyPerzyna m{7.0, 3.0, 0.4, 0.5};
  Mat3 f = Mat3::Identity();
  f.topLeftCorner<2, 2>() << 1.2, 0.3, -0.1, 0.9;
  const double a = 0.7;
  Mat3 R = Mat3::Identity();
  R.topLeftCorner<2, 2>() << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  const HistoryResponse r1 = respond(m, f, Mat3::Identity(), 0.1, false), r2 = respond(m, R * f, Mat3::Identity(), 0.1, false);
  EXPECT_TRUE(r1.plastic);
  EXPECT_LT((r2.tau - R * r1.tau * R.transpose()).norm(), 1e-13);
  EXPECT_LT((r2.be - R * r1.be * R.transpose()).norm(), 1e-13);
}

// P = tau(f) f^-T against central differences, with b^e_n random and plane-strain f.
Mat9 fd_tangent(const HenckyPerzyna& m, const Mat3& f, const Mat3& be_n, bool deviatoric, double h = 1e-6) {
  Mat9 A;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      HistoryResponse rp, rm;
      EXPECT_TRUE(m.update(f + h * unit(k, l), be_n, 0.1, deviatoric, false, rp));
      EXPECT_TRUE(m.update(f - h * unit(k, l), be_n, 0.1, deviatoric, false, rm));
      const Mat3 dP = (rp.tau * (f + h * unit(k, l)).inverse().transpose() - rm.tau * (f - h * unit(k, l)).inverse().transpose()) / (2 * h);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) A(ij(i, j), ij(k, l)) = dP(i, j);
    }
  return A;
}

TEST(HenckyPerzyna, TangentMatchesFiniteDifferences) {
  std::mt19937 rng(1);
  std::normal_distribution<double> normal;
  std::vector<std::pair<Mat3, Mat3>> states;
  for (int s = 0; s < 6; ++s) {
    Mat3 f = Mat3::Identity(), X = Mat3::Zero();
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) f(i, j) += 0.3 * normal(rng), X(i, j) = 0.2 * normal(rng);
    Mat3 be = Mat3::Identity() + X * X.transpose();
    be(2, 2) = 1.1;
    if (f.determinant() > 0.2) states.emplace_back(f, be);
  }
  states.emplace_back(Vec3(1.1, 1.1, 1.0).asDiagonal(), Mat3::Identity());  // equal stretches
  states.emplace_back(Mat3::Identity(), Mat3::Identity());                  // all equal, stress free
  for (const double tau0 : {0.4, 1e300}) {
    const HenckyPerzyna m{7.0, 3.0, tau0, 0.5};
    int plastic = 0;
    for (const auto& [f, be] : states)
      for (const bool deviatoric : {true, false}) {
        const HistoryResponse r = respond(m, f, be, 0.1, deviatoric);
        plastic += r.plastic;
        Mat3 P;
        Mat9 A;
        first_piola(f, r.tau, r.c_tau, 1.0, P, A);
        EXPECT_LT((P - r.tau * f.inverse().transpose()).norm(), 1e-14);
        EXPECT_LT((A - fd_tangent(m, f, be, deviatoric)).cwiseAbs().maxCoeff(), 1e-7) << "tau0 " << tau0 << " deviatoric " << deviatoric << "\nf\n" << f;
      }
    if (tau0 < 1) {
      EXPECT_GT(plastic, 4);
    }
  }
}

TEST(HenckyPerzyna, HyperelasticInterfaceIsElasticHencky) {
  const HenckyPerzyna m{7.0, 3.0};
  Mat3 F = Mat3::Identity();
  F.topLeftCorner<2, 2>() << 1.2, 0.3, -0.1, 0.9;
  Mat3 P, P2;
  Mat9 A;
  ASSERT_TRUE(m.stress(F, P));
  ASSERT_TRUE(m.stress_tangent(F, P2, A));
  EXPECT_LT((P - P2).norm(), 1e-14);
  EXPECT_LT((A - fd_tangent(m, F, Mat3::Identity(), false)).cwiseAbs().maxCoeff(), 1e-7);
}

TEST(FirstPiola, PressurePartMatchesFiniteDifferences) {
  Mat3 F = Mat3::Identity();
  F.topLeftCorner<2, 2>() << 1.2, 0.3, -0.1, 0.9;
  const double p = 0.7, h = 1e-6;
  auto P_of = [&](const Mat3& G) { return Mat3(p * G.determinant() * G.inverse().transpose()); };
  Mat3 tau, P;
  Mat9 c, A, fd;
  pressure_kirchhoff(F.determinant(), p, tau, c);
  first_piola(F, tau, c, 1.0, P, A);
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      const Mat3 dP = (P_of(F + h * unit(k, l)) - P_of(F - h * unit(k, l))) / (2 * h);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) fd(ij(i, j), ij(k, l)) = dP(i, j);
    }
  EXPECT_LT((P - P_of(F)).norm(), 1e-14);
  EXPECT_LT((A - fd).cwiseAbs().maxCoeff(), 1e-8);
}

// The step at a particle, P(F) = tau(F F_n^-1; b^e_n) F^-T: its tangent dP/dF against central differences of P, at
// elastic and plastic states with F_n and b^e_n away from the identity.
TEST(HenckyPerzynaStep, TangentOfTotalGradientMatchesFiniteDifferences) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  const HenckyPerzyna m{7.0, 3.0, 0.4, 0.5};
  int plastic = 0, checked = 0;
  for (int s = 0; s < 8; ++s) {
    Mat3 F_n = Mat3::Identity(), f = Mat3::Identity(), X = Mat3::Zero();
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) F_n(i, j) += 0.2 * normal(rng), f(i, j) += 0.2 * normal(rng), X(i, j) = 0.2 * normal(rng);
    if (F_n.determinant() < 0.3 || f.determinant() < 0.3) continue;
    const Mat3 be_n = Mat3::Identity() + X * X.transpose();
    const Mat3 F = f * F_n;
    const HenckyPerzynaStep step{m, F_n.inverse(), be_n, 0.1};
    Mat3 P, P_only;
    Mat9 A;
    ASSERT_TRUE(step.stress_tangent(F, P, A));
    const Mat3 be = step.be;
    ASSERT_TRUE(step.stress(F, P_only));
    EXPECT_LT((P - P_only).norm(), 1e-14 * P.norm());
    EXPECT_LT((be - step.be).norm(), 1e-15);
    HistoryResponse r;
    ASSERT_TRUE(m.update(f, be_n, 0.1, false, false, r));
    plastic += r.plastic;
    EXPECT_LT((A - testing::stress_derivative(step, F)).cwiseAbs().maxCoeff(), 1e-7) << "state " << s;
    ++checked;
  }
  EXPECT_GE(checked, 5);
  EXPECT_GE(plastic, 3);
}

// Without yield (tau0 infinite) the history is elastic: b^e = F F^T whatever the steps, so the step from F_n with
// b^e_n = F_n F_n^T gives Hencky's P(F) of the hyperelastic interface, and its b^e is F F^T, to round-off.
TEST(HenckyPerzynaStep, ElasticHistoryIsHenckyOfTotalGradient) {
  const HenckyPerzyna m{7.0, 3.0};
  Mat3 F_n = Mat3::Identity(), F = Mat3::Identity();
  F_n.topLeftCorner<2, 2>() << 1.1, 0.2, -0.05, 0.95;
  F.topLeftCorner<2, 2>() << 1.2, 0.3, -0.1, 0.9;
  const HenckyPerzynaStep step{m, F_n.inverse(), F_n * F_n.transpose(), 0.1};
  Mat3 P, P_hencky;
  ASSERT_TRUE(step.stress(F, P));
  ASSERT_TRUE(m.stress(F, P_hencky));
  EXPECT_LT((P - P_hencky).norm(), 1e-14 * P.norm());
  EXPECT_LT((step.be - F * F.transpose()).norm(), 1e-14);
  EXPECT_LT((m.kirchhoff(step.be) - P * F.transpose()).norm(), 1e-14 * P.norm());  // the stress written for output
  // Energy probes of elastic Hencky (no b^e carried): the energy of F F^T, that of the history when it is carried.
  const BodyMaterial body{m, 1.0};
  EXPECT_GT(elastic_energy(body, F), 0.0);
  EXPECT_NEAR(elastic_energy(body, F), m.energy(step.be), 1e-14);
}

// visit_point_material: a point without history sees the model itself; with history, the step, whose b^e it keeps.
TEST(HenckyPerzynaStep, PointMaterialVisitsTheStepOnlyWithHistory) {
  const Material material = HenckyPerzyna{7.0, 3.0, 0.4, 0.5};
  Mat3 F_n = Mat3::Identity(), F = Mat3::Identity(), be_n = Mat3::Identity(), be = Mat3::Zero();
  F(0, 1) = 0.5;
  Mat3 P_plain, P_step;
  EXPECT_TRUE(visit_point_material(material, PointHistory{}, [&](const auto& m) { return m.stress(F, P_plain); }));
  EXPECT_TRUE(visit_point_material(material, PointHistory{&F_n, &be_n, 0.1, &be}, [&](const auto& m) { return m.stress(F, P_step); }));
  EXPECT_GT(be.norm(), 1.0);  // written (it was zero)
  EXPECT_GT((P_plain - P_step).norm(), 1e-3);  // the plain model is elastic Hencky, the step yields
  HistoryResponse r;
  ASSERT_TRUE(std::get<HenckyPerzyna>(material).update(F, be_n, 0.1, false, false, r));
  EXPECT_TRUE(r.plastic);
  EXPECT_LT((be - r.be).norm(), 1e-15);
}

}  // namespace
}  // namespace loom
