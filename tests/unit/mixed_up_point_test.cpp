// systems/assemble/elements/mixed_up_point: the tangent of the mixed u-p material-point kernel (seed 003
// eqs 16-26) is the derivative of its residual, checked by central finite differences over the local
// dofs (9 on a tri3 cell, 12 on a quad4 cell, 16 on a tet4 cell in 3D), for the Galerkin, ASGS and OSGS forms, static and dynamic, compressible and incompressible
// (OSGS: with the pressure part of the projected R_p following the pressure, see residual());
// the Galerkin coupling blocks are each other's negative transpose (B = B*, eq 18); PPP annihilates
// constant pressures.
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "systems/assemble/elements/mixed_up_point.hpp"

namespace loom {
namespace {

template <int NC, int D = 2>
struct PointSetup {
  UpPoint<NC, D> pt;
  UpCellValues<NC, D> cell;
  CornerVectors<NC, D> a0;  // acceleration at du = 0: a = a0 + c_a du
};

// tri3: a triangle's constant gradients; quad4: the bilinear functions of a 1.1 x 0.8 cell at (xi, eta) =
// (0.3, 0.6); tet4 (D = 3): a tetrahedron's constant gradients.
template <int NC, int D = 2>
PointSetup<NC, D> random_setup(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PointSetup<NC, D> s;
  if constexpr (D == 3) {
    const Vec3 x0(0.1, 0.0, 0.2), e1 = Vec3(1.2, 0.3, 0.1) - x0, e2 = Vec3(0.4, 0.9, 0.0) - x0, e3 = Vec3(0.3, 0.2, 1.1) - x0;
    const double det = e1.dot(e2.cross(e3));
    s.pt.dN.row(1) = e2.cross(e3).transpose() / det;
    s.pt.dN.row(2) = e3.cross(e1).transpose() / det;
    s.pt.dN.row(3) = e1.cross(e2).transpose() / det;
    s.pt.dN.row(0) = -(s.pt.dN.row(1) + s.pt.dN.row(2) + s.pt.dN.row(3));
    s.pt.N = Vec4(0.1, 0.2, 0.3, 0.4);
  } else if constexpr (NC == 3) {
    const Vec2 x[3] = {Vec2(0.1, 0.0), Vec2(1.2, 0.3), Vec2(0.4, 0.9)};
    double two_area = (x[1] - x[0]).x() * (x[2] - x[0]).y() - (x[2] - x[0]).x() * (x[1] - x[0]).y();
    s.pt.dN << x[1].y() - x[2].y(), x[2].x() - x[1].x(), x[2].y() - x[0].y(), x[0].x() - x[2].x(), x[0].y() - x[1].y(), x[1].x() - x[0].x();
    s.pt.dN /= two_area;
    s.pt.N = Vec3(0.2, 0.5, 0.3);
  } else {
    const double xi = 0.3, eta = 0.6, hx = 1.1, hy = 0.8;
    s.pt.N << (1 - xi) * (1 - eta), xi * (1 - eta), xi * eta, (1 - xi) * eta;
    s.pt.dN << -(1 - eta) / hx, -(1 - xi) / hy, (1 - eta) / hx, -xi / hy, eta / hx, xi / hy, -eta / hx, (1 - xi) / hy;
  }
  s.pt.F_n = Mat3::Identity();
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) s.pt.F_n(i, j) += 0.2 * u(rng);
  s.pt.V0 = 0.07;
  s.pt.rho_n = 1.3;
  for (int i = 0; i < D; ++i) s.pt.b[i] = i == 1 ? -2.0 : 0.4;
  for (int a = 0; a < NC; ++a) {
    for (int i = 0; i < D; ++i) s.cell.du(a, i) = 0.05 * u(rng);
    s.cell.p[a] = 3.0 * u(rng);
    for (int i = 0; i < D; ++i) s.a0(a, i) = u(rng);
    for (int i = 0; i < D; ++i) s.cell.proj_u(a, i) = u(rng);
    s.cell.proj_p[a] = 0.01 * u(rng);
  }
  return s;
}

// OSGS: the projection P_p follows the pressure term of R_p, P_p,a -= (p_a - p_a^0) / kappa, as the lumped
// projection of the linear field p_h / kappa nearly does; the OSGS tangent leaves that term out.
template <int NC, int D>
UpVector<NC, D> residual(const NeoHookeSplit& m, const UpStabilisation& st, PointSetup<NC, D> s, const UpVector<NC, D>& dofs) {
  constexpr int PN = D + 1;
  for (int a = 0; a < NC; ++a) {
    for (int i = 0; i < D; ++i) s.cell.du(a, i) = dofs[PN * a + i];
    if (st.projected) s.cell.proj_p[a] -= m.inv_kappa * (dofs[PN * a + D] - s.cell.p[a]);
    s.cell.p[a] = dofs[PN * a + D];
  }
  s.cell.a = s.a0 + st.c_a * s.cell.du;
  UpVector<NC, D> r = UpVector<NC, D>::Zero();
  Mat3 F;
  EXPECT_TRUE((add_up_point<NC, D>(m, st, s.pt, s.cell, F, r, nullptr)));
  return r;
}

template <int NC, int D>
void check_tangent(const NeoHookeSplit& m, const UpStabilisation& st, PointSetup<NC, D> s, const std::string& label) {
  SCOPED_TRACE(label + (D == 3 ? " tet4" : NC == 4 ? " quad4" : " tri3"));
  constexpr int PN = D + 1;
  UpVector<NC, D> dofs;
  for (int a = 0; a < NC; ++a) {
    for (int i = 0; i < D; ++i) dofs[PN * a + i] = s.cell.du(a, i);
    dofs[PN * a + D] = s.cell.p[a];
  }
  s.cell.a = s.a0 + st.c_a * s.cell.du;
  UpVector<NC, D> r = UpVector<NC, D>::Zero();
  UpMatrix<NC, D> K = UpMatrix<NC, D>::Zero();
  Mat3 F;
  ASSERT_TRUE((add_up_point<NC, D>(m, st, s.pt, s.cell, F, r, &K)));
  EXPECT_LE((r - residual<NC, D>(m, st, s, dofs)).norm(), 1e-14 * r.norm());
  UpMatrix<NC, D> K_fd;
  for (int k = 0; k < PN * NC; ++k) {
    const double h = (k % PN == D ? 1e-4 : 1e-6);
    UpVector<NC, D> e = UpVector<NC, D>::Zero();
    e[k] = h;
    K_fd.col(k) = (residual<NC, D>(m, st, s, dofs + e) - residual<NC, D>(m, st, s, dofs - e)) / (2 * h);
  }
  EXPECT_LE((K - K_fd).norm(), 1e-7 * K.norm()) << "K =\n" << K << "\nK_fd =\n" << K_fd;
}

template <int NC, int D = 2>
void check_all_tangents() {
  const double mu = 2.0;
  for (const double ik : {0.0, 0.1}) {
    const NeoHookeSplit m{mu, ik};
    for (unsigned seed : {1u, 2u, 3u}) {
      const PointSetup<NC, D> s = random_setup<NC, D>(seed);
      UpStabilisation none;
      check_tangent<NC, D>(m, none, s, "galerkin");
      for (const bool dynamic : {false, true})
        for (const bool projected : {false, true}) {
          UpStabilisation vms{true, projected, 0.03 / (2 * mu), 2 * mu, dynamic ? 1.0 / (0.25 * 0.01) : 0.0};
          check_tangent<NC, D>(m, vms, s, std::string(projected ? "osgs" : "asgs") + (dynamic ? " dynamic" : " static") + (ik > 0 ? " compressible" : ""));
        }
    }
  }
}

TEST(MixedUpPoint, TangentIsTheDerivativeOfTheResidual) { check_all_tangents<3>(); }
TEST(MixedUpPoint, QuadCellTangentIsTheDerivativeOfTheResidual) { check_all_tangents<4>(); }
TEST(MixedUpPoint, TetCellTangentIsTheDerivativeOfTheResidual) { check_all_tangents<4, 3>(); }

TEST(MixedUpPoint, TetCellGalerkinCouplingBlocksAreNegativeTransposes) {
  const PointSetup<4, 3> s = random_setup<4, 3>(6);
  UpVector<4, 3> r = UpVector<4, 3>::Zero();
  UpMatrix<4, 3> K = UpMatrix<4, 3>::Zero();
  Mat3 F;
  ASSERT_TRUE((add_up_point<4, 3>(NeoHookeSplit{1.0, 0.0}, UpStabilisation{}, s.pt, s.cell, F, r, &K)));
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(K(4 * a + i, 4 * b + 3), -K(4 * b + 3, 4 * a + i), 1e-14);
  EXPECT_EQ(K(3, 3), 0.0);  // incompressible: no pressure-pressure block without stabilisation
}

TEST(MixedUpPoint, GalerkinCouplingBlocksAreNegativeTransposes) {
  const PointSetup<3> s = random_setup<3>(4);
  UpVector<3> r = UpVector<3>::Zero();
  UpMatrix<3> K = UpMatrix<3>::Zero();
  Mat3 F;
  ASSERT_TRUE(add_up_point<3>(NeoHookeSplit{1.0, 0.0}, UpStabilisation{}, s.pt, s.cell, F, r, &K));
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int i = 0; i < 2; ++i) EXPECT_NEAR(K(3 * a + i, 3 * b + 2), -K(3 * b + 2, 3 * a + i), 1e-14);
  EXPECT_EQ(K(2, 2), 0.0);  // incompressible: no pressure-pressure block without stabilisation (eq 18)
}

