// solver.reuse_factor (engine/linalg/linear_solver.hpp, factor_preconditioned_gmres.cpp): a new matrix of an
// analysed pattern is solved by GMRES preconditioned with the kept factorisation, to the tolerance on the solution's
// relative error; a matrix too far from the factorised one is factorised afresh and solved directly; a slow GMRES solve
// makes the next factorize() factorise; a new pattern is always factorised; the solve is that of a fresh
// factorisation within the tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/linalg/linear_solver.hpp"
#include "engine/timing/timers.hpp"
#include "systems/solve/solve_linear_step.hpp"

namespace loom {
namespace {

constexpr int kN = 200;

// The unsymmetric tridiagonal matrix diag(d + shift * i / n), sub -1, super -1 - skew: a 1D convection-diffusion operator.
SparsePattern convection_diffusion(double d, double shift, double skew, std::uint64_t version) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < kN; ++i) {
    t.emplace_back(i, i, d + shift * i / kN);
    if (i + 1 < kN) t.emplace_back(i, i + 1, -1.0 - skew), t.emplace_back(i + 1, i, -1.0);
  }
  SparsePattern p;
  p.matrix.resize(kN, kN);
  p.matrix.setFromTriplets(t.begin(), t.end());
  p.matrix.makeCompressed();
  p.version = version;
  return p;
}

Eigen::VectorXd rhs() {
  Eigen::VectorXd b(kN);
  for (int i = 0; i < kN; ++i) b[i] = std::sin(0.05 * i) + 0.3;
  return b;
}

double relative_residual(const SparsePattern& p, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  return (p.matrix * x - b).norm() / b.norm();
}

// A UMFPACK LinearSolve (tolerance 1e-10) that has factorised and solved the base matrix diag 2.5 of pattern 1.
struct SolvedOnce {
  explicit SolvedOnce(bool reuse) : s(LinearSolverKind::umfpack, 1e-10, reuse) { started = run(convection_diffusion(2.5, 0.0, 0.0, 1)); }
  bool run(const SparsePattern& p) { return s.factorize(p) && s.solve(b, x); }
  LinearSolve s;
  Eigen::VectorXd b = rhs(), x;
  bool started = false;
};

}  // namespace

TEST(FactorReuse, ANearbyMatrixIsSolvedByGmresOnTheKeptFactorisation) {
  for (auto kind : {LinearSolverKind::umfpack, LinearSolverKind::cholmod}) {
    const double tolerance = 1e-10;
    LinearSolve s(kind, tolerance, true);
    const Eigen::VectorXd b = rhs();
    Eigen::VectorXd x;
    SparsePattern p = convection_diffusion(2.5, 0.0, 0.0, 1);
    ASSERT_TRUE(s.factorize(p) && s.solve(b, x));
    EXPECT_LT(relative_residual(p, x, b), 1e-14);
    EXPECT_EQ(s.factorizations(), 1);
    // The next iterate's tangent: 1 % off, and (for UMFPACK) unsymmetric. CHOLMOD's factor preconditions a
    // symmetric change.
    const double skew = kind == LinearSolverKind::umfpack ? 0.01 : 0.0;
    const SparsePattern q = convection_diffusion(2.5, 0.02, skew, 1);
    ASSERT_TRUE(s.factorize(q) && s.solve(b, x)) << s.backend();
    EXPECT_EQ(s.factorizations(), 1) << s.backend();
    EXPECT_EQ(s.reused_solves(), 1);
    EXPECT_GT(s.gmres_iterations(), 0);
    EXPECT_LE(s.gmres_iterations(), LinearSolve::kRefactorAbove);
    EXPECT_EQ(s.reuse_fallbacks(), 0);
    // The answer of a fresh factorisation to the tolerance (GMRES's test bounds the relative error of x), and the
    // residual to the tolerance times the condition (below 10 here).
    LinearSolve fresh(kind);
    Eigen::VectorXd y;
    ASSERT_TRUE(fresh.factorize(q) && fresh.solve(b, y));
    EXPECT_LE((x - y).norm(), 2 * tolerance * y.norm());
    EXPECT_LE(relative_residual(q, x, b), 10 * tolerance);
  }
}

