// The integrator family (systems/update/time_integrator.hpp) on an undamped linear oscillator
// m u'' + k u = 0: one Newton step per time step with the integrator's inertia (exactly what assemble_system
// and commit_step do per node), compared with the amplification matrix of alpha-Bossak written here from
// its defining equations (Wood, Bossak & Zienkiewicz 1980):
//   (1 - alpha) a1 + alpha a0 + w^2 u1 = 0
//   u1 = u0 + dt v0 + dt^2 ((1/2 - beta) a0 + beta a1),  v1 = v0 + dt ((1 - gamma) a0 + gamma a1)
// so that x1 = L^-1 R x0 with x = (u, v, a). Its principal eigenvalues rho e^(+-i W dt) give the numerical
// period 2 pi / W and the damping ratio -ln(rho) / (W dt); the simulated period and decay must match them.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>

#include "systems/update/time_integrator.hpp"

namespace loom {
namespace {

struct Spectral {
  double period, damping;
};

Spectral bossak_spectrum(double alpha, double omega, double dt) {
  const double beta = 0.25 * (1 - alpha) * (1 - alpha), gamma = 0.5 - alpha;
  Eigen::Matrix3d L, R;
  L << omega * omega, 0, 1 - alpha, 1, 0, -beta * dt * dt, 0, 1, -gamma * dt;
  R << 0, 0, -alpha, 1, dt, (0.5 - beta) * dt * dt, 0, 1, (1 - gamma) * dt;
  const Eigen::Matrix3d A = L.inverse() * R;
  const Eigen::EigenSolver<Eigen::Matrix3d> es(A);
  std::complex<double> lambda(0, 0);
  for (int k = 0; k < 3; ++k)
    if (es.eigenvalues()[k].imag() > 0) lambda = es.eigenvalues()[k];
  const double W = std::arg(lambda) / dt, rho = std::abs(lambda);
  return {2 * M_PI / W, -std::log(rho) / (W * dt)};
}

// Simulates the oscillator with the integrator; returns the mean period from upward zero crossings.
double simulated_period(const TimeIntegrator& ti, double omega, int steps) {
  const double k = omega * omega, m = 1.0;
  Vec2 u(1.0, 0.0), v = Vec2::Zero(), a(-k * 1.0, 0.0);  // equilibrium a_0
  std::vector<double> crossings;
  for (int n = 0; n < steps; ++n) {
    // One Newton step on r(du) = m ia(du) + k (u + du) is exact (linear).
    Vec2 du = Vec2::Zero();
    const double r = m * ti.inertial_acceleration(du, v, a)[0] + k * u[0];
    du[0] = -r / (m * ti.stiffness() + k);
    const Vec2 a1 = ti.acceleration(du, v, a), v1 = ti.velocity(du, v, a, a1);
    const double u1 = u[0] + du[0];
    if (u[0] < 0 && u1 >= 0) crossings.push_back(n + u[0] / (u[0] - u1));
    u[0] = u1, v = v1, a = a1;
  }
  return (crossings.back() - crossings.front()) / double(crossings.size() - 1) * ti.dt;
}

TEST(TimeIntegrator, BossakPeriodMatchesAmplificationMatrix) {
  const double omega = 2 * M_PI, dt = 0.05;  // T = 1, 20 steps per period
  for (const double alpha : {0.0, -0.1, -0.3}) {
    TimeSpec spec;
    spec.integrator = Integrator::bossak;
    spec.alpha = alpha;
    const TimeIntegrator ti = time_integrator_of(spec, dt);
    const Spectral expected = bossak_spectrum(alpha, omega, dt);
    EXPECT_NEAR(simulated_period(ti, omega, 2000), expected.period, 2e-4 * expected.period) << "alpha " << alpha;
    EXPECT_GT(expected.period, 1.0);  // period elongation
    if (alpha == 0.0) EXPECT_NEAR(expected.damping, 0.0, 1e-12);
    else EXPECT_GT(expected.damping, 0.0);
  }
}

// After N steps the state is A^N x0: the simulated state against the matrix power (the numerical damping
// is rho < 1 for alpha < 0, none for alpha = 0).
TEST(TimeIntegrator, BossakStepIsTheAmplificationMatrix) {
  const double omega = 3.0, dt = 0.1;
  for (const double alpha : {0.0, -0.1, -0.3}) {
    TimeSpec spec;
    spec.integrator = Integrator::bossak;
    spec.alpha = alpha;
    const TimeIntegrator ti = time_integrator_of(spec, dt);
    const double beta = ti.beta, gamma = ti.gamma;
    Eigen::Matrix3d L, R;
    L << omega * omega, 0, 1 - alpha, 1, 0, -beta * dt * dt, 0, 1, -gamma * dt;
    R << 0, 0, -alpha, 1, dt, (0.5 - beta) * dt * dt, 0, 1, (1 - gamma) * dt;
    const Eigen::Matrix3d A = L.inverse() * R;
    Eigen::Vector3d x(1.0, 0.5, -omega * omega);
    Vec2 u(1.0, 0), v(0.5, 0), a(-omega * omega, 0);
    for (int n = 0; n < 200; ++n) {
      const double r = ti.inertial_acceleration(Vec2::Zero(), v, a)[0] + omega * omega * u[0];
      const Vec2 du(-r / (ti.stiffness() + omega * omega), 0.0);
      const Vec2 a1 = ti.acceleration(du, v, a);
      v = ti.velocity(du, v, a, a1), a = a1, u += du;
      x = A * x;
    }
    EXPECT_NEAR(u[0], x[0], 1e-10);
    EXPECT_NEAR(v[0], x[1], 1e-10);
    EXPECT_NEAR(a[0], x[2], 1e-9);
    const double rho = Eigen::EigenSolver<Eigen::Matrix3d>(A).eigenvalues().cwiseAbs().maxCoeff();
    if (alpha == 0.0) EXPECT_NEAR(rho, 1.0, 1e-12);  // average acceleration conserves energy
    else EXPECT_LT(rho, 1.0);
  }
}

// Constant acceleration g from a_0 = g: u = g t^2 / 2 and v = g t exactly, for every alpha.
TEST(TimeIntegrator, FreeFallIsExact) {
  const double g = -9.81, dt = 0.01;
  for (const double alpha : {0.0, -0.1, -0.3}) {
    TimeSpec spec;
    spec.integrator = Integrator::bossak;
    spec.alpha = alpha;
    const TimeIntegrator ti = time_integrator_of(spec, dt);
    Vec2 u = Vec2::Zero(), v = Vec2::Zero(), a(0.0, g);
    for (int n = 1; n <= 100; ++n) {
      // r(du) = ia(du) - g = 0, linear in du.
      const Vec2 r = ti.inertial_acceleration(Vec2::Zero(), v, a) - Vec2(0.0, g);
      const Vec2 du = -r / ti.stiffness();
      const Vec2 a1 = ti.acceleration(du, v, a);
      v = ti.velocity(du, v, a, a1), a = a1, u += du;
      const double t = n * dt;
      EXPECT_NEAR(u[1], 0.5 * g * t * t, 1e-12);
      EXPECT_NEAR(v[1], g * t, 1e-12);
    }
  }
}

// The inertia tangent is the derivative of the inertial acceleration.
TEST(TimeIntegrator, StiffnessIsTheDerivative) {
  for (const Integrator kind : {Integrator::euler_backward, Integrator::newmark, Integrator::bossak}) {
    TimeSpec spec;
    spec.integrator = kind;
    const TimeIntegrator ti = time_integrator_of(spec, 0.3);
    const Vec2 du(0.2, -0.1), v(1.0, 2.0), a(-3.0, 0.5);
    const double h = 1e-6;
    const double fd = (ti.inertial_acceleration(du + Vec2(h, 0), v, a)[0] - ti.inertial_acceleration(du - Vec2(h, 0), v, a)[0]) / (2 * h);
    EXPECT_NEAR(fd, ti.stiffness(), 1e-6 * ti.stiffness());
  }
}

}  // namespace
}  // namespace loom
