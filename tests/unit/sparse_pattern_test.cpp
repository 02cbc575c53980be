// Sparsity pattern and cell scatters (engine/linalg/sparse_pattern): the pattern holds exactly the
// couplings of the cells' free dofs, is symmetric, knows its diagonal slots, and every scatter slot
// addresses the (row, column) it claims, so assembling through slots equals a dense assembly.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <utility>

#include "engine/core/parallel.hpp"
#include "engine/linalg/sparse_pattern.hpp"
#include "engine/mesh/generators.hpp"

namespace loom {
namespace {

using K = DofKind;

// 3 --- 4 --- 5
// |   / |   / |    2 x 1 grid, right pattern: cells {0,1,4}, {0,4,3}, {1,2,5}, {1,5,4}; node 0 clamped,
// | /   | /   |    node 3 x prescribed, node 5 y absent.
// 0 --- 1 --- 2
struct Fixture {
  Cells cells;
  DofMap dofs;
  Fixture() {
    RectangleSpec spec;
    spec.nx = 2, spec.ny = 1;
    const MeshData m = generate_rectangle(spec);
    cells.nodes.values() = m.triangles;
    cells.body.assign(m.n_triangles(), 0);
    std::vector<K> kinds(12, K::free);
    kinds[0] = kinds[1] = K::prescribed;
    kinds[6] = K::prescribed;
    kinds[11] = K::absent;
    dofs.build(2, kinds);
  }
};

std::set<std::pair<Index, Index>> expected_couplings(const std::vector<const Cells*>& blocks, const DofMap& dofs) {
  std::set<std::pair<Index, Index>> s;
  for (const Cells* cells : blocks)
    for (Index c = 0; c < cells->size(); ++c)
      for (int a = 0; a < cells->stride; ++a)
        for (int b = 0; b < cells->stride; ++b)
          for (int i = 0; i < dofs.per_node; ++i)
            for (int j = 0; j < dofs.per_node; ++j) {
              const Index row = dofs.equation[std::size_t(dofs.dof(cells->node(c, a), i))];
              const Index col = dofs.equation[std::size_t(dofs.dof(cells->node(c, b), j))];
              if (row != kNoIndex && col != kNoIndex) s.insert({row, col});
            }
  return s;
}

std::set<std::pair<Index, Index>> pattern_entries(const SparseMatrix& A) {
  std::set<std::pair<Index, Index>> s;
  for (int j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) s.insert({Index(it.row()), Index(it.col())});
  return s;
}

}  // namespace

TEST(BuildPattern, HoldsExactlyTheCouplingsOfTheCells) {
  Fixture f;
  SparsePattern p;
  build_pattern({&f.cells}, f.dofs, p);
  EXPECT_EQ(p.matrix.rows(), f.dofs.n_free);
  EXPECT_EQ(p.matrix.cols(), f.dofs.n_free);
  EXPECT_EQ(f.dofs.n_free, 12 - 4);
  EXPECT_TRUE(p.matrix.isCompressed());
  const auto entries = pattern_entries(p.matrix);
  EXPECT_EQ(entries, expected_couplings({&f.cells}, f.dofs));
  for (const auto& [r, c] : entries) EXPECT_TRUE(entries.count({c, r})) << "not symmetric at " << r << ", " << c;
  // Nodes 2 and 4 share no cell.
  EXPECT_FALSE(entries.count({f.dofs.equation[8], f.dofs.equation[4]}));
}

TEST(BuildPattern, DiagonalSlotsAddressTheDiagonal) {
  Fixture f;
  SparsePattern p;
  build_pattern({&f.cells}, f.dofs, p);
  ASSERT_EQ(Index(p.diagonal_slot.size()), f.dofs.n_free);
  const SparseMatrix& A = p.matrix;
  for (Index j = 0; j < f.dofs.n_free; ++j) {
    const Index s = p.diagonal_slot[std::size_t(j)];
    EXPECT_GE(s, A.outerIndexPtr()[j]);
    EXPECT_LT(s, A.outerIndexPtr()[j + 1]);
    EXPECT_EQ(A.innerIndexPtr()[s], j);
  }
}

TEST(BuildPattern, UnitesTheCouplingsOfSeveralBlocks) {
  Fixture f;
  Cells extra;
  extra.nodes.values() = {2, 4, 5};  // couples node 2 with node 4, which no cell of the grid does
  extra.body.assign(1, 0);
  SparsePattern p;
  build_pattern({&f.cells, &extra}, f.dofs, p);
  EXPECT_EQ(pattern_entries(p.matrix), expected_couplings({&f.cells, &extra}, f.dofs));
  EXPECT_TRUE(pattern_entries(p.matrix).count({f.dofs.equation[8], f.dofs.equation[4]}));
}

TEST(BuildPattern, EveryBuildGetsANewVersion) {
  Fixture f;
  SparsePattern a, b;
  build_pattern({&f.cells}, f.dofs, a);
  build_pattern({&f.cells}, f.dofs, b);
  EXPECT_NE(a.version, 0u);
  EXPECT_NE(a.version, b.version);
}

TEST(BuildScatter, SlotsAddressTheRowAndColumnTheyClaim) {
  Fixture f;
  SparsePattern p;
  build_pattern({&f.cells}, f.dofs, p);
  CellScatter sc;
  build_scatter(f.cells, f.dofs, p, sc);
  const int nd = 6;
  ASSERT_EQ(sc.dofs_per_cell, nd);
  const SparseMatrix& A = p.matrix;
  for (Index c = 0; c < f.cells.size(); ++c)
    for (int a = 0; a < nd; ++a) {
      const Index dof_a = sc.cell_dof(c, a);
      EXPECT_EQ(dof_a, 2 * f.cells.node(c, a / 2) + a % 2);
      for (int b = 0; b < nd; ++b) {
        const Index row = f.dofs.equation[std::size_t(dof_a)];
        const Index col = f.dofs.equation[std::size_t(sc.cell_dof(c, b))];
        const Index s = sc.matrix_slot(c, a, b);
        if (row == kNoIndex || col == kNoIndex) {
          EXPECT_EQ(s, kNoIndex);
          continue;
        }
        ASSERT_NE(s, kNoIndex);
        EXPECT_GE(s, A.outerIndexPtr()[col]);
        EXPECT_LT(s, A.outerIndexPtr()[col + 1]);
        EXPECT_EQ(A.innerIndexPtr()[s], row);
      }
    }
}

TEST(BuildScatter, AssemblyThroughSlotsEqualsDenseAssembly) {
  Fixture f;
  SparsePattern p;
  build_pattern({&f.cells}, f.dofs, p);
  CellScatter sc;
  build_scatter(f.cells, f.dofs, p, sc);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-1, 1);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(f.dofs.n_free, f.dofs.n_free);
  for (Index c = 0; c < f.cells.size(); ++c) {
    Eigen::Matrix<double, 6, 6> Ke;
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) Ke(a, b) = d(rng);  // unsymmetric on purpose: rows and columns must not swap
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) {
        const Index s = sc.matrix_slot(c, a, b);
        if (s != kNoIndex) p.matrix.valuePtr()[s] += Ke(a, b);
        const Index row = f.dofs.equation[std::size_t(sc.cell_dof(c, a))];
        const Index col = f.dofs.equation[std::size_t(sc.cell_dof(c, b))];
        if (row != kNoIndex && col != kNoIndex) dense(row, col) += Ke(a, b);
      }
  }
  EXPECT_LE((Eigen::MatrixXd(p.matrix) - dense).norm(), 1e-14);
}

