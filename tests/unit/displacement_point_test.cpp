// Element kernel (systems/assemble/elements/displacement_point.hpp, p1_cell.hpp): the element tangent is
// the derivative of the element residual with respect to the nodal displacements (central differences),
// in an updated-Lagrangian state with a non-identity history F_n; the residual is invariant under rigid
// motions; the internal forces of a cell are self-equilibrated.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "systems/assemble/elements/p1_cell.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {
namespace {

// One triangle in the previous configuration B_n, its history F_n (plane strain) and an increment du.
struct Fixture {
  NodalVectors<3> x_n;  // corners in B_n
  NodalVectors<3> dN;   // dN/dx_n
  double dV_n = 0.0;
  Mat3 F_n = Mat3::Identity();
};

Fixture make_fixture(bool with_history) {
  Fixture f;
  f.x_n << 0.1, 0.2, 1.3, 0.4, 0.5, 1.1;
  Tri3Gradients dN;
  f.dV_n = tri3_gradients(f.x_n.row(0).transpose(), f.x_n.row(1).transpose(), f.x_n.row(2).transpose(), dN);
  f.dN = dN;
  if (with_history) {
    f.F_n.topLeftCorner<2, 2>() << 1.2, 0.3, -0.1, 0.9;  // det = 1.11
  }
  return f;
}

NodalVectors<3> random_increment(unsigned seed, double size) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-size, size);
  NodalVectors<3> du;
  for (int a = 0; a < 3; ++a) du.row(a) << d(rng), d(rng);
  return du;
}

template <class MaterialT>
ElementVector<3> residual(const MaterialT& m, const Fixture& f, const NodalVectors<3>& du) {
  ElementVector<3> r = ElementVector<3>::Zero();
  Mat3 F;
  EXPECT_TRUE(add_displacement_point<3>(m, du, f.dN, f.dV_n, f.F_n, F, r, nullptr));
  return r;
}

template <class MaterialT>
void expect_tangent_matches_differences(const MaterialT& m) {
  const Fixture f = make_fixture(true);
  for (unsigned seed : {1u, 2u, 3u}) {
    const NodalVectors<3> du = random_increment(seed, 0.15);
    ElementVector<3> r = ElementVector<3>::Zero();
    ElementMatrix<3> K = ElementMatrix<3>::Zero();
    Mat3 F;
    ASSERT_TRUE(add_displacement_point<3>(m, du, f.dN, f.dV_n, f.F_n, F, r, &K));
    EXPECT_LE((r - residual(m, f, du)).norm(), 1e-14 * r.norm());  // with and without tangent agree

    ElementMatrix<3> K_fd;
    const double h = 1e-6;
    for (int b = 0; b < 3; ++b)
      for (int k = 0; k < 2; ++k) {
        NodalVectors<3> up = du, um = du;
        up(b, k) += h, um(b, k) -= h;
        K_fd.col(2 * b + k) = (residual(m, f, up) - residual(m, f, um)) / (2 * h);
      }
    EXPECT_LE((K - K_fd).norm(), 1e-6 * K.norm()) << "seed " << seed << "\nK =\n" << K << "\nK_fd =\n" << K_fd;
  }
}

// Rotation by angle a in the plane, embedded in 3x3.
Mat3 rotation(double a) {
  Mat3 R = Mat3::Identity();
  R.topLeftCorner<2, 2>() << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return R;
}

}  // namespace

TEST(DisplacementPoint, NeoHookeTangentMatchesFiniteDifferences) { expect_tangent_matches_differences(NeoHooke{2.0, 0.6}); }

TEST(DisplacementPoint, LinearElasticTangentMatchesFiniteDifferences) {
  expect_tangent_matches_differences(LinearElastic{2.0, 0.6});
}

TEST(DisplacementPoint, DeformationGradientComposesIncrementAndHistory) {
  const Fixture f = make_fixture(true);
  // du = (H - I) x_n: an affine increment with increment gradient H, so F = H F_n.
  Mat3 H = Mat3::Identity();
  H.topLeftCorner<2, 2>() << 1.1, -0.2, 0.05, 0.95;
  NodalVectors<3> du = f.x_n * (H.topLeftCorner<2, 2>() - Eigen::Matrix2d::Identity()).transpose();
  const Mat3 F = deformation_gradient<3>(du, f.dN, f.F_n);
  EXPECT_LE((F - H * f.F_n).norm(), 1e-14);
  EXPECT_EQ(F(2, 2), 1.0);
}

TEST(DisplacementPoint, ResidualUsesReferenceVolumeAndGradients) {
  // Hand check with F_n = diag(2, 1): dV_0 = dV_n / 2 and G = dN F_n; a zero increment gives F = F_n and
  // f^A_i = P_ij G^A_j dV_0.
  Fixture f = make_fixture(false);
  f.F_n(0, 0) = 2.0;
  const NeoHooke m{1.0, 1.0};
  const ElementVector<3> r = residual(m, f, NodalVectors<3>::Zero());
  Mat3 P;
  ASSERT_TRUE(m.stress(f.F_n, P));
  for (int a = 0; a < 3; ++a) {
    const Vec2 G(2.0 * f.dN(a, 0), f.dN(a, 1));
    const Vec2 expected = P.topLeftCorner<2, 2>() * G * (f.dV_n / 2.0);
    EXPECT_NEAR(r(2 * a), expected.x(), 1e-14);
    EXPECT_NEAR(r(2 * a + 1), expected.y(), 1e-14);
  }
}

