// Drucker-Prager (systems/assemble/materials/drucker_prager.hpp, hosted by hencky_perzyna.hpp's Hencky elasticity):
// the cones against Mohr-Coulomb's sections, the return map's consistency and flow rule, the apex of a cohesionless
// material in tension, the algorithmic modulus and the full finite-strain tangent dP/dF (also of the step at a
// particle) against central differences, and the strain-driven element test against its closed form: along a radial
// path of logarithmic strain the rate equations are linear with constant coefficients once on the cone, so the
// stress is piecewise linear in time and backward Euler reproduces it exactly, at any step size.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "systems/assemble/materials/first_piola.hpp"
#include "systems/assemble/materials/hencky_perzyna.hpp"
#include "systems/assemble/materials/history_point.hpp"
#include "tests/support/drucker_prager_path.hpp"
#include "tests/support/stress_derivative.hpp"

namespace loom {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

HenckyPerzyna sand(double friction_deg, double dilatancy_deg, double cohesion, DruckerPragerCone cone = DruckerPragerCone::plane_strain) {
  HenckyPerzyna m{5.0e6, 3.0e6};
  m.friction = DruckerPrager::from_mohr_coulomb(friction_deg * kDegree, dilatancy_deg * kDegree, cohesion, cone);
  return m;
}

double q_of(const Vec3& t) { return std::sqrt(0.5 * (t - Vec3::Constant(t.mean())).squaredNorm()); }

// Mohr-Coulomb with tension positive: (s_max - s_min) + (s_max + s_min) sin phi - 2 c cos phi.
double mohr_coulomb(double s_max, double s_min, double phi, double c) {
  return (s_max - s_min) + (s_max + s_min) * std::sin(phi) - 2.0 * c * std::cos(phi);
}

TEST(DruckerPrager, OuterAndInnerConesPassThroughMohrCoulombsMeridians) {
  const double phi = 32.0 * kDegree, c = 7.0;
  for (const double confining : {-50.0, -300.0}) {
    // Triaxial compression: the axial stress s3 the most compressive, s1 = s2 the confining one, on Mohr-Coulomb.
    const double axial = (confining * (1 + std::sin(phi)) - 2 * c * std::cos(phi)) / (1 - std::sin(phi));
    ASSERT_NEAR(mohr_coulomb(confining, axial, phi, c), 0.0, 1e-12 * std::abs(axial));
    const Vec3 tc(confining, confining, axial);
    const DruckerPrager outer = DruckerPrager::from_mohr_coulomb(phi, 0.0, c, DruckerPragerCone::compression);
    EXPECT_NEAR(outer.yield(q_of(tc), tc.mean()), 0.0, 1e-12 * std::abs(axial));
    // Triaxial extension: s1 the least compressive, s2 = s3 the confining one.
    const double lateral = (confining * (1 - std::sin(phi)) + 2 * c * std::cos(phi)) / (1 + std::sin(phi));
    ASSERT_NEAR(mohr_coulomb(lateral, confining, phi, c), 0.0, 1e-12 * std::abs(confining));
    const Vec3 te(lateral, confining, confining);
    const DruckerPrager inner = DruckerPrager::from_mohr_coulomb(phi, 0.0, c, DruckerPragerCone::extension);
    EXPECT_NEAR(inner.yield(q_of(te), te.mean()), 0.0, 1e-12 * std::abs(confining));
  }
}

// The plane-strain cone: a state on it whose flow has no out-of-plane component (s3 = -2 q eta_bar / 3) is on
// Mohr-Coulomb in the plane, and its in-plane flow dilates at the angle psi, for associated and non-associated flow;
// with psi = phi the cone is de Souza Neto's 3 tan phi / sqrt(9 + 12 tan^2 phi).
TEST(DruckerPrager, PlaneStrainConeMatchesMohrCoulombWhereTheFlowIsPlane) {
  const double phi = 32.0 * kDegree, c = 7.0;
  for (const double psi : {0.0, 10.0 * kDegree, phi}) {
    const DruckerPrager dp = DruckerPrager::from_mohr_coulomb(phi, psi, c, DruckerPragerCone::plane_strain);
    for (const double p : {-20.0, -400.0}) {
      const double q = dp.xi_c - dp.eta * p, s3 = -2.0 * q * dp.eta_bar / 3.0, d = std::sqrt(4 * q * q - 3 * s3 * s3);
      const double s1 = p + (-s3 + d) / 2, s2 = p + (-s3 - d) / 2;
      EXPECT_NEAR(mohr_coulomb(s1, s2, phi, c), 0.0, 1e-12 * std::abs(p)) << "psi " << psi;
      // The flow s_A / (2q) + eta_bar / 3: none out of the plane, in-plane dilatancy sin psi.
      const Vec3 s(s1 - p, s2 - p, s3), flow = s / (2 * q) + Vec3::Constant(dp.eta_bar / 3);
      EXPECT_NEAR(flow[2], 0.0, 1e-14);
      EXPECT_NEAR((flow[0] + flow[1]) / (flow[0] - flow[1]), std::sin(psi), 1e-14);
    }
  }
  const double t = std::tan(phi);
  const DruckerPrager associated = DruckerPrager::from_mohr_coulomb(phi, phi, c, DruckerPragerCone::plane_strain);
  EXPECT_NEAR(associated.eta, 3 * t / std::sqrt(9 + 12 * t * t), 1e-15);
  EXPECT_NEAR(associated.xi_c, 3 * c / std::sqrt(9 + 12 * t * t), 1e-14);
}

// Trial strains on the cone's side, its apex's side and inside, for associated and non-associated flow.
std::vector<Vec3> trial_strains() {
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  std::vector<Vec3> e;
  for (int k = 0; k < 12; ++k) e.push_back(Vec3(normal(rng), normal(rng), normal(rng)) * 2e-5 - Vec3::Constant(1e-5 * (k % 3)));
  e.push_back(Vec3(3e-5, 2e-5, 1e-5));  // tension: the apex
  return e;
}

TEST(DruckerPrager, ReturnLandsOnTheConeAlongTheFlowRule) {
  int cone = 0, apex = 0;
  for (const double psi : {0.0, 10.0, 30.0}) {
    const HenckyPerzyna m = sand(30.0, psi, 20.0);
    const DruckerPrager& dp = *m.friction;
    for (const Vec3& trial : trial_strains()) {
      Vec3 eps = trial, t;
      Mat3 a;
      double q;
      if (!dp.return_map(m.K, m.G, eps, t, a, q)) {
        EXPECT_LE(dp.yield(q_of(t), t.mean()), 0.0);
        continue;
      }
      EXPECT_NEAR(q, q_of(t), 1e-9);
      EXPECT_NEAR(dp.yield(q, t.mean()), 0.0, 1e-9);  // stresses ~1e2: round-off
      // The elastic strains carry the stress by Hencky's law.
      const Vec3 dev_e = eps - Vec3::Constant(eps.sum() / 3);
      EXPECT_LT((t - (2 * m.G * dev_e + Vec3::Constant(m.K * eps.sum()))).norm(), 1e-9);
      if (q > 0.0) {
        ++cone;  // plastic strain = dgamma (s / (2q) + eta_bar / 3), one dgamma for all three components
        const Vec3 s = t - Vec3::Constant(t.mean()), flow = s / (2 * q) + Vec3::Constant(dp.eta_bar / 3);
        const Vec3 plastic = trial - eps;
        const double dgamma = plastic.dot(flow) / flow.squaredNorm();
        EXPECT_GT(dgamma, 0.0);
        EXPECT_LT((plastic - dgamma * flow).norm(), 1e-12 + 1e-9 * plastic.norm());
      } else {
        ++apex;
        EXPECT_NEAR(t.mean(), dp.xi_c / dp.eta, 1e-9);
      }
    }
  }
  EXPECT_GT(cone, 10);
  EXPECT_GT(apex, 2);
}

TEST(DruckerPrager, CohesionlessMaterialInTensionCarriesNothing) {
  const HenckyPerzyna m = sand(30.0, 0.0, 0.0);
  HistoryResponse r;
  ASSERT_TRUE(m.update(Vec3(1.01, 1.02, 1.0).asDiagonal(), Mat3::Identity(), 1.0, false, true, r));
  EXPECT_TRUE(r.plastic);
  EXPECT_EQ(r.tau.norm(), 0.0);
  EXPECT_LT((r.be - Mat3::Identity()).norm(), 1e-15);
  EXPECT_EQ(r.c_tau.norm(), 0.0);
}

TEST(DruckerPrager, ModulusMatchesCentralDifferences) {
  for (const double psi : {0.0, 30.0}) {
    const HenckyPerzyna m = sand(30.0, psi, 20.0);
    for (const Vec3& trial : trial_strains()) {
      Vec3 eps = trial, t;
      Mat3 a, fd;
      double q;
      m.friction->return_map(m.K, m.G, eps, t, a, q);
      const double h = 1e-10;
      for (int b = 0; b < 3; ++b) {
        Vec3 ep = trial, em = trial, tp, tm;
        Mat3 unused;
        ep[b] += h, em[b] -= h;
        m.friction->return_map(m.K, m.G, ep, tp, unused, q);
        m.friction->return_map(m.K, m.G, em, tm, unused, q);
        fd.col(b) = (tp - tm) / (2 * h);
      }
      EXPECT_LT((a - fd).cwiseAbs().maxCoeff(), 1e-5 * m.K) << "psi " << psi << " trial " << trial.transpose() << "\n" << a << "\n" << fd;
    }
  }
}

// The finite-strain step at a particle, P(F) = tau(F F_n^-1; b^e_n) F^-T, against central differences, with F_n and
// b^e_n away from the identity and the incremental strain of the order of the elastic range.
TEST(DruckerPrager, StepTangentMatchesFiniteDifferences) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  int plastic = 0, checked = 0;
  for (const double psi : {0.0, 20.0}) {
    HenckyPerzyna m{5.0, 3.0};
    m.friction = DruckerPrager::from_mohr_coulomb(30.0 * kDegree, psi * kDegree, 0.05, DruckerPragerCone::plane_strain);
    for (int s = 0; s < 10; ++s) {
      Mat3 F_n = Mat3::Identity(), f = Mat3::Identity(), X = Mat3::Zero();
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) F_n(i, j) += 0.2 * normal(rng), f(i, j) += 0.05 * normal(rng), X(i, j) = 0.03 * normal(rng);
      f -= 0.03 * Mat3::Identity() * (s % 2);  // compressed: the cone rather than the apex
      f(2, 2) = 1.0;
      if (F_n.determinant() < 0.3) continue;
      const Mat3 be_n = Mat3::Identity() + X * X.transpose();
      const Mat3 F = f * F_n;
      const HenckyPerzynaStep step{m, F_n.inverse(), be_n, 0.1};
      Mat3 P;
      Mat9 A;
      ASSERT_TRUE(step.stress_tangent(F, P, A));
      HistoryResponse r;
      ASSERT_TRUE(m.update(f, be_n, 0.1, false, false, r));
      if (r.plastic && r.tau_eq == 0.0) continue;  // the apex: a kink of P(F) within h of nothing, but a = 0 there
      plastic += r.plastic;
      EXPECT_LT((A - testing::stress_derivative(step, F, 1e-7)).cwiseAbs().maxCoeff(), 1e-6) << "psi " << psi << " state " << s;
      ++checked;
    }
  }
  EXPECT_GE(checked, 12);
  EXPECT_GE(plastic, 6);
}

