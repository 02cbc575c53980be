// The whole-node layout of the PETSc back-end (engine/linalg/whole_node_layout.hpp): on a matrix of loom's free
// equations with prescribed and absent dofs, the rows are whole nodes (block size = dofs per node) in node order,
// nodes without a free dof are left out, eliminated dofs are decoupled diagonal rows, the CSR holds loom's matrix
// exactly (an unsymmetric one too), and the transpose map tells a symmetric matrix from an unsymmetric one.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "engine/linalg/whole_node_layout.hpp"

namespace loom {
namespace {

// Four nodes, three dofs each (u_x, u_y, p): node 0 all prescribed, node 1's u_y prescribed, node 2's p absent,
// node 3 free. Free equations: node 1: 2, node 2: 2, node 3: 3 (7).
SolveStructure structure() {
  SolveStructure s;
  s.dim = 2;
  std::vector<DofKind> kinds(12, DofKind::free);
  kinds[0] = kinds[1] = kinds[2] = DofKind::prescribed;
  kinds[4] = DofKind::prescribed;
  kinds[8] = DofKind::absent;
  s.dofs.build(3, kinds);
  s.coordinates = {0, 0, 1, 0, 0, 1, 1, 1};
  return s;
}

// A dense 7 x 7 matrix with a(i, j) = 10 i + j + 1 (unsymmetric), or its symmetric part.
SparseMatrix matrix(bool symmetric) {
  Eigen::MatrixXd dense(7, 7);
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 7; ++j) dense(i, j) = symmetric ? double(10 * (i + j) + 2) : double(10 * i + j + 1);
  SparseMatrix A = dense.sparseView();
  A.makeCompressed();
  return A;
}

TEST(WholeNodeLayout, RowsAreWholeNodesWithTheEliminatedDofsDecoupled) {
  const SparseMatrix A = matrix(false);
  const WholeNodeLayout l = whole_node_layout(A, structure());
  EXPECT_TRUE(l.whole_nodes);
  EXPECT_EQ(l.block_size, 3);
  EXPECT_EQ(l.rows, 9);  // nodes 1, 2, 3
  EXPECT_EQ(l.node_of_row_block, (std::vector<Index>{1, 2, 3}));
  EXPECT_EQ(l.row_of_equation, (std::vector<int>{0, 2, 3, 4, 6, 7, 8}));
  EXPECT_EQ(l.decoupled_slots.size(), 2u);  // node 1's u_y (row 1), node 2's p (row 5)
  // The CSR reproduces A on the rows of the free equations and the decoupled diagonal elsewhere.
  std::vector<double> values(l.columns.size(), 0.0);
  copy_values(A, l, -5.0, values.data());
  Eigen::MatrixXd csr = Eigen::MatrixXd::Zero(9, 9);
  for (int r = 0; r < 9; ++r) {
    for (int s = l.offsets[std::size_t(r)]; s < l.offsets[std::size_t(r) + 1]; ++s) {
      csr(r, l.columns[std::size_t(s)]) = values[std::size_t(s)];
      if (s > l.offsets[std::size_t(r)]) {
        EXPECT_LT(l.columns[std::size_t(s) - 1], l.columns[std::size_t(s)]);
      }
    }
  }
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 7; ++j) EXPECT_EQ(csr(l.row_of_equation[std::size_t(i)], l.row_of_equation[std::size_t(j)]), A.coeff(i, j));
  EXPECT_EQ(csr(1, 1), -5.0);
  EXPECT_EQ(csr(5, 5), -5.0);
  EXPECT_EQ(csr.row(1).cwiseAbs().sum(), 5.0);
  EXPECT_EQ(csr.col(5).cwiseAbs().sum(), 5.0);
}

TEST(WholeNodeLayout, TheTransposeMapTellsASymmetricMatrix) {
  const SparseMatrix unsymmetric = matrix(false), symmetric = matrix(true);
  const WholeNodeLayout l = whole_node_layout(unsymmetric, structure());
  EXPECT_FALSE(is_symmetric(unsymmetric, l.transpose, 1e-12));
  EXPECT_TRUE(is_symmetric(symmetric, whole_node_layout(symmetric, structure()).transpose, 1e-12));
}

TEST(WholeNodeLayout, WithoutAFittingStructureTheRowsAreTheEquations) {
  const SparseMatrix A = matrix(false);
  const WholeNodeLayout l = whole_node_layout(A, SolveStructure{});
  EXPECT_FALSE(l.whole_nodes);
  EXPECT_EQ(l.block_size, 1);
  EXPECT_EQ(l.rows, 7);
  EXPECT_TRUE(l.decoupled_slots.empty());
  EXPECT_EQ(l.columns.size(), 49u);
}

// Every rank count splits the rows into contiguous ranges of whole blocks that cover them once, each holding at most
// its share of the entries plus one block's.
void expect_balanced_split(const WholeNodeLayout& l, int ranks) {
  const std::vector<int> first = rows_of_ranks(l, ranks);
  ASSERT_EQ(first.size(), std::size_t(ranks) + 1);
  EXPECT_EQ(first.front(), 0);
  EXPECT_EQ(first.back(), l.rows);
  int widest_block = 0;
  for (int b = 0; b < l.rows; b += l.block_size)
    widest_block = std::max(widest_block, l.offsets[std::size_t(b + l.block_size)] - l.offsets[std::size_t(b)]);
  for (int r = 0; r < ranks; ++r) {
    EXPECT_LE(first[std::size_t(r)], first[std::size_t(r) + 1]) << ranks;
    EXPECT_EQ(first[std::size_t(r)] % l.block_size, 0) << ranks;
    const double mine = l.offsets[std::size_t(first[std::size_t(r) + 1])] - l.offsets[std::size_t(first[std::size_t(r)])];
    EXPECT_LE(mine, double(l.offsets.back()) / ranks + widest_block) << ranks << " ranks, rank " << r;
  }
}

TEST(WholeNodeLayout, RanksOwnContiguousWholeBlocksBalancedByEntries) {
  const WholeNodeLayout blocks = whole_node_layout(matrix(false), structure());
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < 101; ++i)  // a banded matrix whose rows hold 1 to 9 entries
    for (int j = std::max(0, i - i % 5); j <= std::min(100, i + i % 5); ++j) t.emplace_back(i, j, 1.0);
  SparseMatrix banded(101, 101);
  banded.setFromTriplets(t.begin(), t.end());
  banded.makeCompressed();
  const WholeNodeLayout rows = whole_node_layout(banded, SolveStructure{});
  for (int ranks = 1; ranks <= 8; ++ranks) {
    expect_balanced_split(blocks, ranks);
    expect_balanced_split(rows, ranks);
  }
  EXPECT_EQ(rows_of_ranks(rows, 1), (std::vector<int>{0, 101}));
}

}  // namespace
}  // namespace loom
