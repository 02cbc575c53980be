// Newton driver (engine/drivers/newton): quadratic convergence on a smooth toy problem, failures reported
// (singular tangent, divergence, inadmissible iterates), and the backtracking line search rescuing
// problems where full steps overshoot.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <string>

#include "engine/drivers/newton.hpp"

namespace loom {
namespace {

// A small dense nonlinear system r(x) = 0 with Jacobian J(x); x is admissible where `admissible` holds.
class ToyProblem : public NonlinearProblem {
 public:
  using Vector = Eigen::VectorXd;
  using Matrix = Eigen::MatrixXd;
  std::function<Vector(const Vector&)> r_of;
  std::function<Matrix(const Vector&)> J_of;
  std::function<bool(const Vector&)> admissible = [](const Vector&) { return true; };
  std::function<bool(int updates)> pending = [](int) { return false; };

  Vector x, x_start, r, du;
  Matrix J;
  int updates = 0;

  ToyProblem(Vector x0, std::function<Vector(const Vector&)> r_fn, std::function<Matrix(const Vector&)> J_fn)
      : r_of(std::move(r_fn)), J_of(std::move(J_fn)), x(x0), x_start(std::move(x0)) {}

  bool assemble(bool with_tangent) override {
    if (!admissible(x)) return false;
    r = r_of(x);
    if (with_tangent) J = J_of(x);
    return true;
  }
  double residual_norm() const override { return r.norm(); }
  bool solve() override {
    Eigen::FullPivLU<Matrix> lu(J);
    if (!lu.isInvertible()) return false;
    du = lu.solve(-r);
    return true;
  }
  void update(double step) override {
    x += step * du;
    ++updates;
  }
  double increment_norm() const override { return du.norm(); }
  double step_change_norm() const override { return (x - x_start).norm(); }
  bool prescribed_pending() const override { return pending(updates); }
};

Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd x(Eigen::Index(v.size()));
  Eigen::Index i = 0;
  for (double e : v) x(i++) = e;
  return x;
}

ToyProblem scalar(double x0, std::function<double(double)> f, std::function<double(double)> df) {
  return ToyProblem(
      vec({x0}), [f](const Eigen::VectorXd& x) { return vec({f(x(0))}); },
      [df](const Eigen::VectorXd& x) { return Eigen::MatrixXd::Constant(1, 1, df(x(0))); });
}

// Only the absolute residual decides, so the rate is seen down to round-off.
NewtonSettings strict(bool line_search = false) {
  NewtonSettings s;
  s.residual_absolute = 1e-13;
  s.residual_relative = 0.0;
  s.increment_relative = 0.0;
  s.line_search = line_search;
  return s;
}

// Counts its assemblies and tangents, and checks that every solve uses the tangent of the iterate it solves at.
struct Counting : ToyProblem {
  using ToyProblem::ToyProblem;
  int tangents = 0, assemblies = 0;
  Eigen::VectorXd tangent_at;
  bool assemble(bool with_tangent) override {
    tangents += with_tangent, ++assemblies;
    if (with_tangent) tangent_at = x;
    return ToyProblem::assemble(with_tangent);
  }
  bool solve() override {
    EXPECT_EQ(tangent_at, x) << "solved with a tangent of another iterate";
    return ToyProblem::solve();
  }
};

}  // namespace