// The element test: plane strain, F(t) = diag(exp(e1 t), exp(e2 t), 1), compressed and sheared, against its closed
// form (tests/support/drucker_prager_path.hpp); steps of any size, crossing the yield time anywhere, land on it.
TEST(DruckerPrager, StrainDrivenElementTestFollowsItsClosedForm) {
  for (const double psi : {0.0, 12.0, 30.0}) {
    const HenckyPerzyna m = sand(30.0, psi, 2.0e3);
    const testing::RadialStrainPath path{m, Vec3(-0.01, 0.004, 0.0)};  // log strain per unit time
    const double t_y = path.yield_time();
    for (const int steps : {7, 40}) {
      const double dt = 3.0 * t_y / steps;
      const Mat3 f = (path.rate * dt).array().exp().matrix().asDiagonal();
      Mat3 be = Mat3::Identity();
      int plastic = 0;
      for (int n = 1; n <= steps; ++n) {
        HistoryResponse r;
        ASSERT_TRUE(m.update(f, be, dt, false, false, r));
        be = r.be, plastic += r.plastic;
        const Vec3 expected = path.stress(n * dt);
        EXPECT_LT((r.tau.diagonal() - expected).norm(), 1e-10 * expected.norm()) << "psi " << psi << " steps " << steps << " n " << n;
        EXPECT_LT(r.tau.norm() - r.tau.diagonal().norm(), 1e-10 * expected.norm());
      }
      EXPECT_GE(plastic, 2 * steps / 3 - 1);
    }
  }
}

}  // namespace
}  // namespace loom