TEST(FactorReuse, AFarMatrixIsFactorisedAfreshAndSolvedDirectly) {
  SolvedOnce r(true);
  ASSERT_TRUE(r.started);
  LinearSolve& s = r.s;
  const Eigen::VectorXd& b = r.b;
  Eigen::VectorXd& x = r.x;
  // Diagonal 2.5 -> 2.02: the preconditioned spectrum spans 0.04 to 0.9 (condition ~22, ~50 GMRES iterations to 1e-10,
  // not 20), while the matrix itself stays well conditioned (eigenvalues 0.02 to 4.02).
  const SparsePattern q = convection_diffusion(2.02, 0.0, 0.0, 1);
  ASSERT_TRUE(s.factorize(q) && s.solve(b, x));
  EXPECT_EQ(s.reuse_fallbacks(), 1);
  EXPECT_EQ(s.factorizations(), 2);
  EXPECT_LT(relative_residual(q, x, b), 1e-13);  // solved directly
}

TEST(FactorReuse, ASlowGmresSolveMakesTheNextFactorizeFactorise) {
  SolvedOnce r(true);
  ASSERT_TRUE(r.started);
  LinearSolve& s = r.s;
  const Eigen::VectorXd& b = r.b;
  Eigen::VectorXd& x = r.x;
  const SparsePattern q = convection_diffusion(2.5, 0.6, 0.0, 1);  // far enough for more than 8 iterations, not 20
  ASSERT_TRUE(s.factorize(q) && s.solve(b, x));
  ASSERT_EQ(s.reuse_fallbacks(), 0);
  ASSERT_GT(s.gmres_iterations(), LinearSolve::kRefactorAbove);
  EXPECT_LE(relative_residual(q, x, b), 1e-9);
  ASSERT_TRUE(s.factorize(q) && s.solve(b, x));
  EXPECT_EQ(s.factorizations(), 2);  // the slow solve's matrix, factorised
  EXPECT_EQ(s.reused_solves(), 1);
  EXPECT_LT(relative_residual(q, x, b), 1e-13);
}

TEST(FactorReuse, ANewPatternIsAlwaysFactorised) {
  SolvedOnce r(true);
  ASSERT_TRUE(r.started);
  LinearSolve& s = r.s;
  const Eigen::VectorXd& b = r.b;
  Eigen::VectorXd& x = r.x;
  const SparsePattern q = convection_diffusion(2.5, 0.02, 0.0, 2);
  ASSERT_TRUE(s.factorize(q) && s.solve(b, x));
  EXPECT_EQ(s.analyses(), 2);
  EXPECT_EQ(s.factorizations(), 2);
  EXPECT_EQ(s.reused_solves(), 0);
  EXPECT_LT(relative_residual(q, x, b), 1e-13);
}

TEST(FactorReuse, WithoutTheOptionEveryFactorizeFactorises) {
  SolvedOnce r(false);
  ASSERT_TRUE(r.started);
  LinearSolve& s = r.s;
  const Eigen::VectorXd& b = r.b;
  Eigen::VectorXd& x = r.x;
  ASSERT_TRUE(s.factorize(convection_diffusion(2.5, 0.02, 0.0, 1)) && s.solve(b, x));
  EXPECT_EQ(s.factorizations(), 2);
  EXPECT_EQ(s.reused_solves(), 0);
}

// A run's profile puts each factorisation under newton/solve/factorize, the one a failed GMRES solve falls back on
// too (it was timed as the back-substitution it happened in).
TEST(FactorReuse, TheFactorisationAFailedGmresSolveFallsBackOnIsTimedAsAFactorisation) {
  LinearSolve s(LinearSolverKind::umfpack, 1e-10, true);
  Timers timers;
  LinearSystem system;
  system.dofs.n_free = kN;
  system.pattern = convection_diffusion(2.5, 0.0, 0.0, 1);
  system.residual = -rhs();
  ASSERT_EQ(solve_free_dofs(s, system, timers), LinearSolveStatus::ok);
  system.pattern = convection_diffusion(2.02, 0.0, 0.0, 1);  // too far for GMRES on the kept factor (test above)
  ASSERT_EQ(solve_free_dofs(s, system, timers), LinearSolveStatus::ok);
  ASSERT_EQ(s.reuse_fallbacks(), 1);
  EXPECT_EQ(s.factorizations(), 2);
  EXPECT_LT(relative_residual(system.pattern, system.increment, rhs()), 1e-13);
  const auto stats = timers.snapshot();
  // Two factorize scopes (the second only defers), the fallback's own scope; the failed GMRES try is a solve.
  EXPECT_EQ(stats.at("newton/solve/factorize").calls, 3);
  EXPECT_EQ(stats.at("newton/solve/back_substitute").calls, 3);
}

}  // namespace loom
