// engine/methods/recipes/anderson_mixing: on a linear fixed-point iteration x <- x + f(x), f(x) = (M - I) x + b,
// contracting slowly (spectral radius 0.95), the mixed increments reach the same fixed point as the plain
// ones in a fraction of the iterations; with a line-search-like partial step the history stays consistent.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "engine/methods/recipes/anderson_mixing.hpp"

namespace loom {
namespace {

struct LinearMap {
  Eigen::MatrixXd M;
  Eigen::VectorXd b;
  Eigen::VectorXd f(const Eigen::VectorXd& x) const { return M * x + b - x; }
  Eigen::VectorXd fixed_point() const { return (Eigen::MatrixXd::Identity(b.size(), b.size()) - M).partialPivLu().solve(b); }
};

LinearMap slow_contraction(int n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd Q = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return u(rng); });
  Q = Eigen::HouseholderQR<Eigen::MatrixXd>(Q).householderQ();
  Eigen::VectorXd lambda(n);
  for (int i = 0; i < n; ++i) lambda[i] = 0.95 * (i + 1) / n;  // eigenvalues in (0, 0.95]
  LinearMap m;
  m.M = Q * lambda.asDiagonal() * Q.transpose();
  m.b = Eigen::VectorXd::NullaryExpr(n, [&] { return u(rng); });
  return m;
}

// Iterations until |f(x)| <= tol |f(0)|, with or without mixing; `step` scales every applied increment.
int iterate(const LinearMap& m, bool mixed, double step, Eigen::VectorXd& x) {
  AndersonMixing anderson(5);
  x = Eigen::VectorXd::Zero(m.b.size());
  const double f0 = m.f(x).norm();
  for (int k = 1; k <= 2000; ++k) {
    const Eigen::VectorXd f = m.f(x);
    if (f.norm() <= 1e-10 * f0) return k - 1;
    const Eigen::VectorXd inc = mixed ? anderson.mix(f, step) : f;
    x += step * inc;
  }
  return 2000;
}

TEST(AndersonMixing, ReachesTheSameFixedPointInAFractionOfTheIterations) {
  const LinearMap m = slow_contraction(40);
  Eigen::VectorXd plain, mixed;
  const int n_plain = iterate(m, false, 1.0, plain), n_mixed = iterate(m, true, 1.0, mixed);
  std::printf("[anderson] plain %d iterations, mixed %d\n", n_plain, n_mixed);
  EXPECT_GT(n_plain, 300);
  EXPECT_LT(n_mixed, n_plain / 3);
  EXPECT_LE((mixed - m.fixed_point()).norm(), 1e-8 * m.fixed_point().norm());
}

TEST(AndersonMixing, AccountsForPartialSteps) {
  const LinearMap m = slow_contraction(20);
  Eigen::VectorXd x;
  const int n = iterate(m, true, 0.5, x);
  EXPECT_LT(n, 200);
  EXPECT_LE((x - m.fixed_point()).norm(), 1e-8 * m.fixed_point().norm());
}

TEST(AndersonMixing, FirstIncrementAndAResizedProblemPassThrough) {
  AndersonMixing a(3);
  const Eigen::VectorXd f = Eigen::VectorXd::LinSpaced(4, 1.0, 4.0);
  EXPECT_EQ(a.mix(f, 1.0), f);
  const Eigen::VectorXd g = Eigen::VectorXd::Constant(6, 2.0);
  EXPECT_EQ(a.mix(g, 1.0), g);  // another size (a new active set): the history restarts
}

}  // namespace
}  // namespace loom