TEST(MixedUpPoint, RejectsInvertedPoints) {
  PointSetup<3> s = random_setup<3>(5);
  s.cell.du << -0.2, 0.0, -2.4, 0.0, -0.8, 0.0;  // u = -2 x e_x at the corners: dF = diag(-1, 1)
  UpVector<3> r = UpVector<3>::Zero();
  Mat3 F;
  EXPECT_FALSE(add_up_point<3>(NeoHookeSplit{1.0, 0.0}, UpStabilisation{}, s.pt, s.cell, F, r, nullptr));
}

TEST(PppAccumulator, IsSymmetricPositiveSemidefiniteAndZeroOnConstants) {
  PppAccumulator<3> ppp;
  ppp.add(Vec3(0.2, 0.5, 0.3), 0.3);
  ppp.add(Vec3(0.6, 0.2, 0.2), 0.2);
  ppp.add(Vec3(0.1, 0.1, 0.8), 0.5);
  UpVector<3> r = UpVector<3>::Zero();
  UpMatrix<3> K = UpMatrix<3>::Zero();
  ppp.apply(0.5, Vec3(2.0, 2.0, 2.0), r, &K);
  EXPECT_LE(r.norm(), 1e-15);
  Eigen::Matrix3d S;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) S(a, b) = K(3 * a + 2, 3 * b + 2);
  EXPECT_LE((S - S.transpose()).norm(), 1e-15);
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S).eigenvalues().minCoeff(), -1e-15);
  EXPECT_GT(S.norm(), 0.01);
}

}  // namespace
}  // namespace loom