TEST(SolveNewton, ConvergesQuadraticallyOnASmoothSystem) {
  // Circle of radius 2 cut by the diagonal: root (sqrt 2, sqrt 2).
  ToyProblem p(
      vec({3.0, 0.5}),
      [](const Eigen::VectorXd& x) { return vec({x(0) * x(0) + x(1) * x(1) - 4.0, x(0) - x(1)}); },
      [](const Eigen::VectorXd& x) {
        Eigen::MatrixXd J(2, 2);
        J << 2 * x(0), 2 * x(1), 1, -1;
        return J;
      });
  Timers timers;
  const NewtonReport rep = solve_newton(p, strict(), timers);
  ASSERT_TRUE(rep.converged) << rep.failure;
  EXPECT_NEAR(p.x(0), std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(p.x(1), std::sqrt(2.0), 1e-12);
  EXPECT_LE(rep.iterations, 8);
  ASSERT_EQ(rep.residuals.size(), std::size_t(rep.iterations) + 1);
  // Quadratic rate: r_{k+1} <= C r_k^2 once in the basin (r_k < 0.1), above round-off.
  int checked = 0;
  for (std::size_t k = 0; k + 1 < rep.residuals.size(); ++k) {
    const double rk = rep.residuals[k], rk1 = rep.residuals[k + 1];
    if (rk > 0.1 || rk1 < 1e-14) continue;
    EXPECT_LE(rk1, 2.0 * rk * rk) << "iteration " << k;
    ++checked;
  }
  EXPECT_GE(checked, 2);
  // The driver times its phases.
  const auto stats = timers.snapshot();
  EXPECT_EQ(stats.at("newton/solve").calls, rep.iterations);
  EXPECT_EQ(stats.at("newton/assemble").calls, rep.iterations + 1);
}

TEST(SolveNewton, AConvergedStartNeedsNoSolve) {
  ToyProblem p = scalar(1.0, [](double x) { return x * x - 1.0; }, [](double x) { return 2 * x; });
  Timers timers;
  const NewtonReport rep = solve_newton(p, strict(), timers);
  EXPECT_TRUE(rep.converged);
  EXPECT_EQ(rep.iterations, 0);
  EXPECT_EQ(p.updates, 0);
}

TEST(SolveNewton, PendingPrescribedValuesForceAnIteration) {
  // The residual is already zero but a prescribed value still lags: one solve and update are needed.
  ToyProblem p = scalar(1.0, [](double x) { return x * x - 1.0; }, [](double x) { return 2 * x; });
  p.pending = [](int updates) { return updates == 0; };
  Timers timers;
  const NewtonReport rep = solve_newton(p, strict(), timers);
  EXPECT_TRUE(rep.converged);
  EXPECT_EQ(rep.iterations, 1);
}

TEST(SolveNewton, ReportsASingularTangent) {
  // r = x^2 - 1 from x = 0: the tangent 2x vanishes.
  ToyProblem p = scalar(0.0, [](double x) { return x * x - 1.0; }, [](double x) { return 2 * x; });
  Timers timers;
  const NewtonReport rep = solve_newton(p, strict(), timers);
  EXPECT_FALSE(rep.converged);
  EXPECT_EQ(rep.iterations, 0);
  EXPECT_NE(rep.failure.find("singular"), std::string::npos) << rep.failure;
}

TEST(SolveNewton, FullStepsDivergeOnArctanFromTwo) {
  // atan(x) = 0 from x = 2: Newton overshoots further every step (|x0| > 1.39...).
  ToyProblem p = scalar(2.0, [](double x) { return std::atan(x); }, [](double x) { return 1.0 / (1.0 + x * x); });
  Timers timers;
  const NewtonReport rep = solve_newton(p, strict(false), timers);
  EXPECT_FALSE(rep.converged);
  EXPECT_FALSE(rep.failure.empty());
  ASSERT_GE(rep.residuals.size(), 2u);
  EXPECT_GT(rep.residuals.back(), rep.residuals.front());  // it went the wrong way
}

TEST(SolveNewton, LineSearchConvergesOnArctanFromTwo) {
  ToyProblem p = scalar(2.0, [](double x) { return std::atan(x); }, [](double x) { return 1.0 / (1.0 + x * x); });
  Timers timers;
  const NewtonReport rep = solve_newton(p, strict(true), timers);
  ASSERT_TRUE(rep.converged) << rep.failure;
  EXPECT_NEAR(p.x(0), 0.0, 1e-12);
  // Every accepted iterate decreased the residual.
  for (std::size_t k = 0; k + 1 < rep.residuals.size(); ++k) EXPECT_LT(rep.residuals[k + 1], rep.residuals[k]);
}

TEST(SolveNewton, InadmissibleIterateFailsWithoutLineSearch) {
  // ln x = 0 from x = 3: the full step lands at x = 3 - 3 ln 3 < 0, where ln is undefined (like J <= 0).
  ToyProblem p = scalar(3.0, [](double x) { return std::log(x); }, [](double x) { return 1.0 / x; });
  p.admissible = [](const Eigen::VectorXd& x) { return x(0) > 0.0; };
  Timers timers;
  const NewtonReport rep = solve_newton(p, strict(false), timers);
  EXPECT_FALSE(rep.converged);
  EXPECT_NE(rep.failure.find("invert"), std::string::npos) << rep.failure;
}

TEST(SolveNewton, LineSearchBacksOutOfAnInadmissibleIterate) {
  ToyProblem p = scalar(3.0, [](double x) { return std::log(x); }, [](double x) { return 1.0 / x; });
  p.admissible = [](const Eigen::VectorXd& x) { return x(0) > 0.0; };
  Timers timers;
  const NewtonReport rep = solve_newton(p, strict(true), timers);
  ASSERT_TRUE(rep.converged) << rep.failure;
  EXPECT_NEAR(p.x(0), 1.0, 1e-12);
}

TEST(SolveNewton, InadmissibleStartIsReported) {
  ToyProblem p = scalar(-1.0, [](double x) { return std::log(x); }, [](double x) { return 1.0 / x; });
  p.admissible = [](const Eigen::VectorXd& x) { return x(0) > 0.0; };
  Timers timers;
  const NewtonReport rep = solve_newton(p, strict(true), timers);
  EXPECT_FALSE(rep.converged);
  EXPECT_EQ(rep.iterations, 0);
  EXPECT_FALSE(rep.failure.empty());
}

TEST(SolveNewton, GivesUpAfterMaxIterations) {
  // A wrong (halved) tangent converges only linearly: 3 iterations are not enough.
  ToyProblem p = scalar(1.5, [](double x) { return x - 1.0; }, [](double) { return 2.0; });
  NewtonSettings s = strict();
  s.max_iterations = 3;
  Timers timers;
  const NewtonReport rep = solve_newton(p, s, timers);
  EXPECT_FALSE(rep.converged);
  EXPECT_EQ(rep.iterations, 3);
  EXPECT_NE(rep.failure.find("3 iterations"), std::string::npos) << rep.failure;
}

TEST(SolveNewton, RelativeResidualCriterion) {
  ToyProblem p = scalar(1.5, [](double x) { return x - 1.0; }, [](double) { return 2.0; });
  NewtonSettings s = strict();
  s.residual_relative = 0.1;  // residuals halve: 0.5, 0.25, 0.125, 0.0625 <= 0.05? no; 0.03125 yes
  s.residual_absolute = 0.0;
  Timers timers;
  const NewtonReport rep = solve_newton(p, s, timers);
  EXPECT_TRUE(rep.converged);
  EXPECT_EQ(rep.iterations, 4);
}

}  // namespace loom

