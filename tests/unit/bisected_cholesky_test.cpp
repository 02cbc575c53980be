// The bisected CHOLMOD back-end (engine/linalg/bisected_cholesky): on a 2D-mesh-like SPD matrix it splits into
// two halves and a small separator and solves as the unsplit CHOLMOD does (to round-off), also after new values
// on the same pattern and after a new pattern; its result does not depend on the thread count, bit for bit; a
// matrix that is not positive definite is refused, whether a half or only the separator's Schur complement
// shows it; tiny matrices (no useful bisection) still solve.
#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <Eigen/Eigenvalues>
#include <vector>

#include "engine/linalg/bisected_cholesky.hpp"
#include "engine/linalg/linear_solver.hpp"

namespace loom {
namespace {

// Two dofs per node of an nx x ny lattice: the 5-point Laplacian (x) [[2, 1], [1, 2]], plus shift * I: SPD for
// shift > -lambda_min, like a plane elastic stiffness with a mass term.
SparsePattern lattice(int nx, int ny, double shift, std::uint64_t version = 1) {
  std::vector<Eigen::Triplet<double>> t;
  auto node = [&](int i, int j) { return i + nx * j; };
  const double block[2][2] = {{2.0, 1.0}, {1.0, 2.0}};
  auto add = [&](int a, int b, double w) {
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) t.emplace_back(2 * a + r, 2 * b + c, w * block[r][c]);
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = node(i, j);
      add(a, a, 4.0);
      if (i + 1 < nx) add(a, node(i + 1, j), -1.0), add(node(i + 1, j), a, -1.0);
      if (j + 1 < ny) add(a, node(i, j + 1), -1.0), add(node(i, j + 1), a, -1.0);
    }
  const int n = 2 * nx * ny;
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, shift);
  SparsePattern p;
  p.matrix.resize(n, n);
  p.matrix.setFromTriplets(t.begin(), t.end());
  p.matrix.makeCompressed();
  p.version = version;
  return p;
}

Eigen::VectorXd solve_with(LinearSolverKind kind, const SparsePattern& p, const Eigen::VectorXd& b) {
  LinearSolve s(kind);
  EXPECT_TRUE(s.factorize(p)) << s.failure();
  Eigen::VectorXd x;
  EXPECT_TRUE(s.solve(b, x)) << s.failure();
  return x;
}

}  // namespace

TEST(BisectedCholesky, SplitsALatticeAndSolvesAsCholmodDoes) {
  const SparsePattern p = lattice(60, 40, 0.01);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(p.matrix.rows(), -1.0, 2.0).array().sin();
  auto solver = make_bisected_cholmod_solver();
  solver->analyze(p.matrix);
  const auto [n0, n1, k] = bisected_cholmod_split(*solver);
  EXPECT_EQ(n0 + n1 + k, p.matrix.rows());
  EXPECT_GT(std::min(n0, n1), p.matrix.rows() / 3);  // balanced
  EXPECT_GT(k, 0);
  EXPECT_LE(k, 2 * 2 * 41);  // a separator across the lattice: about one line of nodes
  const Eigen::VectorXd x_ref = solve_with(LinearSolverKind::cholmod, p, b);
  const Eigen::VectorXd x = solve_with(LinearSolverKind::cholmod_bisected, p, b);
  EXPECT_LE((x - x_ref).norm(), 1e-11 * x_ref.norm());
  EXPECT_LE((p.matrix * x - b).norm(), 1e-11 * b.norm());
  std::printf("[bisected cholesky] n = %d: halves %d + %d, separator %d; |x - x_cholmod| / |x| = %.1e\n", int(p.matrix.rows()), n0, n1, k,
              (x - x_ref).norm() / x_ref.norm());
}

TEST(BisectedCholesky, RefactorisesNewValuesAndReanalysesANewPattern) {
  LinearSolve s(LinearSolverKind::cholmod_bisected);
  for (const auto& [nx, shift, version] : std::vector<std::tuple<int, double, int>>{{30, 0.5, 1}, {30, 2.0, 1}, {34, 0.1, 2}}) {
    const SparsePattern p = lattice(nx, 20, shift, std::uint64_t(version));
    const Eigen::VectorXd x_known = Eigen::VectorXd::LinSpaced(p.matrix.rows(), 1.0, -3.0);
    ASSERT_TRUE(s.factorize(p)) << s.failure();
    Eigen::VectorXd x;
    ASSERT_TRUE(s.solve(p.matrix * x_known, x));
    EXPECT_LE((x - x_known).norm(), 1e-11 * x_known.norm()) << nx << " " << shift;
  }
  EXPECT_EQ(s.analyses(), 2);
  EXPECT_EQ(s.backend(), "cholmod_bisected");
}

TEST(BisectedCholesky, DoesNotDependOnTheThreadCount) {
  // Bit for bit, over repeated runs. The halves were once ordered by METIS at once on two threads: METIS draws
  // from the C library's one rand() state, their draws interleaved as the scheduler chose, and under load 10 of
  // 20 two-thread solves differed from the one-thread solve in round-off.
  const SparsePattern p = lattice(50, 50, 0.02);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(p.matrix.rows(), 0.0, 5.0).array().cos();
  Eigen::VectorXd one;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = solve_with(LinearSolverKind::cholmod_bisected, p, b);
  }
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  int differing = 0;
  for (int run = 0; run < 20; ++run) differing += solve_with(LinearSolverKind::cholmod_bisected, p, b) != one;
  EXPECT_EQ(differing, 0) << "of 20 two-thread solves";
}

TEST(BisectedCholesky, RefusesAMatrixThatIsNotPositiveDefinite) {
  // Shifted between the two lowest eigenvalues: one negative eigenvalue, of a smooth (global) mode that the
  // halves, stiffer as principal submatrices, may not see; the Schur complement then must.
  const SparsePattern base = lattice(16, 12, 0.0);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Eigen::MatrixXd(base.matrix), Eigen::EigenvaluesOnly);
  const double l0 = eig.eigenvalues()[0], l1 = eig.eigenvalues()[1];
  ASSERT_LT(l0, l1);
  const SparsePattern p = lattice(16, 12, -0.5 * (l0 + l1));
  LinearSolve s(LinearSolverKind::cholmod_bisected);
  EXPECT_FALSE(s.factorize(p));
  EXPECT_NE(s.failure().find("not positive definite"), std::string::npos) << s.failure();
  // A negative diagonal entry inside a half.
  SparsePattern q = lattice(16, 12, 0.5);
  q.matrix.coeffRef(0, 0) = -1.0;
  LinearSolve s2(LinearSolverKind::cholmod_bisected);
  EXPECT_FALSE(s2.factorize(q));
}

TEST(BisectedCholesky, SolvesMatricesTooSmallToSplit) {
  for (int nx : {1, 2, 3}) {
    const SparsePattern p = lattice(nx, 1, 1.0);
    const Eigen::VectorXd x_known = Eigen::VectorXd::LinSpaced(p.matrix.rows(), 1.0, 2.0);
    LinearSolve s(LinearSolverKind::cholmod_bisected);
    ASSERT_TRUE(s.factorize(p)) << nx;
    Eigen::VectorXd x;
    ASSERT_TRUE(s.solve(p.matrix * x_known, x));
    EXPECT_LE((x - x_known).norm(), 1e-13 * x_known.norm()) << nx;
  }
}

}  // namespace loom