TEST(DisplacementPoint, RigidTranslationGivesNoResidualFromAStressFreeState) {
  const Fixture f = make_fixture(false);
  NodalVectors<3> du;
  du.rowwise() = Eigen::RowVector2d(0.7, -1.3);
  EXPECT_LE(residual(NeoHooke{2.0, 0.6}, f, du).norm(), 1e-14);
  EXPECT_LE(residual(LinearElastic{2.0, 0.6}, f, du).norm(), 1e-14);
}

TEST(DisplacementPoint, RigidTranslationLeavesAPrestressedResidualUnchanged) {
  const Fixture f = make_fixture(true);
  const NeoHooke m{2.0, 0.6};
  NodalVectors<3> du;
  du.rowwise() = Eigen::RowVector2d(0.7, -1.3);
  const ElementVector<3> r0 = residual(m, f, NodalVectors<3>::Zero());
  ASSERT_GT(r0.norm(), 0.1);  // the history carries stress
  EXPECT_LE((residual(m, f, du) - r0).norm(), 1e-13 * r0.norm());
}

TEST(DisplacementPoint, NeoHookeIsObjectiveUnderFiniteRotation) {
  // From a stress-free B_n, the rigid motion x = R x_n + c gives F = R and P = 0.
  const Fixture f = make_fixture(false);
  const Mat3 R = rotation(0.9);
  NodalVectors<3> du = f.x_n * (R.topLeftCorner<2, 2>() - Eigen::Matrix2d::Identity()).transpose();
  du.rowwise() += Eigen::RowVector2d(0.3, 0.2);
  EXPECT_LE(residual(NeoHooke{2.0, 0.6}, f, du).norm(), 1e-13);
}

TEST(DisplacementPoint, NeoHookeForcesRotateWithAPrestressedCell) {
  // P(R F) = R P(F): superposing a rigid rotation on a stressed state rotates each nodal force.
  const Fixture f = make_fixture(true);
  const NeoHooke m{2.0, 0.6};
  const Mat3 R = rotation(-0.6);
  const NodalVectors<3> du = f.x_n * (R.topLeftCorner<2, 2>() - Eigen::Matrix2d::Identity()).transpose();
  const ElementVector<3> r0 = residual(m, f, NodalVectors<3>::Zero());
  const ElementVector<3> r = residual(m, f, du);
  for (int a = 0; a < 3; ++a)
    EXPECT_LE((r.segment<2>(2 * a) - R.topLeftCorner<2, 2>() * r0.segment<2>(2 * a)).norm(), 1e-13 * r0.norm());
}

TEST(DisplacementPoint, InternalForcesOfACellSumToZero) {
  const Fixture f = make_fixture(true);
  const ElementVector<3> r = residual(NeoHooke{2.0, 0.6}, f, random_increment(7, 0.2));
  ASSERT_GT(r.norm(), 0.1);
  EXPECT_LE((r.segment<2>(0) + r.segment<2>(2) + r.segment<2>(4)).norm(), 1e-14 * r.norm());
}

TEST(DisplacementPoint, ReportsAnInvertedPoint) {
  const Fixture f = make_fixture(false);
  // Mirror the triangle through x = 0: du = -2 x_n (x only) gives det F = -1.
  NodalVectors<3> du = NodalVectors<3>::Zero();
  du.col(0) = -2.0 * f.x_n.col(0);
  ElementVector<3> r = ElementVector<3>::Zero();
  ElementMatrix<3> K = ElementMatrix<3>::Zero();
  Mat3 F;
  EXPECT_FALSE(add_displacement_point<3>(NeoHooke{2.0, 0.6}, du, f.dN, f.dV_n, f.F_n, F, r, &K));
  EXPECT_FALSE(add_displacement_point<3>(NeoHooke{2.0, 0.6}, du, f.dN, f.dV_n, f.F_n, F, r, nullptr));
  EXPECT_NEAR(F.determinant(), -1.0, 1e-14);
}

TEST(P1Cell, GathersIncrementGradientsAndHistoryFromTheStores) {
  Nodes<2> nodes;
  nodes.resize(4);
  Cells cells;
  cells.nodes.values() = {3, 1, 2};  // one cell on nodes 3, 1, 2 of four
  cells.body.values() = {0};
  cells.colour.values() = {0};
  for (Index n = 0; n < 4; ++n) {
    nodes.X[n] = Vec2(n, 2.0 * n);
    nodes.u_n[n] = Vec2(0.1 * n, 0.0);
    nodes.u[n] = Vec2(0.1 * n + 0.01 * n, -0.02 * n);
  }
  QuadPoints<2> quad;
  quad.resize(1);
  Tri3Gradients dN;
  dN << 1, 2, 3, 4, 5, 6;
  Eigen::Map<Tri3Gradients>(quad.grad(0)) = dN;
  quad.weight_n[0] = 0.5;
  quad.F_n[0](0, 0) = 2.0;

  const P1Cell cell = gather_p1_cell(nodes, cells, quad, 0);

  const Index corner[3] = {3, 1, 2};
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(cell.du(a, 0), 0.01 * corner[a], 1e-15);
    EXPECT_NEAR(cell.du(a, 1), -0.02 * corner[a], 1e-15);
  }
  EXPECT_EQ(cell.dN, NodalVectors<3>(dN));
  EXPECT_EQ(cell.dV_n, 0.5);
  EXPECT_EQ(cell.F_n(0, 0), 2.0);
  EXPECT_DOUBLE_EQ(cell.volume0, 0.25);
}

}  // namespace loom
