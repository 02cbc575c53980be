// Mixed u-phi element kernel (systems/assemble/elements/p1p1_uphi_cell.hpp, seed 000 §4.2): every tangent
// block (u-u, u-phi, phi-u, phi-phi, eqs 40-43) equals the central finite difference of the residual
// (38)-(39), with a non-trivial history F~_n and stabilisation; a compatible homogeneous state (phi = J) has
// no dilatation residual; the stabilisation vanishes for a uniform phi.
#include <gtest/gtest.h>

#include <random>

#include "systems/assemble/elements/p1p1_uphi_cell.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {
namespace {

UPhiCell make_cell(bool with_history) {
  UPhiCell c;
  NodalVectors<3> x;
  x << 0.1, 0.2, 1.3, 0.4, 0.5, 1.1;
  Tri3Gradients dN;
  const double area = tri3_gradients(x.row(0).transpose(), x.row(1).transpose(), x.row(2).transpose(), dN);
  c.dN = dN;
  for (int q = 0; q < 3; ++q) {
    c.dV_n[q] = area / 3;
    c.F_n[q] = Mat3::Identity();
    if (with_history) {
      // F~_n differs per point and has F33 != 1 (the dilatation scales all three directions).
      c.F_n[q].topLeftCorner<2, 2>() << 1.1 + 0.02 * q, 0.2, -0.1, 0.95 - 0.01 * q;
      c.F_n[q](2, 2) = 1.03;
    }
  }
  c.du.setZero();
  c.phi.setOnes();
  return c;
}

void randomise(UPhiCell& c, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-0.1, 0.1);
  for (int a = 0; a < 3; ++a) c.du.row(a) << d(rng), d(rng), c.phi[a] = 1.0 + d(rng);
}

template <class M>
UPhiVector residual(const M& m, double alpha, const UPhiCell& c) {
  UPhiVector r = UPhiVector::Zero();
  Mat3 Ft[3];
  EXPECT_TRUE(uphi_internal(m, alpha, c, Ft, r, nullptr));
  return r;
}

template <class M>
void expect_tangent_matches_differences(const M& m, double alpha) {
  for (bool history : {false, true})
    for (unsigned seed : {1u, 2u, 3u}) {
      UPhiCell c = make_cell(history);
      randomise(c, seed);
      UPhiVector r = UPhiVector::Zero();
      UPhiMatrix K = UPhiMatrix::Zero();
      Mat3 Ft[3];
      ASSERT_TRUE(uphi_internal(m, alpha, c, Ft, r, &K));
      EXPECT_LE((r - residual(m, alpha, c)).norm(), 1e-14 * r.norm());
      UPhiMatrix K_fd;
      const double h = 1e-6;
      for (int b = 0; b < 3; ++b)
        for (int k = 0; k < 3; ++k) {
          UPhiCell p = c, n = c;
          if (k < 2) p.du(b, k) += h, n.du(b, k) -= h;
          else p.phi[b] += h, n.phi[b] -= h;
          K_fd.col(3 * b + k) = (residual(m, alpha, p) - residual(m, alpha, n)) / (2 * h);
        }
      // Each block against its own scale: the blocks differ by orders of magnitude (stress vs. volume).
      const int u[6] = {0, 1, 3, 4, 6, 7}, f[3] = {2, 5, 8};
      auto block = [](const UPhiMatrix& A, const int* rows, int nr, const int* cols, int nc) {
        Eigen::MatrixXd B(nr, nc);
        for (int i = 0; i < nr; ++i)
          for (int j = 0; j < nc; ++j) B(i, j) = A(rows[i], cols[j]);
        return B;
      };
      const struct {
        const char* name;
        const int *rows, *cols;
        int nr, nc;
      } blocks[4] = {{"uu", u, u, 6, 6}, {"uphi", u, f, 6, 3}, {"phiu", f, u, 3, 6}, {"phiphi", f, f, 3, 3}};
      for (const auto& bl : blocks) {
        const Eigen::MatrixXd A = block(K, bl.rows, bl.nr, bl.cols, bl.nc), B = block(K_fd, bl.rows, bl.nr, bl.cols, bl.nc);
        EXPECT_LE((A - B).norm(), 1e-6 * A.norm()) << bl.name << " history " << history << " seed " << seed << "\n" << A << "\nfd\n" << B;
      }
    }
}

TEST(P1P1UPhiCell, TangentBlocksMatchFiniteDifferencesNeoHooke) {
  expect_tangent_matches_differences(NeoHooke{30.0, 2.0}, 5.0);
}

TEST(P1P1UPhiCell, TangentBlocksMatchFiniteDifferencesLinearElastic) {
  expect_tangent_matches_differences(LinearElastic{30.0, 2.0}, 0.0);
}

TEST(P1P1UPhiCell, HomogeneousCompatibleStateHasNoDilatationResidual) {
  // Uniform deformation with phi = J at every node and no history: J - phi vanishes pointwise and the
  // projection term vanishes for a uniform phi, so the phi rows are zero.
  UPhiCell c = make_cell(false);
  NodalVectors<3> x;
  x << 0.1, 0.2, 1.3, 0.4, 0.5, 1.1;
  Eigen::Matrix2d H;
  H << 0.1, 0.05, -0.02, -0.07;
  for (int a = 0; a < 3; ++a) c.du.row(a) = (H * x.row(a).transpose()).transpose();
  const double J = (Eigen::Matrix2d::Identity() + H).determinant();
  c.phi.setConstant(J);
  const UPhiVector r = residual(NeoHooke{30.0, 2.0}, 7.0, c);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(r[3 * a + 2], 0.0, 1e-15);
}

}  // namespace
}  // namespace loom
