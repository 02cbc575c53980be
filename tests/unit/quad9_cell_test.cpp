// The biquadratic displacement quadrilateral as an FEM element (isoparametric_cell.hpp, element_mass.hpp,
// compute_geometry): the element tangent equals the central difference of the residual on a curved cell with a
// non-trivial history; the consistent mass integrates 1 and x exactly and its row sum is the lumped mass,
// positive at every node; the mid-side/centre construction (add_quad9_nodes) makes the quad9 map of a
// straight-sided quadrilateral the bilinear one, so the cached gradients reproduce affine fields.
#include <gtest/gtest.h>

#include <random>

#include "engine/mesh/mid_nodes.hpp"
#include "systems/assemble/compute_geometry.hpp"
#include "systems/assemble/elements/element_mass.hpp"
#include "systems/assemble/elements/isoparametric_cell.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {
namespace {

// A curved cell: corners of a skewed quadrilateral, mid-sides and centre pushed off their straight places.
Quad9Coordinates curved_cell() {
  Quad9Coordinates x;
  x << 0.0, 0.0, 1.1, 0.1, 1.3, 1.0, -0.1, 0.9,  // corners
      0.56, 0.08, 1.24, 0.52, 0.6, 0.98, -0.02, 0.43,  // mid-sides
      0.58, 0.5;                                         // centre
  return x;
}

Quad9Cell cell_with_history(const Quad9Coordinates& x) {
  Quad9Cell c;
  const Quad9Gauss& rule = quad9_gauss();
  for (int q = 0; q < 9; ++q) {
    double det = 0.0;
    c.dN[q] = quad9_gradients(x, rule.xi[std::size_t(q)], &det);
    c.dV_n[q] = det * rule.weight[std::size_t(q)];
    c.F_n[q] = Mat3::Identity();
    c.F_n[q].topLeftCorner<2, 2>() << 1.05, 0.03 * q, -0.05, 0.97;
  }
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-0.05, 0.05);
  for (int a = 0; a < 9; ++a) c.du.row(a) << d(rng), d(rng);
  return c;
}

template <class M>
ElementVector<9> residual(const M& m, const Quad9Cell& c) {
  ElementVector<9> r = ElementVector<9>::Zero();
  Mat3 F[9];
  EXPECT_TRUE(isoparametric_internal(m, c, F, r, nullptr));
  return r;
}

template <class M>
void expect_tangent_matches_differences(const M& material) {
  const Quad9Cell c = cell_with_history(curved_cell());
  ElementVector<9> r = ElementVector<9>::Zero();
  ElementMatrix<9> K = ElementMatrix<9>::Zero();
  Mat3 F[9];
  ASSERT_TRUE(isoparametric_internal(material, c, F, r, &K));
  ElementMatrix<9> K_fd;
  const double h = 1e-6;
  for (int b = 0; b < 9; ++b)
    for (int k = 0; k < 2; ++k) {
      Quad9Cell p = c, n = c;
      p.du(b, k) += h, n.du(b, k) -= h;
      K_fd.col(2 * b + k) = (residual(material, p) - residual(material, n)) / (2 * h);
    }
  EXPECT_LE((K - K_fd).norm(), 1e-6 * K.norm()) << "K\n" << K << "\nfd\n" << K_fd;
  EXPECT_LE((K - K.transpose()).norm(), 1e-12 * K.norm());  // hyperelastic: symmetric
  EXPECT_GT(r.norm(), 0.0);
}

TEST(Quad9Cell, TangentMatchesFiniteDifferencesNeoHooke) { expect_tangent_matches_differences(NeoHooke{30.0, 2.0}); }
TEST(Quad9Cell, TangentMatchesFiniteDifferencesLinearElastic) { expect_tangent_matches_differences(LinearElastic{3.0, 2.0}); }

