// Linear solves (engine/linalg/linear_solver): CHOLMOD for SPD matrices, UMFPACK for any nonsingular one,
// automatic = CHOLMOD that falls back to UMFPACK for good when a matrix is not positive definite; the
// symbolic analysis is redone only when the pattern version changes; cg (conjugate gradients, diagonal
// preconditioner) reaches its relative-residual tolerance, has no pivots to estimate a condition from, and refuses a
// matrix whose diagonal is not positive; UMFPACK's 64-bit-index path (taken by large 3D systems) solves as the
// 32-bit one does.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "engine/linalg/linear_solver.hpp"

namespace loom {
namespace {

// Tridiagonal n x n: diagonal d(i), off-diagonals -1 (symmetric).
SparsePattern tridiagonal(int n, const std::function<double(int)>& d, std::uint64_t version) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, d(i));
    if (i + 1 < n) t.emplace_back(i, i + 1, -1.0), t.emplace_back(i + 1, i, -1.0);
  }
  SparsePattern p;
  p.matrix.resize(n, n);
  p.matrix.setFromTriplets(t.begin(), t.end());
  p.matrix.makeCompressed();
  p.version = version;
  return p;
}

SparsePattern spd(std::uint64_t version = 1) {  // 1D Laplacian + I: eigenvalues in (1, 5)
  return tridiagonal(6, [](int) { return 3.0; }, version);
}
SparsePattern indefinite(std::uint64_t version = 1) {  // diagonal alternating 3, -3: eigenvalues of both signs
  return tridiagonal(6, [](int i) { return i % 2 ? -3.0 : 3.0; }, version);
}

Eigen::VectorXd known_solution() {
  Eigen::VectorXd x(6);
  x << 1, -2, 3, 0.5, -1, 2;
  return x;
}

// Solves A x = A x_known; returns the error (infinite when the solver reports failure).
double solve_error(LinearSolve& s, const SparsePattern& p) {
  const Eigen::VectorXd x_known = known_solution();
  const Eigen::VectorXd b = p.matrix * x_known;
  if (!s.factorize(p)) return INFINITY;
  Eigen::VectorXd x;
  if (!s.solve(b, x)) return INFINITY;
  return (x - x_known).norm();
}

}  // namespace

TEST(LinearSolve, CholmodSolvesAnSpdSystem) {
  LinearSolve s(LinearSolverKind::cholmod);
  EXPECT_LE(solve_error(s, spd()), 1e-13);
  EXPECT_EQ(s.backend(), "cholmod");
}

TEST(LinearSolve, CholmodReportsAnIndefiniteMatrix) {
  LinearSolve s(LinearSolverKind::cholmod);
  EXPECT_FALSE(s.factorize(indefinite()));
  EXPECT_EQ(s.backend(), "cholmod");
}

TEST(LinearSolve, UmfpackSolvesSpdAndIndefiniteSystems) {
  LinearSolve s(LinearSolverKind::umfpack);
  EXPECT_LE(solve_error(s, spd(1)), 1e-13);
  EXPECT_LE(solve_error(s, indefinite(2)), 1e-13);
  EXPECT_EQ(s.backend(), "umfpack");
}

TEST(LinearSolve, UmfpackReportsASingularMatrix) {
  LinearSolve s(LinearSolverKind::umfpack);
  SparsePattern p = spd();
  for (int k = p.matrix.outerIndexPtr()[2]; k < p.matrix.outerIndexPtr()[3]; ++k) p.matrix.valuePtr()[k] = 0.0;  // zero column
  EXPECT_FALSE(s.factorize(p));
}

TEST(LinearSolve, AutomaticKeepsCholmodForSpd) {
  LinearSolve s(LinearSolverKind::automatic);
  EXPECT_LE(solve_error(s, spd()), 1e-13);
  EXPECT_EQ(s.backend(), "cholmod");
}

TEST(LinearSolve, AutomaticFallsBackToUmfpackForAnIndefiniteMatrix) {
  LinearSolve s(LinearSolverKind::automatic);
  EXPECT_LE(solve_error(s, indefinite()), 1e-13);
  EXPECT_EQ(s.backend(), "umfpack");
  // For good: an SPD matrix later is solved by UMFPACK too.
  EXPECT_LE(solve_error(s, spd(2)), 1e-13);
  EXPECT_EQ(s.backend(), "umfpack");
}

TEST(LinearSolve, AutomaticReportsASingularMatrix) {
  LinearSolve s(LinearSolverKind::automatic);
  SparsePattern p = spd();
  for (int k = p.matrix.outerIndexPtr()[2]; k < p.matrix.outerIndexPtr()[3]; ++k) p.matrix.valuePtr()[k] = 0.0;
  EXPECT_FALSE(s.factorize(p));
}

TEST(LinearSolve, KeepsTheSymbolicAnalysisWhileThePatternIsUnchanged) {
  LinearSolve s(LinearSolverKind::cholmod);
  SparsePattern p = spd(7);
  EXPECT_LE(solve_error(s, p), 1e-13);
  // New values in the same pattern: refactorized, not reanalysed, and the new values are used.
  for (int k = 0; k < p.matrix.nonZeros(); ++k)
    if (p.matrix.innerIndexPtr()[k] == 0 && k < p.matrix.outerIndexPtr()[1]) p.matrix.valuePtr()[k] = 5.0;
  EXPECT_LE(solve_error(s, p), 1e-13);
  EXPECT_EQ(s.analyses(), 1);
  EXPECT_EQ(s.factorizations(), 2);
  p.version = 8;  // a new pattern
  EXPECT_LE(solve_error(s, p), 1e-13);
  EXPECT_EQ(s.analyses(), 2);
}

}  // namespace loom

