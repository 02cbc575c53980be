// systems/assemble/elements/ghost_face: the face ghost penalty of the MPM grid (grid.ghost_penalty).
// The jump coefficients give the jump of the normal derivative: zero for any linear field (both cell types),
// the slope change for a field with a kink along the face; the penalty matrix is symmetric positive
// semi-definite, vanishes on linear fields, and has the documented scale (gamma_0 mu h times h times the
// squared jump); the faces listed for an active set are the sides between active cells next to inactive ones.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "engine/mesh/background_grid.hpp"
#include "engine/mesh/generators.hpp"
#include "systems/assemble/elements/ghost_face.hpp"
#include "systems/locate/ghost_faces.hpp"
#include "tests/support/grid_stores.hpp"

namespace loom {
namespace {

using Grid = testing::GridStores;

Grid make_grid(bool quad) {
  RectangleSpec spec;
  spec.origin = Vec2(0.0, 0.0), spec.size = Vec2(1.0, 0.6), spec.nx = 5, spec.ny = 3;
  Grid g;
  if (quad) build_quad_grid(spec, Formulation::p1, g.nodes, g.cells, g.layout);
  else build_background_grid(generate_rectangle(spec), &spec, Formulation::p1, g.nodes, g.cells, g.layout);
  return g;
}

// The two cells across side `a` of cell c.
template <int NC>
GhostFace<NC> face_of(const Grid& g, Index c, int a) {
  const Index n = g.cells.neighbour[std::size_t(g.cells.sides()) * std::size_t(c) + std::size_t(a)];
  EXPECT_NE(n, kNoIndex);
  const auto [i, j] = g.cells.side_corners(c, a);
  return ghost_face<NC>(g.cells, g.nodes, c, n, i, j);
}

template <int NC>
void check_faces(const Grid& g) {
  constexpr int NF = 2 * NC - 2;
  const double mu = 3.0, gamma_0 = 0.2;
  int checked = 0;
  for (Index c = 0; c < g.cells.size(); ++c)
    for (int a = 0; a < g.cells.sides(); ++a) {
      if (g.cells.neighbour[std::size_t(g.cells.sides()) * std::size_t(c) + std::size_t(a)] == kNoIndex) continue;
      const GhostFace<NC> f = face_of<NC>(g, c, a);
      const Vec2 t = f.b - f.a, mid = 0.5 * (f.a + f.b);
      const double h = t.norm();
      Vec2 n(t.y() / h, -t.x() / h);
      Vec2 centre = Vec2::Zero();
      for (int k = 0; k < NC; ++k) centre += g.nodes.X[g.cells.node(c, k)] / NC;
      if (n.dot(mid - centre) < 0) n = -n;
      // A linear field: no jump. A kink s(x) = k max(0, (x - mid) . n) ... restricted to the right cell's side:
      // the jump of its normal derivative is -k.
      Eigen::Matrix<double, NF, 1> linear, kink;
      for (int k = 0; k < NF; ++k) {
        const Vec2& X = g.nodes.X[f.nodes[std::size_t(k)]];
        linear[k] = 0.7 - 1.3 * X.x() + 2.1 * X.y();
        kink[k] = 1.5 * std::max(0.0, (X - mid).dot(n));
      }
      for (const double s : {0.2, 0.8}) {
        const auto w = ghost_jump<NC>(g.cells, g.nodes, f, f.a + s * t, n);
        EXPECT_NEAR(w.dot(linear), 0.0, 1e-12);
        EXPECT_NEAR(w.dot(kink), -1.5, 1e-12);
      }
      const auto K = ghost_penalty_matrix<NC, 3>(g.cells, g.nodes, f, gamma_0, mu);
      EXPECT_LE((K - K.transpose()).norm(), 1e-14 * K.norm());
      using FaceMatrix = Eigen::Matrix<double, 3 * NF, 3 * NF>;
      const double smallest = Eigen::SelfAdjointEigenSolver<FaceMatrix>(K).eigenvalues().minCoeff();
      EXPECT_GE(smallest, -1e-12 * K.norm());
      Eigen::Matrix<double, 3 * NF, 1> u_lin = Eigen::Matrix<double, 3 * NF, 1>::Zero(), u_kink = u_lin;
      for (int k = 0; k < NF; ++k) u_lin[3 * k] = linear[k], u_lin[3 * k + 2] = linear[k], u_kink[3 * k + 1] = kink[k], u_kink[3 * k + 2] = kink[k];
      EXPECT_LE((K * u_lin).norm(), 1e-12 * K.norm());
      // u_y and p with a kink of slope 1.5: gamma_u h (1.5)^2 + gamma_p h (1.5)^2.
      const double expected = (gamma_0 * mu * h + gamma_0 * h * h * h / (2 * mu)) * h * 1.5 * 1.5;
      EXPECT_NEAR(u_kink.dot(K * u_kink), expected, 1e-12 * expected);
      ++checked;
    }
  EXPECT_GT(checked, 20);
}

TEST(GhostFace, JumpsVanishOnLinearFieldsAndMeasureKinksOnTriangleGrids) { check_faces<3>(make_grid(false)); }
TEST(GhostFace, JumpsVanishOnLinearFieldsAndMeasureKinksOnQuadGrids) { check_faces<4>(make_grid(true)); }

TEST(GhostFaces, AreTheSidesBetweenActiveCellsNextToTheInactiveOnes) {
  const Grid g = make_grid(true);  // 5 x 3 squares; active: the left 3 x 3 block without its top-right square
  GridActivity act;
  act.cell_active.assign(15, 0);
  for (Index c : {0, 1, 2, 5, 6, 7, 10, 11}) act.cell_active[std::size_t(c)] = 1, act.active_cells.push_back(c);
  find_ghost_faces(g.cells, g.nodes.size(), act);
  // Cut cells (a corner shared with an inactive cell), by brute force over the inactive ones:
  std::vector<char> near(std::size_t(g.nodes.size()), 0);
  for (Index c = 0; c < 15; ++c)
    if (!act.cell_active[std::size_t(c)])
      for (int a = 0; a < 4; ++a) near[std::size_t(g.cells.node(c, a))] = 1;
  auto cut = [&](Index c) {
    for (int a = 0; a < 4; ++a)
      if (near[std::size_t(g.cells.node(c, a))]) return true;
    return false;
  };
  int expected = 0;
  for (Index c : act.active_cells)
    for (int a = 0; a < 4; ++a) {
      const Index n = g.cells.neighbour[std::size_t(4 * c + a)];
      if (n > c && act.cell_active[std::size_t(n)] && (cut(c) || cut(n))) ++expected;
    }
  EXPECT_EQ(act.ghost_faces.size(), expected);
  EXPECT_EQ(act.ghost_faces.stride, 6);
  EXPECT_EQ(act.ghost_cells.size(), std::size_t(2 * expected));
  EXPECT_FALSE(cut(0));  // the bottom-left cell is interior: its faces to 1 and 5 are penalised only because those are cut
  for (Index f = 0; f < act.ghost_faces.size(); ++f) {
    const Index l = act.ghost_cells[std::size_t(2 * f)], r = act.ghost_cells[std::size_t(2 * f + 1)];
    EXPECT_TRUE(cut(l) || cut(r));
    const GhostFace<4> face = ghost_face<4>(g.cells, g.nodes, l, r, act.ghost_ends[std::size_t(2 * f)], act.ghost_ends[std::size_t(2 * f + 1)]);
    for (int k = 0; k < 6; ++k) EXPECT_EQ(face.nodes[std::size_t(k)], act.ghost_faces.node(f, k));
  }
  for (std::size_t k = 0; k + 1 < act.ghost_faces.colour_offsets.size(); ++k) EXPECT_LE(act.ghost_faces.colour_offsets[k], act.ghost_faces.colour_offsets[k + 1]);
}

}  // namespace
}  // namespace loom
