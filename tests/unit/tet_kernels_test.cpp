// The displacement kernel (displacement_point.hpp) and the mixed u-phi kernel (p1p1_uphi_cell.hpp) with D = 3:
// every tangent equals the central difference of its residual at a general 3D state (a full F_n history with
// out-of-plane shear, random increments), for tet4 (one point), tet10 (four points) and the mixed tet4;
// forces of a cell sum to zero, Neo-Hooke is objective under a 3D rotation, and the mixed tet's dilatation
// rows vanish on a compatible homogeneous state (N-check = 1/4).
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Geometry>  // AngleAxis

#include "systems/assemble/elements/p1p1_uphi_cell.hpp"
#include "systems/assemble/elements/tet10.hpp"
#include "systems/assemble/elements/tet4.hpp"
#include "tests/unit/general_tetrahedron.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {
namespace {

Tet4Corners corners() { return testing::general_tetrahedron(); }

Mat3 history(int q) {
  Mat3 F;
  F << 1.1 + 0.02 * q, 0.2, -0.15, -0.1, 0.95, 0.12, 0.08, -0.05, 1.04 - 0.01 * q;
  return F;
}

template <int NEN>
NodalVectors<NEN, 3> random_vectors(unsigned seed, double size) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-size, size);
  NodalVectors<NEN, 3> v;
  for (int a = 0; a < NEN; ++a) v.row(a) << d(rng), d(rng), d(rng);
  return v;
}

// A 3D cell of NEN nodes integrated at NQ points with gradients dN[q] and weights dV_n[q] in B_n.
template <int NEN, int NQ>
struct Cell3 {
  NodalVectors<NEN, 3> dN[NQ];
  double dV_n[NQ];
  Mat3 F_n[NQ];
};

Cell3<4, 1> tet4_cell() {
  Cell3<4, 1> c;
  Tet4Gradients dN;
  c.dV_n[0] = tet4_gradients(corners(), dN);
  c.dN[0] = dN;
  c.F_n[0] = history(0);
  return c;
}

Cell3<10, 4> tet10_cell() {
  Cell3<10, 4> c;
  const Tet4Corners x4 = corners();
  Tet10Nodes x;
  x.topRows<4>() = x4;
  for (int e = 0; e < 6; ++e) x.row(4 + e) = 0.5 * (x4.row(kTet10Edges[e][0]) + x4.row(kTet10Edges[e][1]));
  x.row(4) += Eigen::RowVector3d(0.03, -0.02, 0.04);  // a curved edge: gradients vary non-linearly
  for (int q = 0; q < 4; ++q) {
    Tet10Gradients dN;
    c.dV_n[q] = tet10_gradients(x, kTet4Rule4[q], dN) / 24.0;  // weight 1/4 of det J / 6
    c.dN[q] = dN;
    c.F_n[q] = history(q);
  }
  return c;
}

template <int NEN, int NQ, class M>
ElementVector<NEN, 3> residual(const M& m, const Cell3<NEN, NQ>& c, const NodalVectors<NEN, 3>& du, ElementMatrix<NEN, 3>* K = nullptr) {
  ElementVector<NEN, 3> r = ElementVector<NEN, 3>::Zero();
  for (int q = 0; q < NQ; ++q) {
    Mat3 F;
    EXPECT_TRUE((add_displacement_point<NEN, 3>(m, du, c.dN[q], c.dV_n[q], c.F_n[q], F, r, K)));
  }
  return r;
}

template <int NEN, int NQ, class M>
void expect_tangent_matches_differences(const M& m, const Cell3<NEN, NQ>& c) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const NodalVectors<NEN, 3> du = random_vectors<NEN>(seed, 0.1);
    ElementMatrix<NEN, 3> K = ElementMatrix<NEN, 3>::Zero();
    const ElementVector<NEN, 3> r = residual(m, c, du, &K);
    EXPECT_LE((r - residual(m, c, du)).norm(), 1e-14 * r.norm());
    ElementMatrix<NEN, 3> K_fd;
    const double h = 1e-6;
    for (int b = 0; b < NEN; ++b)
      for (int k = 0; k < 3; ++k) {
        NodalVectors<NEN, 3> up = du, um = du;
        up(b, k) += h, um(b, k) -= h;
        K_fd.col(3 * b + k) = (residual(m, c, up) - residual(m, c, um)) / (2 * h);
      }
    EXPECT_LE((K - K_fd).norm(), 1e-7 * K.norm()) << "seed " << seed;
    EXPECT_LE((K - K.transpose()).norm(), 1e-12 * K.norm());  // hyperelastic: symmetric
  }
}

Mat3 rotation(const Vec3& axis, double angle) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }

}  // namespace

TEST(Tet4Kernel, TangentMatchesFiniteDifferences) {
  expect_tangent_matches_differences(NeoHooke{2.0, 0.6}, tet4_cell());
  expect_tangent_matches_differences(LinearElastic{2.0, 0.6}, tet4_cell());
}

TEST(Tet10Kernel, TangentMatchesFiniteDifferences) {
  expect_tangent_matches_differences(NeoHooke{2.0, 0.6}, tet10_cell());
  expect_tangent_matches_differences(LinearElastic{2.0, 0.6}, tet10_cell());
}