// A grid large enough for the parallel scatter, three dofs per node (u, p) with random kinds and a subset of
// the cells, as an MPM grid's active part: every slot addresses its row and column.
TEST(BuildScatter, SlotsOfAMixedSubsetGridAddressTheirEntries) {
  RectangleSpec spec;
  spec.nx = 30, spec.ny = 20;
  const MeshData m = generate_rectangle(spec);
  Cells cells;
  cells.nodes.values() = m.triangles;
  cells.body.assign(m.n_triangles(), 0);
  std::mt19937 rng(11);
  std::vector<Index> subset;
  for (Index c = 0; c < cells.size(); ++c)
    if (rng() % 4 != 0) subset.push_back(c);
  std::vector<char> used(std::size_t(Index(m.X.size())), 0);
  for (Index c : subset)
    for (int a = 0; a < 3; ++a) used[std::size_t(cells.node(c, a))] = 1;
  std::vector<K> kinds(std::size_t(3 * Index(m.X.size())), K::absent);
  for (Index i = 0; i < Index(m.X.size()); ++i)
    for (int d = 0; d < 3; ++d)
      if (used[std::size_t(i)]) kinds[std::size_t(3 * i + d)] = rng() % 5 == 0 ? K::prescribed : K::free;
  DofMap dofs;
  dofs.build(3, kinds);
  SparsePattern p;
  build_pattern({&cells}, dofs, p, {&subset});
  CellScatter sc;
  build_scatter(cells, dofs, p, sc, &subset);
  ASSERT_GT(Index(subset.size()), 2 * kParallelGrain);
  for (Index e = 0; e < Index(subset.size()); ++e)
    for (int a = 0; a < 9; ++a) {
      ASSERT_EQ(sc.cell_dof(e, a), 3 * cells.node(subset[std::size_t(e)], a / 3) + a % 3);
      for (int b = 0; b < 9; ++b) {
        const Index row = dofs.equation[std::size_t(sc.cell_dof(e, a))];
        const Index col = dofs.equation[std::size_t(sc.cell_dof(e, b))];
        const Index s = sc.matrix_slot(e, a, b);
        if (row == kNoIndex || col == kNoIndex) {
          ASSERT_EQ(s, kNoIndex);
          continue;
        }
        ASSERT_EQ(s, find_slot(p, row, col)) << "cell entry " << e << ", " << a << ", " << b;
      }
    }
}

}  // namespace loom
