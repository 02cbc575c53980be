// systems/assemble/elements/mixed_up_point: the tangent of the mixed u-p material-point kernel (seed 003
// eqs 16-26) is the derivative of its residual, checked by central finite differences over the local
// dofs (9 on a tri3 cell, 12 on a quad4 cell), for the Galerkin, ASGS and OSGS forms, static and dynamic, compressible and incompressible
// (OSGS: with the pressure part of the projected R_p following the pressure, see residual());
// the Galerkin coupling blocks are each other's negative transpose (B = B*, eq 18); PPP annihilates
// constant pressures.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "systems/assemble/elements/mixed_up_point.hpp"

namespace loom {
namespace {

template <int NC>
struct PointSetup {
  UpPoint<NC> pt;
  UpCellValues<NC> cell;
  CornerVectors<NC> a0;  // acceleration at du = 0: a = a0 + c_a du
};

// tri3: a triangle's constant gradients; quad4: the bilinear functions of a 1.1 x 0.8 cell at (xi, eta) =
// (0.3, 0.6).
template <int NC>
PointSetup<NC> random_setup(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PointSetup<NC> s;
  if constexpr (NC == 3) {
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
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) s.pt.F_n(i, j) += 0.2 * u(rng);
  s.pt.V0 = 0.07;
  s.pt.rho_n = 1.3;
  s.pt.b = Vec2(0.4, -2.0);
  for (int a = 0; a < NC; ++a) {
    s.cell.du.row(a) << 0.05 * u(rng), 0.05 * u(rng);
    s.cell.p[a] = 3.0 * u(rng);
    s.a0.row(a) << u(rng), u(rng);
    s.cell.proj_u.row(a) << u(rng), u(rng);
    s.cell.proj_p[a] = 0.01 * u(rng);
  }
  return s;
}

// OSGS: the projection P_p follows the pressure term of R_p, P_p,a -= (p_a - p_a^0) / kappa, as the lumped
// projection of the linear field p_h / kappa nearly does; the OSGS tangent leaves that term out.
template <int NC>
UpVector<NC> residual(const NeoHookeSplit& m, const UpStabilisation& st, PointSetup<NC> s, const UpVector<NC>& dofs) {
  for (int a = 0; a < NC; ++a) {
    s.cell.du.row(a) << dofs[3 * a], dofs[3 * a + 1];
    if (st.projected) s.cell.proj_p[a] -= m.inv_kappa * (dofs[3 * a + 2] - s.cell.p[a]);
    s.cell.p[a] = dofs[3 * a + 2];
  }
  s.cell.a = s.a0 + st.c_a * s.cell.du;
  UpVector<NC> r = UpVector<NC>::Zero();
  Mat3 F;
  EXPECT_TRUE(add_up_point<NC>(m, st, s.pt, s.cell, F, r, nullptr));
  return r;
}

template <int NC>
void check_tangent(const NeoHookeSplit& m, const UpStabilisation& st, PointSetup<NC> s, const std::string& label) {
  SCOPED_TRACE(label + (NC == 4 ? " quad4" : " tri3"));
  UpVector<NC> dofs;
  for (int a = 0; a < NC; ++a) dofs.template segment<3>(3 * a) << s.cell.du(a, 0), s.cell.du(a, 1), s.cell.p[a];
  s.cell.a = s.a0 + st.c_a * s.cell.du;
  UpVector<NC> r = UpVector<NC>::Zero();
  UpMatrix<NC> K = UpMatrix<NC>::Zero();
  Mat3 F;
  ASSERT_TRUE(add_up_point<NC>(m, st, s.pt, s.cell, F, r, &K));
  EXPECT_LE((r - residual<NC>(m, st, s, dofs)).norm(), 1e-14 * r.norm());
  UpMatrix<NC> K_fd;
  for (int k = 0; k < 3 * NC; ++k) {
    const double h = (k % 3 == 2 ? 1e-4 : 1e-6);
    UpVector<NC> e = UpVector<NC>::Zero();
    e[k] = h;
    K_fd.col(k) = (residual<NC>(m, st, s, dofs + e) - residual<NC>(m, st, s, dofs - e)) / (2 * h);
  }
  EXPECT_LE((K - K_fd).norm(), 1e-7 * K.norm()) << "K =\n" << K << "\nK_fd =\n" << K_fd;
}

template <int NC>
void check_all_tangents() {
  const double mu = 2.0;
  for (const double ik : {0.0, 0.1}) {
    const NeoHookeSplit m{mu, ik};
    for (unsigned seed : {1u, 2u, 3u}) {
      const PointSetup<NC> s = random_setup<NC>(seed);
      UpStabilisation none;
      check_tangent<NC>(m, none, s, "galerkin");
      for (const bool dynamic : {false, true})
        for (const bool projected : {false, true}) {
          UpStabilisation vms{true, projected, 0.03 / (2 * mu), 2 * mu, dynamic ? 1.0 / (0.25 * 0.01) : 0.0};
          check_tangent<NC>(m, vms, s, std::string(projected ? "osgs" : "asgs") + (dynamic ? " dynamic" : " static") + (ik > 0 ? " compressible" : ""));
        }
    }
  }
}

TEST(MixedUpPoint, TangentIsTheDerivativeOfTheResidual) { check_all_tangents<3>(); }
TEST(MixedUpPoint, QuadCellTangentIsTheDerivativeOfTheResidual) { check_all_tangents<4>(); }

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