namespace loom {
namespace {

// Two residual blocks of very different size (forces and volumes): x0 - 1 = 0 (block 0, solved exactly by
// the first iteration) and 1e-6 (x1 - 2) = 0 (block 1, whose error the tangent only halves per iteration).
// The combined norm is below 1e-3 of its start after one iteration; the block test waits for block 1.
class TwoBlockProblem : public ToyProblem {
 public:
  using ToyProblem::ToyProblem;
  int blocks() const override { return 2; }
  double block_norm(int b) const override { return std::abs(r(b)); }
};

}  // namespace

TEST(SolveNewton, EveryResidualBlockMustConverge) {
  auto r_fn = [](const Eigen::VectorXd& x) { return vec({x(0) - 1.0, 1e-6 * (x(1) - 2.0)}); };
  auto J_fn = [](const Eigen::VectorXd&) {
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2, 2);
    J(0, 0) = 1.0, J(1, 1) = 2e-6;
    return J;
  };
  NewtonSettings s = strict();
  s.residual_relative = 1e-3, s.residual_absolute = 0.0;
  Timers timers;
  TwoBlockProblem blocks(vec({2.0, 3.0}), r_fn, J_fn);
  const NewtonReport rep = solve_newton(blocks, s, timers);
  ASSERT_TRUE(rep.converged);
  EXPECT_EQ(rep.iterations, 10);  // 2^-10 < 1e-3 < 2^-9 for block 1
  ToyProblem combined(vec({2.0, 3.0}), r_fn, J_fn);
  const NewtonReport one = solve_newton(combined, s, timers);
  ASSERT_TRUE(one.converged);
  EXPECT_EQ(one.iterations, 1);
}