TEST(Tet10Kernel, ForcesSumToZeroAndRotateWithTheCell) {
  const Cell3<10, 4> c = tet10_cell();
  const NeoHooke m{2.0, 0.6};
  const ElementVector<10, 3> r0 = residual(m, c, NodalVectors<10, 3>(NodalVectors<10, 3>::Zero()));
  ASSERT_GT(r0.norm(), 0.1);  // the history carries stress
  Vec3 sum = Vec3::Zero();
  for (int a = 0; a < 10; ++a) sum += r0.segment<3>(3 * a);
  EXPECT_LE(sum.norm(), 1e-14 * r0.norm());
  // Superposing a rigid rotation R on B_n (du = (R - I) x_n) rotates every nodal force: P(R F) = R P(F).
  const Mat3 R = rotation(Vec3(0.3, -0.5, 0.8), 0.7);
  const Tet4Corners x4 = corners();
  Tet10Nodes x;
  x.topRows<4>() = x4;
  for (int e = 0; e < 6; ++e) x.row(4 + e) = 0.5 * (x4.row(kTet10Edges[e][0]) + x4.row(kTet10Edges[e][1]));
  x.row(4) += Eigen::RowVector3d(0.03, -0.02, 0.04);
  const NodalVectors<10, 3> du = x * (R - Mat3::Identity()).transpose();
  const ElementVector<10, 3> r = residual(m, c, du);
  for (int a = 0; a < 10; ++a) EXPECT_LE((r.segment<3>(3 * a) - R * r0.segment<3>(3 * a)).norm(), 1e-13 * r0.norm());
}

namespace {

UPhiCellT<3> uphi_tet(bool with_history, unsigned seed) {
  UPhiCellT<3> c;
  Tet4Gradients dN;
  const double volume = tet4_gradients(corners(), dN);
  c.dN = dN;
  for (int q = 0; q < 4; ++q) {
    c.dV_n[q] = volume / 4;
    c.F_n[q] = with_history ? Mat3(1.02 * history(q)) : Mat3::Identity();
  }
  c.du = random_vectors<4>(seed, 0.08);
  std::mt19937 rng(seed + 100);
  std::uniform_real_distribution<double> d(-0.1, 0.1);
  for (int a = 0; a < 4; ++a) c.phi[a] = 1.0 + d(rng);
  return c;
}

template <class M>
UPhiVectorT<3> uphi_residual(const M& m, double alpha, const UPhiCellT<3>& c, UPhiMatrixT<3>* K = nullptr) {
  UPhiVectorT<3> r = UPhiVectorT<3>::Zero();
  Mat3 Ft[4];
  EXPECT_TRUE(uphi_internal(m, alpha, c, Ft, r, K));
  return r;
}

}  // namespace

TEST(UPhiTet, TangentBlocksMatchFiniteDifferences) {
  const NeoHooke neo{30.0, 2.0};
  for (bool with_history : {false, true})
    for (unsigned seed : {1u, 2u}) {
      const UPhiCellT<3> c = uphi_tet(with_history, seed);
      UPhiMatrixT<3> K = UPhiMatrixT<3>::Zero();
      const UPhiVectorT<3> r = uphi_residual(neo, 5.0, c, &K);
      EXPECT_LE((r - uphi_residual(neo, 5.0, c)).norm(), 1e-14 * r.norm());
      UPhiMatrixT<3> K_fd;
      const double h = 1e-6;
      for (int b = 0; b < 4; ++b)
        for (int k = 0; k < 4; ++k) {
          UPhiCellT<3> p = c, n = c;
          if (k < 3) p.du(b, k) += h, n.du(b, k) -= h;
          else p.phi[b] += h, n.phi[b] -= h;
          K_fd.col(4 * b + k) = (uphi_residual(neo, 5.0, p) - uphi_residual(neo, 5.0, n)) / (2 * h);
        }
      // Each block against its own scale (stress vs volume): rows/cols 4a+3 are phi.
      for (int rphi : {0, 1})
        for (int cphi : {0, 1}) {
          double diff = 0.0, size = 0.0;
          for (int i = 0; i < 16; ++i)
            for (int j = 0; j < 16; ++j)
              if ((i % 4 == 3) == bool(rphi) && (j % 4 == 3) == bool(cphi)) {
                diff += std::pow(K(i, j) - K_fd(i, j), 2);
                size += std::pow(K(i, j), 2);
              }
          EXPECT_LE(std::sqrt(diff), 1e-7 * std::sqrt(size)) << "block " << rphi << cphi << " history " << with_history;
        }
    }
}

TEST(UPhiTet, HomogeneousCompatibleStateHasNoDilatationResidual) {
  // phi = J at every node and a uniform phi: J - phi vanishes pointwise and the projection (M - m / 4) phi
  // vanishes only with N-check = 1/4 (1/3 would leave V (1/4 - 1/3) alpha phi in each row).
  UPhiCellT<3> c = uphi_tet(false, 1);
  Mat3 H;
  H << 0.1, 0.05, 0.2, -0.02, -0.07, 0.03, 0.04, -0.1, 0.06;
  const Tet4Corners x = corners();
  c.du = x * H.transpose();
  c.phi.setConstant((Mat3::Identity() + H).determinant());
  const UPhiVectorT<3> r = uphi_residual(NeoHooke{30.0, 2.0}, 7.0, c);
  for (int a = 0; a < 4; ++a) EXPECT_NEAR(r[4 * a + 3], 0.0, 1e-15);
}

}  // namespace loom
