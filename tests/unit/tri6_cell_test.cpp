// Quadratic triangle (systems/assemble/elements/tri6.hpp, isoparametric_cell.hpp; seed 000 §4.1): shape functions
// are a partition of unity and interpolate quadratics exactly; the element tangent equals the central
// difference of the residual with a non-trivial history; the mass helpers integrate exactly.
#include <gtest/gtest.h>

#include <random>

#include "systems/assemble/elements/element_mass.hpp"
#include "systems/assemble/elements/tri3.hpp"
#include "systems/assemble/elements/isoparametric_cell.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {
namespace {

// A curved cell: straight corners, mid-nodes pushed off the edges.
Eigen::Matrix<double, 6, 2> curved_cell() {
  Eigen::Matrix<double, 6, 2> x;
  x << 0.0, 0.0, 1.2, 0.1, 0.3, 0.9, 0.62, 0.02, 0.8, 0.55, 0.12, 0.47;
  return x;
}

TEST(Tri6, ShapeFunctionsArePartitionOfUnityAndInterpolateQuadratics) {
  const Eigen::Matrix<double, 6, 2> x = curved_cell();
  auto f = [](double a, double b) { return 1.0 + 2.0 * a - b + 0.5 * a * a - 0.3 * a * b + 0.7 * b * b; };
  // Reference-space quadratic: interpolation from the nodal values of the reference triangle is exact.
  const double ref[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};
  for (const auto& p : kTriangleRule6) {
    const Tri6Values N = tri6_values(p.l[0], p.l[1], p.l[2]);
    EXPECT_NEAR(N.sum(), 1.0, 1e-14);
    double interp = 0.0;
    for (int a = 0; a < 6; ++a) interp += N[a] * f(ref[a][0], ref[a][1]);
    EXPECT_NEAR(interp, f(p.l[1], p.l[2]), 1e-13);
    Tri6Gradients dN;
    EXPECT_GT(tri6_gradients(x, p.l[0], p.l[1], p.l[2], dN), 0.0);
    EXPECT_NEAR(dN.col(0).sum(), 0.0, 1e-13);
    EXPECT_NEAR(dN.col(1).sum(), 0.0, 1e-13);
    // The isoparametric map reproduces the coordinates themselves: sum_A x_A (x) dN^A/dx = I.
    EXPECT_LE((x.transpose() * dN - Eigen::Matrix2d::Identity()).norm(), 1e-13);
  }
}

TEST(Tri6, ConsistentMassIntegratesExactlyAndHrzKeepsTheTotal) {
  const double area = 0.37;
  const auto M = tri6_consistent_mass(area);
  EXPECT_NEAR(M.sum(), area, 1e-14);  // sum N^A N^B = 1
  EXPECT_NEAR(M(0, 0), area / 30.0, 1e-14);  // exact P2 mass: corners 6/180, mid-nodes 32/180, times 2A
  EXPECT_NEAR(M(3, 3), 8.0 * area / 45.0, 1e-14);
  const auto m = tri6_lumped_mass(area);
  EXPECT_NEAR(m.sum(), area, 1e-14);
  for (int a = 0; a < 6; ++a) EXPECT_GT(m[a], 0.0);
}

template <class M>
Tri6Vector residual(const M& m, const Tri6Cell& c) {
  Tri6Vector r = Tri6Vector::Zero();
  Mat3 F[3];
  EXPECT_TRUE(tri6_internal(m, c, F, r, nullptr));
  return r;
}

template <class M>
void expect_tangent_matches_differences(const M& material) {
  const Eigen::Matrix<double, 6, 2> x = curved_cell();
  Tri6Cell c;
  for (int q = 0; q < 3; ++q) {
    Tri6Gradients dN;
    c.dV_n[q] = tri6_gradients(x, kTri3Rule3[q][0], kTri3Rule3[q][1], kTri3Rule3[q][2], dN) / 6.0;
    c.dN[q] = dN;
    c.F_n[q] = Mat3::Identity();
    c.F_n[q].topLeftCorner<2, 2>() << 1.05, 0.1 * q, -0.05, 0.97;
  }
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-0.05, 0.05);
  for (int a = 0; a < 6; ++a) c.du.row(a) << d(rng), d(rng);
  Tri6Vector r = Tri6Vector::Zero();
  Tri6Matrix K = Tri6Matrix::Zero();
  Mat3 F[3];
  ASSERT_TRUE(tri6_internal(material, c, F, r, &K));
  Tri6Matrix K_fd;
  const double h = 1e-6;
  for (int b = 0; b < 6; ++b)
    for (int k = 0; k < 2; ++k) {
      Tri6Cell p = c, n = c;
      p.du(b, k) += h, n.du(b, k) -= h;
      K_fd.col(2 * b + k) = (residual(material, p) - residual(material, n)) / (2 * h);
    }
  EXPECT_LE((K - K_fd).norm(), 1e-6 * K.norm()) << "K\n" << K << "\nfd\n" << K_fd;
  EXPECT_LE((K - K.transpose()).norm(), 1e-12 * K.norm());  // hyperelastic: symmetric
}

TEST(Tri6Cell, TangentMatchesFiniteDifferencesNeoHooke) { expect_tangent_matches_differences(NeoHooke{30.0, 2.0}); }
TEST(Tri6Cell, TangentMatchesFiniteDifferencesLinearElastic) { expect_tangent_matches_differences(LinearElastic{3.0, 2.0}); }

}  // namespace
}  // namespace loom