// A frozen tangent assembles it once: later iterations ask for the residual only.
TEST(SolveNewton, TangentOncePerStepAssemblesItOnce) {
  struct Counting : ToyProblem {
    using ToyProblem::ToyProblem;
    int tangents = 0;
    bool assemble(bool with_tangent) override {
      tangents += with_tangent;
      return ToyProblem::assemble(with_tangent);
    }
  };
  Counting p(vec({0.5}), [](const Eigen::VectorXd& x) { return vec({std::atan(x(0))}); },
             [](const Eigen::VectorXd& x) { return Eigen::MatrixXd::Constant(1, 1, 1.0 / (1.0 + x(0) * x(0))); });
  NewtonSettings s = strict();
  s.tangent_once_per_step = true;
  Timers timers;
  const NewtonReport rep = solve_newton(p, s, timers);
  ASSERT_TRUE(rep.converged) << rep.failure;
  EXPECT_EQ(p.tangents, 1);
  EXPECT_GT(rep.iterations, 4);  // linear convergence of the modified Newton method
}

// Lazy tangent (NewtonSettings::expected_iterations): the same iterates, residuals and solution bit for bit
// whatever the expectation, with one tangent fewer when the expectation is met, one residual-only
// assembly more when it is not, and the tangent always at the iterate that is solved with.
TEST(SolveNewton, LazyTangentChangesNoIterateAndSkipsTheUnusedTangent) {
  auto make = [] {
    return Counting(vec({0.5, -0.3}), [](const Eigen::VectorXd& x) { return vec({std::atan(x(0)) + 0.1 * x(1), x(1) * x(1) * x(1) + x(1) - 0.2}); },
                    [](const Eigen::VectorXd& x) {
                      Eigen::MatrixXd J(2, 2);
                      J << 1.0 / (1.0 + x(0) * x(0)), 0.1, 0.0, 3.0 * x(1) * x(1) + 1.0;
                      return J;
                    });
  };
  Timers timers;
  Counting eager = make();
  const NewtonReport ref = solve_newton(eager, strict(), timers);
  ASSERT_TRUE(ref.converged) << ref.failure;
  ASSERT_GE(ref.iterations, 3);
  EXPECT_EQ(eager.tangents, ref.iterations + 1);  // one per assembly: the last is never used
  for (int expected : {1, ref.iterations - 1, ref.iterations, ref.iterations + 2}) {
    Counting lazy = make();
    NewtonSettings s = strict();
    s.expected_iterations = expected;
    const NewtonReport rep = solve_newton(lazy, s, timers);
    ASSERT_TRUE(rep.converged) << rep.failure;
    EXPECT_EQ(rep.iterations, ref.iterations) << "expected " << expected;
    EXPECT_EQ(rep.residuals, ref.residuals) << "expected " << expected;
    EXPECT_EQ(lazy.x, eager.x) << "expected " << expected;
    const int n = ref.iterations;
    if (expected <= n) {
      EXPECT_EQ(lazy.tangents, n) << "expected " << expected;  // every solve's, not the last assembly's
      // From the expected iteration on, each unconverged residual is assembled again with its tangent.
      EXPECT_EQ(lazy.assemblies, 1 + n + (n - expected)) << "expected " << expected;
    } else {  // never lazy
      EXPECT_EQ(lazy.tangents, n + 1) << "expected " << expected;
      EXPECT_EQ(lazy.assemblies, n + 1) << "expected " << expected;
    }
  }
}

