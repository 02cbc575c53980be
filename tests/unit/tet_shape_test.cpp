// Tetrahedra (systems/assemble/elements/tet4.hpp, tet10.hpp, element_mass.hpp): signed volume and gradients
// of tet4; partition of unity, nodal interpolation and linear and quadratic completeness of tet10 on a general
// (straight-sided) tetrahedron; exactness of the 4-point (degree 2) and 14-point (degree 5) rules on every
// monomial, and the degree they stop being exact at; the mass matrices.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "systems/assemble/elements/element_mass.hpp"
#include "systems/assemble/elements/tet10.hpp"
#include "systems/assemble/elements/tet4.hpp"
#include "tests/unit/general_tetrahedron.hpp"

namespace loom {
namespace {

Tet4Corners corners() { return testing::general_tetrahedron(); }

Tet10Nodes tet10_nodes(const Tet4Corners& x) {
  Tet10Nodes n;
  n.topRows<4>() = x;
  for (int e = 0; e < 6; ++e) n.row(4 + e) = 0.5 * (x.row(kTet10Edges[e][0]) + x.row(kTet10Edges[e][1]));
  return n;
}

// x(l) of a straight tetrahedron.
Vec3 point(const Tet4Corners& x, const double l[4]) {
  Vec3 p = Vec3::Zero();
  for (int a = 0; a < 4; ++a) p += l[a] * x.row(a).transpose();
  return p;
}

// Integral of xi^i eta^j zeta^k over the reference tetrahedron divided by its volume 1/6: 6 i! j! k! / (i+j+k+3)!.
double reference_moment(int i, int j, int k) {
  return 6.0 * std::tgamma(i + 1) * std::tgamma(j + 1) * std::tgamma(k + 1) / std::tgamma(i + j + k + 4);
}

// Largest error of `rule` over the monomials of total degree `degree` (points as barycentric l, weights w).
double monomial_error(int degree, const std::function<void(const std::function<void(const double*, double)>&)>& rule) {
  double worst = 0.0;
  for (int i = 0; i <= degree; ++i)
    for (int j = 0; i + j <= degree; ++j) {
      const int k = degree - i - j;
      double sum = 0.0;
      rule([&](const double* l, double w) { sum += w * std::pow(l[1], i) * std::pow(l[2], j) * std::pow(l[3], k); });
      worst = std::max(worst, std::abs(sum - reference_moment(i, j, k)));
    }
  return worst;
}

void rule4(const std::function<void(const double*, double)>& f) {
  for (const auto& l : kTet4Rule4) f(l, 0.25);
}
void rule14(const std::function<void(const double*, double)>& f) {
  for (const auto& p : kTetrahedronRule14) f(p.l, p.w);
}

}  // namespace

TEST(Tet4, SignedVolumeOfAHandCheckedTetrahedron) {
  Tet4Corners x;
  Tet4Gradients dN;
  x << 0, 0, 0, 2, 0, 0, 0, 1, 0, 0, 0, 3;
  EXPECT_DOUBLE_EQ(tet4_gradients(x, dN), 1.0);
  Tet4Gradients expected;  // N1 = x/2, N2 = y, N3 = z/3, N0 = 1 - the others
  expected << -0.5, -1, -1.0 / 3, 0.5, 0, 0, 0, 1, 0, 0, 0, 1.0 / 3;
  EXPECT_LE((dN - expected).norm(), 1e-15);
  x.row(2).swap(x.row(3));
  EXPECT_DOUBLE_EQ(tet4_gradients(x, dN), -1.0);  // an odd permutation inverts it
}

TEST(Tet4, GradientsReproduceAnAffineField) {
  const Tet4Corners x = corners();
  Tet4Gradients dN;
  ASSERT_GT(tet4_gradients(x, dN), 0.0);
  const Vec3 g(0.7, -1.3, 2.1);  // u = g . x + 5
  Eigen::Vector4d u;
  for (int a = 0; a < 4; ++a) u[a] = g.dot(x.row(a).transpose()) + 5.0;
  EXPECT_LE((dN.transpose() * u - g).norm(), 1e-13);
  EXPECT_LE(dN.colwise().sum().norm(), 1e-14);
}

TEST(Tet10, InterpolatesAtItsNodesAndSumsToOne) {
  const double nodes[10][4] = {{1, 0, 0, 0},     {0, 1, 0, 0},     {0, 0, 1, 0},     {0, 0, 0, 1},     {.5, .5, 0, 0},
                               {0, .5, .5, 0},   {.5, 0, .5, 0},   {.5, 0, 0, .5},   {0, .5, 0, .5},   {0, 0, .5, .5}};
  for (int b = 0; b < 10; ++b) {
    const Tet10Values N = tet10_values(nodes[b]);
    for (int a = 0; a < 10; ++a) EXPECT_NEAR(N[a], a == b ? 1.0 : 0.0, 1e-15) << a << " at node " << b;
  }
  for (const auto& p : kTetrahedronRule14) {
    EXPECT_NEAR(tet10_values(p.l).sum(), 1.0, 1e-15);
    EXPECT_LE(tet10_reference_gradients(p.l).colwise().sum().norm(), 1e-14);
  }
}

TEST(Tet10, ReproducesQuadraticFieldsAndTheirGradients) {
  const Tet4Corners c = corners();
  const Tet10Nodes x = tet10_nodes(c);
  // u(x) = 1 + g.x + x^T H x, grad u = g + 2 H x.
  const Vec3 g(0.3, -0.8, 1.1);
  Mat3 H;
  H << 0.5, 0.2, -0.1, 0.2, -0.7, 0.4, -0.1, 0.4, 0.9;
  Tet10Values u;
  for (int a = 0; a < 10; ++a) {
    const Vec3 p = x.row(a).transpose();
    u[a] = 1.0 + g.dot(p) + p.dot(H * p);
  }
  Tet4Gradients dN4;
  const double volume = tet4_gradients(c, dN4);
  for (const auto& q : kTetrahedronRule14) {
    const Vec3 p = point(c, q.l);
    EXPECT_NEAR(tet10_values(q.l).dot(u), 1.0 + g.dot(p) + p.dot(H * p), 1e-13);
    Tet10Gradients dN;
    EXPECT_NEAR(tet10_gradients(x, q.l, dN), 6.0 * volume, 1e-13);  // straight cell: det J = 6 V everywhere
    EXPECT_LE((dN.transpose() * u - (g + 2.0 * H * p)).norm(), 1e-12);
  }
}

TEST(TetrahedronRules, FourPointRuleIsExactToDegreeTwoOnly) {
  for (int d = 0; d <= 2; ++d) EXPECT_LE(monomial_error(d, rule4), 1e-15) << "degree " << d;
  EXPECT_GT(monomial_error(3, rule4), 1e-4);
}

TEST(TetrahedronRules, FourteenPointRuleIsExactToDegreeFiveOnly) {
  double weights = 0.0;
  for (const auto& p : kTetrahedronRule14) {
    EXPECT_GT(p.w, 0.0);
    EXPECT_NEAR(p.l[0] + p.l[1] + p.l[2] + p.l[3], 1.0, 1e-15);
    weights += p.w;
  }
  EXPECT_NEAR(weights, 1.0, 1e-15);
  for (int d = 0; d <= 5; ++d) EXPECT_LE(monomial_error(d, rule14), 2e-16) << "degree " << d;
  EXPECT_GT(monomial_error(6, rule14), 1e-7);
}

TEST(TetMass, Tet4ConsistentMassIsTheIntegralOfProductsAndLumpsToQuarters) {
  const double V = 0.37;
  const Eigen::Matrix4d M = tet4_consistent_mass(V);
  Eigen::Matrix4d integrated = Eigen::Matrix4d::Zero();
  for (const auto& p : kTetrahedronRule14) {
    const Eigen::Vector4d N(p.l[0], p.l[1], p.l[2], p.l[3]);
    integrated += p.w * V * N * N.transpose();
  }
  EXPECT_LE((M - integrated).norm(), 1e-15);
  EXPECT_NEAR(M.sum(), V, 1e-15);
  EXPECT_NEAR(M.rowwise().sum().maxCoeff(), V / 4, 1e-16);
}

TEST(TetMass, Tet10MassHasTheTotalAndAPositiveLumping) {
  const double V = 0.37;
  const Eigen::Matrix<double, 10, 10> M = tet10_consistent_mass(V);
  EXPECT_NEAR(M.sum(), V, 1e-15);
  // Closed forms (exact integrals of the quadratic products): M_00 = V/70, M_44 = 8V/105, row sums -V/20 at the
  // corners and V/5 at the mid-nodes (which is why the row sum cannot be used as a lumped mass).
  EXPECT_NEAR(M(0, 0), V / 70, 1e-16);
  EXPECT_NEAR(M(4, 4), 8 * V / 105, 1e-16);
  EXPECT_NEAR(M.row(0).sum(), -V / 20, 1e-16);
  EXPECT_NEAR(M.row(4).sum(), V / 5, 1e-16);
  const Tet10Values m = tet10_lumped_mass(V);
  EXPECT_NEAR(m.sum(), V, 1e-15);
  EXPECT_GT(m.minCoeff(), 0.0);
}

}  // namespace loom
