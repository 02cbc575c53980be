// The CHOLMOD back-end stores the matrix as the lower triangle in the factor's order (engine/linalg/cholmod_lower.hpp)
// and must factorise and solve exactly as CHOLMOD given the upper triangle with its own ordering (what Eigen's
// CholmodSupernodalLLT<Upper> hands it, and what loom did before): the same solution bit for bit, the same factor
// size, the upper triangle read where the matrix is not symmetric; and a system with no unknowns solves.
#include <gtest/gtest.h>

#include <Eigen/CholmodSupport>
#include <vector>

#include "engine/linalg/cholmod_lower.hpp"
#include "engine/linalg/linear_solver.hpp"

namespace loom {
namespace {

// A 2D elasticity-like pattern: n x n nodes, 2 dofs a node, each node coupled to its 8 neighbours; SPD values that
// vary from entry to entry (a weighted graph Laplacian plus a diagonal shift), so that round-off differences show.
// `skew` is added to the strictly lower entries only (an unsymmetric matrix whose upper triangle is the SPD one).
SparseMatrix lattice(int n, double skew = 0.0) {
  const int dofs = 2 * n * n;
  std::vector<Eigen::Triplet<double>> t;
  std::vector<double> diagonal(std::size_t(dofs), 0.0);
  auto node = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int di = 0; di <= 1; ++di)
        for (int dj = -1; dj <= 1; ++dj) {
          if (di == 0 && dj <= 0) continue;
          const int i2 = i + di, j2 = j + dj;
          if (i2 >= n || j2 < 0 || j2 >= n) continue;
          const int a = node(i, j), b = node(i2, j2);
          for (int p = 0; p < 2; ++p)
            for (int q = 0; q < 2; ++q) {
              const int r = 2 * a + p, c = 2 * b + q;
              const double w = 0.1 + 0.37 * std::sin(0.7 * r + 1.3 * c) * std::sin(0.7 * r + 1.3 * c);
              t.emplace_back(std::min(r, c), std::max(r, c), -w);
              t.emplace_back(std::max(r, c), std::min(r, c), -w + skew);
              diagonal[std::size_t(r)] += w, diagonal[std::size_t(c)] += w;
            }
        }
  for (int r = 0; r < dofs; ++r) t.emplace_back(r, r, diagonal[std::size_t(r)] + 0.01 * (1 + r % 7));
  SparseMatrix A(dofs, dofs);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

Eigen::VectorXd rhs(int n) {
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::cos(0.1 * i) + 0.01 * i;
  return b;
}

// CHOLMOD through Eigen with the upper triangle and the back-end's supernode settings.
struct Reference {
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Upper> llt;
  explicit Reference(const SparseMatrix& A) {
    set_relaxed_supernodes(llt.cholmod());
    llt.compute(A);
  }
};

}  // namespace

TEST(CholmodPermuted, SolvesBitForBitAsCholmodGivenTheUpperTriangleAndItsOrdering) {
  const SparseMatrix A = lattice(30);
  Reference ref(A);
  ASSERT_EQ(ref.llt.info(), Eigen::Success);
  const Eigen::VectorXd b = rhs(int(A.rows()));
  const Eigen::VectorXd x_ref = ref.llt.solve(b);
  auto solver = make_cholmod_solver();
  solver->analyze(A);
  ASSERT_TRUE(solver->factorize(A));
  Eigen::VectorXd x;
  ASSERT_TRUE(solver->solve(b, x));
  EXPECT_LT((A.selfadjointView<Eigen::Upper>() * x - b).norm(), 1e-10 * b.norm());
  for (Eigen::Index i = 0; i < x.size(); ++i) ASSERT_EQ(x[i], x_ref[i]) << "dof " << i;
  EXPECT_EQ(solver->factor_size().entries, ref.llt.cholmod().lnz);
  EXPECT_EQ(solver->factor_size().flops, ref.llt.cholmod().fl);
  // Refactorised with other values on the same pattern: still the same.
  SparseMatrix B = A;
  for (Eigen::Index k = 0; k < B.nonZeros(); ++k) B.valuePtr()[k] *= 1.0 + 0.1 * std::sin(double(k));
  for (Eigen::Index r = 0; r < B.rows(); ++r) B.coeffRef(r, r) += 1.0;  // keeps it diagonally dominant
  Reference ref_b(B);
  ASSERT_TRUE(solver->factorize(B));
  ASSERT_TRUE(solver->solve(b, x));
  const Eigen::VectorXd y_ref = ref_b.llt.solve(b);
  for (Eigen::Index i = 0; i < x.size(); ++i) ASSERT_EQ(x[i], y_ref[i]) << "dof " << i;
}

TEST(CholmodPermuted, ReadsTheUpperTriangleOfAnUnsymmetricMatrix) {
  const SparseMatrix A = lattice(12, 0.05);  // lower triangle off by 0.05
  Reference ref(A);
  const Eigen::VectorXd b = rhs(int(A.rows()));
  auto solver = make_cholmod_solver();
  solver->analyze(A);
  ASSERT_TRUE(solver->factorize(A));
  Eigen::VectorXd x;
  ASSERT_TRUE(solver->solve(b, x));
  const Eigen::VectorXd x_ref = ref.llt.solve(b);
  for (Eigen::Index i = 0; i < x.size(); ++i) ASSERT_EQ(x[i], x_ref[i]) << "dof " << i;
}

TEST(CholmodPermuted, AnIndefiniteMatrixFailsAndASystemWithoutUnknownsSolves) {
  SparseMatrix A = lattice(5);
  A.coeffRef(7, 7) = -50.0;
  auto solver = make_cholmod_solver();
  solver->analyze(A);
  EXPECT_FALSE(solver->factorize(A));
  SparseMatrix empty(0, 0);
  empty.makeCompressed();
  solver->analyze(empty);
  EXPECT_TRUE(solver->factorize(empty));
  Eigen::VectorXd x;
  EXPECT_TRUE(solver->solve(Eigen::VectorXd(0), x));
  EXPECT_EQ(x.size(), 0);
}

}  // namespace loom