TEST(SolveNewton, LineSearchTrialsWithoutTangentChangeNoIterate) {
  // atan(x) = 0 from x = 2 backtracks in its first iterations: each trial point is assembled for its residual,
  // the tangent only at the accepted point that has not converged.
  auto make = [] {
    return Counting(vec({2.0}), [](const Eigen::VectorXd& x) { return vec({std::atan(x(0))}); },
                    [](const Eigen::VectorXd& x) { return Eigen::MatrixXd::Constant(1, 1, 1.0 / (1.0 + x(0) * x(0))); });
  };
  Timers timers;
  Counting eager = make();
  const NewtonReport ref = solve_newton(eager, strict(true), timers);
  ASSERT_TRUE(ref.converged) << ref.failure;
  const int n = ref.iterations;
  ASSERT_GT(eager.assemblies, n + 1) << "the line search did not backtrack: the test shows nothing";
  EXPECT_EQ(eager.tangents, eager.assemblies);
  Counting trial = make();
  NewtonSettings s = strict(true);
  s.trials_without_tangent = true;
  const NewtonReport rep = solve_newton(trial, s, timers);
  ASSERT_TRUE(rep.converged) << rep.failure;
  EXPECT_EQ(rep.iterations, n);
  EXPECT_EQ(rep.residuals, ref.residuals);
  EXPECT_EQ(trial.x, eager.x);
  EXPECT_EQ(trial.tangents, n);  // the start's and one per accepted, unconverged iterate
  EXPECT_EQ(trial.assemblies, eager.assemblies + n - 1);
  // Without the line search the setting does nothing.
  Counting plain = make();
  plain.x = plain.x_start = vec({0.5});
  Counting plain_ref = make();
  plain_ref.x = plain_ref.x_start = vec({0.5});
  NewtonSettings off = strict(false);
  const NewtonReport a = solve_newton(plain_ref, off, timers);
  off.trials_without_tangent = true;
  const NewtonReport b = solve_newton(plain, off, timers);
  ASSERT_TRUE(a.converged && b.converged);
  EXPECT_EQ(a.residuals, b.residuals);
  EXPECT_EQ(plain.tangents, plain_ref.tangents);
}

// A residual with a floor: r(x) = x - 1 + 1e-7 sin(1e9 x), solved with the tangent 1. Newton lands within 1e-7 of
// the root at once and then wanders there: with residual_relative = 1e-9 it cannot converge, and says at what
// level it stagnated and which key to loosen, instead of only "no convergence".
TEST(SolveNewton, AResidualAtAFloorAboveTheToleranceIsReportedAsStagnated) {
  ToyProblem p = scalar(
      2.0, [](double x) { return x - 1.0 + 1e-7 * std::sin(1e9 * x); }, [](double) { return 1.0; });
  NewtonSettings s;
  s.residual_relative = 1e-9;
  s.residual_absolute = 1e-300;
  s.increment_relative = 0.0;
  s.max_iterations = 12;
  Timers timers;
  const NewtonReport report = solve_newton(p, s, timers);
  ASSERT_FALSE(report.converged);
  EXPECT_TRUE(report.stagnated);
  const double floor = report.stagnation;  // relative to |r_0| = 1
  EXPECT_GT(floor, 1e-9);
  EXPECT_LT(floor, 2e-7);
  EXPECT_NE(report.failure.find("the residual stagnated at "), std::string::npos) << report.failure;
  EXPECT_NE(report.failure.find("above solver.residual_relative = 1e-09: loosen it (solver.residual_relative = "), std::string::npos)
      << report.failure;
}

// Linear convergence is not stagnation: x^3 = 0 from 1 converges with ratio 2/3 per iteration.
TEST(SolveNewton, SlowButSteadyConvergenceIsNotStagnation) {
  ToyProblem p = scalar(
      1.0, [](double x) { return x * x * x; }, [](double x) { return 3.0 * x * x; });
  NewtonSettings s = strict();
  s.max_iterations = 12;
  Timers timers;
  const NewtonReport report = solve_newton(p, s, timers);
  ASSERT_FALSE(report.converged);
  EXPECT_FALSE(report.stagnated) << report.failure;
  EXPECT_EQ(report.failure.find("stagnated"), std::string::npos) << report.failure;
  EXPECT_FALSE(residual_stagnated({1.0, 0.3, 0.1, 0.03, 0.01, 0.003}));
  EXPECT_TRUE(residual_stagnated({1.0, 1e-7, 2e-7, 1.5e-7, 1e-7, 3e-7}));
  EXPECT_FALSE(residual_stagnated({1.0, 1e-7, 2e-7, 1.5e-7, 1e-7}));  // too few to tell
}

