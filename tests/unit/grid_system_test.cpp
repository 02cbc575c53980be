// systems/locate/grid_system: the MPM grid's Newton system spans the active set it was built around and a
// layer of cells beyond it, so that it outlives a move of the body by that layer: the fitted active sets
// keep the pattern (no new symbolic analysis), the ghost faces of a moved boundary find their couplings,
// a move beyond the layer or a halved active set does not fit; and the identity rows of the dormant dofs
// leave the solution on the active dofs what a system of the active set alone gives.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include <random>
#include <set>

#include "engine/mesh/background_grid.hpp"
#include "engine/mesh/generators.hpp"
#include "systems/assemble/grid_scatter.hpp"
#include "systems/locate/ghost_faces.hpp"
#include "systems/locate/grid_system.hpp"
#include "tests/support/grid_stores.hpp"

namespace loom {
namespace {

constexpr int kNx = 12, kNy = 8;

struct Fixture {
  testing::GridStores g;
  BoundaryConditions<2> bc;
  GridActivity act;
  LinearSystem system;
  Fixture() {
    RectangleSpec spec;
    spec.origin = Vec2(0.0, 0.0), spec.size = Vec2(1.2, 0.8), spec.nx = kNx, spec.ny = kNy;
    build_quad_grid(spec, Formulation::p1, g.nodes, g.cells, g.layout);
    bc.per_node = 2;
    bc.target = Eigen::VectorXd::Zero(2 * g.nodes.size());
    for (Index i = 0; i < g.nodes.size(); ++i)  // the left side clamped
      if (g.nodes.X[i].x() < 1e-12) bc.prescribed.push_back({2 * i, i, kNoIndex}), bc.prescribed.push_back({2 * i + 1, i, kNoIndex});
  }
  // The active set: the cells of columns [i0, i1) and rows [j0, j1) (cell c = j * kNx + i).
  void activate(int i0, int i1, int j0, int j1) {
    act.cell_active.assign(std::size_t(g.cells.size()), 0);
    act.active_index.assign(std::size_t(g.cells.size()), kNoIndex);
    act.node_active.assign(std::size_t(g.nodes.size()), 0);
    act.active_cells.clear();
    for (int j = j0; j < j1; ++j)
      for (int i = i0; i < i1; ++i) {
        const Index c = j * kNx + i;
        act.cell_active[std::size_t(c)] = 1;
        act.active_cells.push_back(c);
      }
    std::sort(act.active_cells.begin(), act.active_cells.end());
    for (std::size_t k = 0; k < act.active_cells.size(); ++k) {
      const Index c = act.active_cells[k];
      act.active_index[std::size_t(c)] = Index(k);
      for (int a = 0; a < 4; ++a) act.node_active[std::size_t(g.cells.node(c, a))] = 1;
    }
    find_ghost_faces(g.cells, g.nodes.size(), act);
  }
  // Fits the active set, or builds the system around it: as activate_grid does.
  bool fit_or_build() {
    if (fit_grid_system(true, act, system)) return true;
    act.system_base = act.active_cells;
    build_grid_system(g.cells, bc, true, act, system);
    EXPECT_TRUE(fit_grid_system(true, act, system));
    return false;
  }
};

TEST(GridSystem, SpansTheActiveSetAndOneLayerAroundIt) {
  Fixture f;
  f.activate(3, 7, 2, 5);
  EXPECT_FALSE(f.fit_or_build());
  // Columns 2..7, rows 1..5: the active 4 x 3 block and its layer.
  EXPECT_EQ(f.act.system_cells.size(), 6u * 5u);
  for (Index c = 0; c < f.g.cells.size(); ++c) {
    const int i = int(c % kNx), j = int(c / kNx);
    const bool in = i >= 2 && i < 8 && j >= 1 && j < 6;
    EXPECT_EQ(f.act.scatter_entry[std::size_t(c)] != kNoIndex, in) << "cell " << c;
    if (in) {
      EXPECT_EQ(f.act.system_cells[std::size_t(f.act.scatter_entry[std::size_t(c)])], c);
    }
  }
  // Dormant: the free dofs of the layer's nodes that no active cell holds.
  std::set<Index> expected;
  for (Index c : f.act.system_cells)
    for (int a = 0; a < 4; ++a) {
      const Index n = f.g.cells.node(c, a);
      if (!f.act.node_active[std::size_t(n)]) expected.insert({2 * n, 2 * n + 1});
    }
  EXPECT_EQ(std::set<Index>(f.act.dormant_dofs.begin(), f.act.dormant_dofs.end()), expected);
}

TEST(GridSystem, KeepsItsPatternWhileTheBodyMovesOneLayer) {
  Fixture f;
  f.activate(3, 7, 2, 5);
  f.fit_or_build();
  const auto version = f.system.pattern.version;
  for (auto [i0, i1, j0, j1] : {std::array{4, 8, 2, 5}, std::array{2, 7, 1, 6}, std::array{3, 6, 2, 4}}) {
    f.activate(i0, i1, j0, j1);
    EXPECT_TRUE(f.fit_or_build()) << i0 << " " << i1 << " " << j0 << " " << j1;
    EXPECT_EQ(f.system.pattern.version, version);
    ASSERT_GT(f.act.ghost_faces.size(), 0);
    // Every ghost face's scatter slot addresses its entry.
    const CellScatter& sc = f.system.scatter[1];
    for (Index e = 0; e < f.act.ghost_faces.size(); ++e)
      for (int a = 0; a < sc.dofs_per_cell; ++a)
        for (int b = 0; b < sc.dofs_per_cell; ++b) {
          const Index row = f.system.dofs.equation[std::size_t(sc.cell_dof(e, a))], col = f.system.dofs.equation[std::size_t(sc.cell_dof(e, b))];
          if (row != kNoIndex && col != kNoIndex) {
            ASSERT_EQ(sc.matrix_slot(e, a, b), find_slot(f.system.pattern, row, col));
          }
        }
  }
  f.activate(5, 9, 2, 5);  // two columns beyond the base: outside the layer
  EXPECT_FALSE(f.fit_or_build());
  EXPECT_NE(f.system.pattern.version, version);
  const auto rebuilt = f.system.pattern.version;
  f.activate(5, 6, 2, 5);  // a third of the base: rebuilt around it
  EXPECT_FALSE(f.fit_or_build());
  EXPECT_NE(f.system.pattern.version, rebuilt);
}

// Random symmetric positive definite cell matrices on the active cells, assembled into the padded system
// (dormant rows pinned) and into a system of the active set alone: the same solution on the active dofs.
TEST(GridSystem, DormantRowsLeaveTheSolutionOfTheActiveDofs) {
  Fixture f;
  f.activate(3, 7, 2, 5);
  f.fit_or_build();
  f.activate(4, 7, 2, 4);  // fits: the layer and part of the base are dormant
  ASSERT_TRUE(fit_grid_system(true, f.act, f.system));
  ASSERT_FALSE(f.act.dormant_dofs.empty());
  LinearSystem exact;
  {
    std::vector<DofKind> kinds(std::size_t(2 * f.g.nodes.size()), DofKind::absent);
    for (Index n = 0; n < f.g.nodes.size(); ++n)
      if (f.act.node_active[std::size_t(n)]) kinds[std::size_t(2 * n)] = kinds[std::size_t(2 * n + 1)] = DofKind::free;
    exact.dofs.build(2, kinds);
    build_pattern({&f.g.cells}, exact.dofs, exact.pattern, {&f.act.active_cells});
    exact.scatter.resize(1);
    build_scatter(f.g.cells, exact.dofs, exact.pattern, exact.scatter[0], &f.act.active_cells);
    exact.resize_vectors();
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  for (LinearSystem* s : {&f.system, &exact}) std::fill(s->pattern.matrix.valuePtr(), s->pattern.matrix.valuePtr() + s->pattern.matrix.nonZeros(), 0.0);
  for (std::size_t k = 0; k < f.act.active_cells.size(); ++k) {
    const Index c = f.act.active_cells[k];
    Eigen::Matrix<double, 8, 8> B;
    for (int a = 0; a < 8; ++a)
      for (int b = 0; b < 8; ++b) B(a, b) = d(rng);
    const Eigen::Matrix<double, 8, 8> K = B * B.transpose() + 8.0 * Eigen::Matrix<double, 8, 8>::Identity();
    Eigen::Matrix<double, 8, 1> r;
    for (int a = 0; a < 8; ++a) r[a] = d(rng);
    for (auto [s, entry] : {std::pair{&f.system, f.act.scatter_entry[std::size_t(c)]}, std::pair{&exact, Index(k)}}) {
      Eigen::Matrix<double, 8, 1> rc = r;
      scatter_cell<8>(entry, s->scatter[0], f.bc, f.g.nodes, true, rc, K, *s);
    }
  }
  for (LinearSystem* s : {&f.system, &exact})
    for (Index dof = 0; dof < s->dofs.n_dofs(); ++dof)
      if (s->dofs.equation[std::size_t(dof)] != kNoIndex) s->residual[s->dofs.equation[std::size_t(dof)]] = s->residual_full[dof];
  f.system.residual_full[f.act.dormant_dofs.front()] = 1.0;  // a stray load on a dormant dof is dropped
  pin_dormant_dofs(f.act, true, f.system);
  for (Index dof : f.act.dormant_dofs) {
    EXPECT_EQ(f.system.residual_full[dof], 0.0);
    EXPECT_GT(f.system.pattern.matrix.valuePtr()[f.system.pattern.diagonal_slot[std::size_t(f.system.dofs.equation[std::size_t(dof)])]], 1.0);
  }
  auto solve = [](const LinearSystem& s) {
    Eigen::SimplicialLDLT<SparseMatrix> ldlt(s.pattern.matrix);
    EXPECT_EQ(ldlt.info(), Eigen::Success);
    return Eigen::VectorXd(ldlt.solve(s.residual));
  };
  const Eigen::VectorXd x = solve(f.system), y = solve(exact);
  double worst = 0.0;
  for (Index dof = 0; dof < exact.dofs.n_dofs(); ++dof) {
    const Index e = exact.dofs.equation[std::size_t(dof)], p = f.system.dofs.equation[std::size_t(dof)];
    if (e == kNoIndex) continue;
    ASSERT_NE(p, kNoIndex);
    worst = std::max(worst, std::abs(x[p] - y[e]) / y.cwiseAbs().maxCoeff());
  }
  EXPECT_LE(worst, 1e-13);
  for (Index dof : f.act.dormant_dofs) EXPECT_EQ(x[f.system.dofs.equation[std::size_t(dof)]], 0.0);
}

}  // namespace
}  // namespace loom