TEST(Quad9Cell, MassIntegratesOneAndXAndLumpsToItsRowSum) {
  const Quad9Coordinates x = curved_cell();
  const Quad9Gauss& rule = quad9_gauss();
  double dV0[9], area = 0.0;
  Vec2 first_moment = Vec2::Zero();
  for (int q = 0; q < 9; ++q) {
    double det = 0.0;
    quad9_gradients(x, rule.xi[std::size_t(q)], &det);
    dV0[q] = det * rule.weight[std::size_t(q)];
    area += dV0[q];
    first_moment += dV0[q] * (x.transpose() * quad9_shape(rule.xi[std::size_t(q)]));
  }
  const Eigen::Matrix<double, 9, 9> M = quad9_consistent_mass(dV0);
  const Quad9Values m = quad9_lumped_mass(dV0);
  EXPECT_NEAR(M.sum(), area, 1e-14);                                         // 1^T M 1 = int 1
  EXPECT_LE((x.transpose() * M * Quad9Values::Ones() - first_moment).norm(), 1e-14);  // x^T M 1 = int x
  EXPECT_LE((M.rowwise().sum() - m).norm(), 1e-15);
  EXPECT_LE((M - M.transpose()).norm(), 1e-16);
  for (int a = 0; a < 9; ++a) EXPECT_GT(m[a], 0.0) << "node " << a;
  // A rectangle: Simpson's tensor product, corners 1/36, mid-sides 1/9, centre 4/9 of the area.
  double rect[9];
  for (int q = 0; q < 9; ++q) rect[q] = 6.0 * rule.weight[std::size_t(q)] / 4.0;  // a 2 x 3 rectangle
  const Quad9Values mr = quad9_lumped_mass(rect);
  for (int a = 0; a < 4; ++a) EXPECT_NEAR(mr[a], 6.0 / 36.0, 1e-14);
  for (int a = 4; a < 8; ++a) EXPECT_NEAR(mr[a], 6.0 / 9.0, 1e-14);
  EXPECT_NEAR(mr[8], 6.0 * 4.0 / 9.0, 1e-14);
}

TEST(Quad9Cell, GeneratedNodesMakeTheBilinearMapAndGradientsReproduceAffineFields) {
  // Two skewed straight-sided quadrilaterals sharing a side: one mid-node on the shared side, two centres.
  std::vector<Vec2> X = {{0, 0}, {1.2, 0.1}, {1.1, 1.0}, {-0.1, 0.8}, {2.3, 0.3}, {2.2, 1.2}};
  const std::vector<Index> quads = {0, 1, 2, 3, 1, 4, 5, 2};
  const std::vector<Index> q9 = add_quad9_nodes(X, quads);
  ASSERT_EQ(q9.size(), 18u);
  EXPECT_EQ(X.size(), 6u + 7u + 2u);  // 7 distinct sides, 2 centres
  EXPECT_EQ(q9[5], q9[9 + 7]);        // side (1, 2) of the first is side (2, 1) of the second
  Nodes<2> nodes;
  nodes.resize(Index(X.size()));
  for (std::size_t i = 0; i < X.size(); ++i) nodes.X[Index(i)] = X[i];
  std::vector<Cells> cells(1, Cells(CellType::quad9, Formulation::quad9));
  cells[0].nodes.values() = q9;
  cells[0].body.values() = {0, 0};
  std::vector<QuadPoints<2>> quad;
  allocate_quad_points(cells, quad);
  ASSERT_EQ(quad[0].per_cell, 9);
  ASSERT_EQ(compute_geometry(nodes, cells, quad), 0);
  Eigen::Matrix2d A;
  A << 0.3, -0.2, 0.15, 0.4;
  double area = 0.0;
  for (Index c = 0; c < 2; ++c)
    for (int q = 0; q < 9; ++q) {
      const auto dN = Eigen::Map<const Quad9Gradients>(quad[0].grad(9 * c + q));
      Eigen::Matrix<double, 9, 2> u;
      for (int a = 0; a < 9; ++a) u.row(a) = (A * X[std::size_t(cells[0].node(c, a))]).transpose();
      EXPECT_LE((u.transpose() * dN - A).norm(), 1e-13);  // grad u = A exactly
      area += quad[0].weight_n[9 * c + q];
    }
  // Shoelace areas of the two quadrilaterals.
  auto shoelace = [&](std::initializer_list<int> v) {
    std::vector<int> p(v);
    double s = 0.0;
    for (std::size_t k = 0; k < p.size(); ++k) {
      const Vec2 &a = X[std::size_t(p[k])], &b = X[std::size_t(p[(k + 1) % p.size()])];
      s += a.x() * b.y() - b.x() * a.y();
    }
    return 0.5 * s;
  };
  EXPECT_NEAR(area, shoelace({0, 1, 2, 3}) + shoelace({1, 4, 5, 2}), 1e-14);
}

}  // namespace
}  // namespace loom