// A fast start and then a tangent ten times too stiff (a kept tangent, say): the residual falls to ~1e-6 and then
// by 0.9 per iteration. The later half is no decade below the earlier one, but it falls at every iteration: that
// is slow convergence (raise max_iterations), not a floor (loosen the tolerance).
TEST(SolveNewton, AFastStartThenLinearConvergenceIsNotStagnation) {
  ToyProblem p = scalar(
      2.0, [](double x) { return x - 1.0 + 0.1 * (x - 1.0) * (x - 1.0); },
      [](double x) { return std::abs(x - 1.0) > 1e-5 ? 1.0 + 0.2 * (x - 1.0) : 10.0; });
  NewtonSettings s = strict();
  s.residual_relative = 1e-12;
  s.max_iterations = 20;
  Timers timers;
  const NewtonReport report = solve_newton(p, s, timers);
  ASSERT_FALSE(report.converged);
  ASSERT_GE(report.residuals.size(), 20u);
  const double last = report.residuals.back(), tenth = report.residuals[9];
  EXPECT_GT(last, 0.1 * tenth) << "the later half fell by a decade: the test shows nothing";
  EXPECT_FALSE(report.stagnated) << report.failure;
  EXPECT_NE(report.failure.find("the residual was still decreasing, by a factor of 0.9 per iteration: raise solver.max_iterations"),
            std::string::npos)
      << report.failure;
  EXPECT_TRUE(residual_still_decreasing({1.0, 1e-5, 9e-6, 8.1e-6, 7.3e-6, 6.6e-6}));
  EXPECT_FALSE(residual_stagnated({1.0, 1e-5, 9e-6, 8.1e-6, 7.3e-6, 6.6e-6}));
}

// A first update of many body sizes followed by an inverted cell: a unit mistake, named as such.
struct HugeUpdate : ToyProblem {
  using ToyProblem::ToyProblem;
  double increment_over_size() const override { return std::abs(du(0)) / 0.1; }  // a body 0.1 long
};

TEST(SolveNewton, AnInversionAfterAHugeFirstUpdateHintsAtUnits) {
  HugeUpdate p(
      vec({0.0}), [](const Eigen::VectorXd& x) { return vec({x(0) - 5e3}); },
      [](const Eigen::VectorXd&) { return Eigen::MatrixXd::Constant(1, 1, 1.0); });
  p.admissible = [](const Eigen::VectorXd& x) { return x(0) < 1.0; };
  Timers timers;
  const NewtonReport report = solve_newton(p, strict(), timers);
  ASSERT_FALSE(report.converged);
  EXPECT_NEAR(report.first_increment_over_size, 5e4, 1e-6);
  EXPECT_NE(report.failure.find("a cell inverted during the Newton iterations; the first Newton update moved nodes by 5e+04 times the body's size"),
            std::string::npos)
      << report.failure;
  EXPECT_NE(report.failure.find("one system of units"), std::string::npos) << report.failure;
  // A modest first update gets no such hint.
  HugeUpdate q(
      vec({0.0}), [](const Eigen::VectorXd& x) { return vec({x(0) - 0.5}); },
      [](const Eigen::VectorXd&) { return Eigen::MatrixXd::Constant(1, 1, 1.0); });
  q.admissible = [](const Eigen::VectorXd& x) { return x(0) < 0.4; };
  const NewtonReport modest = solve_newton(q, strict(), timers);
  EXPECT_EQ(modest.failure, "a cell inverted during the Newton iterations");
}


}  // namespace loom