namespace loom {
namespace {

// A singular matrix: UMFPACK reports it (zero pivot) and says so; CHOLMOD cannot factorize it either.
TEST(LinearSolve, ASingularMatrixFailsWithAMessageThatSaysSo) {
  const SparsePattern p = tridiagonal(6, [](int i) { return i == 0 || i == 5 ? 1.0 : 2.0; }, 1);  // Laplacian, free ends: null space 1
  LinearSolve u(LinearSolverKind::umfpack);
  EXPECT_FALSE(u.factorize(p));
  EXPECT_NE(u.failure().find("singular"), std::string::npos) << u.failure();
  EXPECT_EQ(u.min_rcond(), 0.0);
  LinearSolve c(LinearSolverKind::cholmod);
  EXPECT_FALSE(c.factorize(p));
  EXPECT_NE(c.failure().find("not positive definite, or singular"), std::string::npos) << c.failure();
}

// Singular up to round-off (the free-ends Laplacian plus 1e-14 on the diagonal: its smallest eigenvalue): the factorization goes
// through, and the pivot ratio says what it is; a regular matrix's ratio is far above the threshold.
TEST(LinearSolve, ThePivotRatioTellsANearlySingularMatrixFromARegularOne) {
  for (auto kind : {LinearSolverKind::umfpack, LinearSolverKind::cholmod}) {
    LinearSolve s(kind);
    s.reset_condition();
    ASSERT_TRUE(s.factorize(tridiagonal(6, [](int i) { return (i == 0 || i == 5 ? 1.0 : 2.0) + 1e-14; }, 1))) << s.backend();
    EXPECT_LT(s.min_rcond(), LinearSolve::kNearlySingular) << s.backend();
    s.reset_condition();
    ASSERT_TRUE(s.factorize(spd(2)));
    EXPECT_GT(s.min_rcond(), 0.1) << s.backend();  // eigenvalues in (1, 5)
  }
}

// A 1D Laplacian + 0.01 I of 200 unknowns (condition ~400): CG needs many iterations, and its error follows its
// tolerance.
TEST(LinearSolve, ConjugateGradientsReachTheirTolerance) {
  const SparsePattern p = tridiagonal(200, [](int) { return 2.01; }, 1);
  Eigen::VectorXd x_known(200);
  for (int i = 0; i < 200; ++i) x_known[i] = std::sin(0.1 * i) + 0.01 * i;
  const Eigen::VectorXd b = p.matrix * x_known;
  for (double tolerance : {1e-6, 1e-12}) {
    LinearSolve s(LinearSolverKind::cg, tolerance);
    s.reset_condition();
    ASSERT_TRUE(s.factorize(p));
    Eigen::VectorXd x;
    ASSERT_TRUE(s.solve(b, x));
    EXPECT_LE((p.matrix * x - b).norm(), tolerance * b.norm());
    EXPECT_GT((p.matrix * x - b).norm(), 1e-4 * tolerance * b.norm());  // it stops near the tolerance, not at round-off
    EXPECT_EQ(s.backend(), "cg");
    EXPECT_EQ(s.min_rcond(), INFINITY);  // no estimate, so never "nearly singular"
  }
}

TEST(LinearSolve, ConjugateGradientsRefuseANonPositiveDiagonal) {
  LinearSolve s(LinearSolverKind::cg);
  EXPECT_FALSE(s.factorize(indefinite()));
  EXPECT_NE(s.failure().find("not positive definite"), std::string::npos) << s.failure();
}

// The path with 64-bit indices, forced (wide_above = 0), against the default int path, on an unsymmetric matrix.
TEST(LinearSolve, UmfpackWithWideIndicesSolvesAsTheIntVersion) {
  SparsePattern p = tridiagonal(50, [](int i) { return 3.0 + 0.1 * i; }, 1);
  for (int j = 0; j < p.matrix.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(p.matrix, j); it; ++it)
      if (it.row() > it.col()) it.valueRef() = -0.5;  // unsymmetric
  Eigen::VectorXd b(50);
  for (int i = 0; i < 50; ++i) b[i] = std::cos(0.3 * i);
  Eigen::VectorXd x_int, x_wide;
  auto narrow = make_umfpack_solver(), wide = make_umfpack_solver(0.0);
  narrow->analyze(p.matrix), wide->analyze(p.matrix);
  ASSERT_TRUE(narrow->factorize(p.matrix) && wide->factorize(p.matrix));
  ASSERT_TRUE(narrow->solve(b, x_int) && wide->solve(b, x_wide));
  EXPECT_LE((p.matrix * x_wide - b).norm(), 1e-14 * b.norm());
  EXPECT_LE((x_wide - x_int).norm(), 1e-15 * x_int.norm());
  EXPECT_EQ(wide->factor_size().entries, narrow->factor_size().entries);
  EXPECT_DOUBLE_EQ(wide->rcond(), narrow->rcond());
  // New values on the same pattern: the wide copy follows them.
  for (int j = 0; j < p.matrix.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(p.matrix, j); it; ++it) it.valueRef() *= 2.0;
  ASSERT_TRUE(wide->factorize(p.matrix) && wide->solve(b, x_wide));
  EXPECT_LE((x_wide - 0.5 * x_int).norm(), 1e-15 * x_int.norm());
}

}  // namespace
}  // namespace loom
