// The integration-domain kernel of seed 001 (systems/assemble/elements/smoothed_domain.hpp): its tangent
// against central finite differences of its residual at random states (edge stencils of 4 and 3 nodes,
// mixed u-p and displacement only, Hencky elastic and viscoplastic with a random history, small-strain
// Hooke), the pressure residual against its closed form, and the triangle's pressure terms; the same in 3D (face
// stencils of 5 and 4 nodes, the tetrahedron's pressure terms, and three equal stretches, where Hencky's spectral
// tangent takes its limit).
#include <gtest/gtest.h>

#include <random>

#include "systems/assemble/elements/smoothed_domain.hpp"

namespace loom {
namespace {

// The pressure point of an edge (face) domain: the mean of its first D stencil nodes.
template <int D>
double pressure_weight_of_slot(int a) {
  return a < D ? 1.0 / D : 0.0;
}

template <int NEN, int D = 2>
SmoothedDomain<NEN, D> random_domain(std::mt19937& rng, double strain) {
  std::normal_distribution<double> normal;
  SmoothedDomain<NEN, D> d;
  // Gradients of a linear-complete stencil: sum b = 0 (any values would do for the derivative check).
  for (int a = 0; a < NEN; ++a)
    for (int i = 0; i < D; ++i) d.b(a, i) = normal(rng);
  d.b.row(NEN - 1) = -d.b.topRows(NEN - 1).colwise().sum();
  // A state that exists and is not near a fold (det f >= 0.5: a central difference of step 1e-6 stays on one side):
  // in 3D, five random gradients of unit size can fold the domain at strain 0.1.
  do {
    for (int a = 0; a < NEN; ++a) {
      for (int i = 0; i < D; ++i) d.du(a, i) = strain * normal(rng);
      d.p[a] = 0.3 * normal(rng);
      d.Np[a] = pressure_weight_of_slot<D>(a);
    }
  } while ((Mat3::Identity().template topLeftCorner<D, D>() + d.du.transpose() * d.b).determinant() < 0.5);
  d.V_n = 0.7;
  Mat3 X = Mat3::Zero();
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) X(i, j) = 0.2 * normal(rng);
  d.be_n = Mat3::Identity() + X * X.transpose();
  if (D == 2) d.be_n(2, 2) = 1.05;
  d.dt = 0.1;
  return d;
}

template <int NEN, bool Mixed, class MaterialT, int D>
void check_tangent(const MaterialT& m, const SmoothedDomain<NEN, D>& d0, double tol, bool* plastic = nullptr) {
  using L = SmoothedLayout<NEN, Mixed, D>;
  typename L::Vector r0 = L::Vector::Zero();
  typename L::Matrix K = L::Matrix::Zero();
  SmoothedDomainState st;
  ASSERT_TRUE((smoothed_domain<NEN, Mixed>(m, d0, r0, &K, st)));
  if constexpr (std::is_same_v<MaterialT, HenckyPerzyna>) {
    if (plastic) {
      HistoryResponse h;
      Mat3 f = Mat3::Identity();
      f.topLeftCorner<D, D>() += d0.du.transpose() * d0.b;
      m.update(f, d0.be_n, d0.dt, Mixed, false, h);
      *plastic = h.plastic;
    }
  }
  const double h = 1e-6;
  typename L::Matrix fd;
  for (int k = 0; k < L::size; ++k) {
    SmoothedDomain<NEN, D> dp = d0, dm = d0;
    const int a = k / L::per_node, c = k % L::per_node;
    if (c < D) dp.du(a, c) += h, dm.du(a, c) -= h;
    else dp.p[a] += h, dm.p[a] -= h;
    typename L::Vector rp = L::Vector::Zero(), rm = L::Vector::Zero();
    SmoothedDomainState s;
    ASSERT_TRUE((smoothed_domain<NEN, Mixed>(m, dp, rp, nullptr, s)));
    ASSERT_TRUE((smoothed_domain<NEN, Mixed>(m, dm, rm, nullptr, s)));
    fd.col(k) = (rp - rm) / (2 * h);
  }
  EXPECT_LT((K - fd).cwiseAbs().maxCoeff(), tol * (1.0 + K.cwiseAbs().maxCoeff())) << "K\n" << K << "\nfd\n" << fd;
  // The residual without the tangent is the same.
  typename L::Vector r1 = L::Vector::Zero();
  ASSERT_TRUE((smoothed_domain<NEN, Mixed>(m, d0, r1, nullptr, st)));
  EXPECT_LT((r1 - r0).norm(), 1e-14 * (1.0 + r0.norm()));
}

TEST(SmoothedDomain, TangentMatchesFiniteDifferencesHencky) {
  std::mt19937 rng(7);
  int plastic = 0;
  for (int trial = 0; trial < 6; ++trial)
    for (const double tau0 : {0.05, 1e300}) {
      const HenckyPerzyna m{7.0, 3.0, tau0, 0.5};
      bool pl = false;
      check_tangent<4, true>(m, random_domain<4>(rng, 0.1), 1e-7, &pl);
      plastic += pl;
      check_tangent<3, true>(m, random_domain<3>(rng, 0.1), 1e-7);
      check_tangent<4, false>(m, random_domain<4>(rng, 0.1), 1e-7);
      check_tangent<3, false>(m, random_domain<3>(rng, 0.1), 1e-7);
    }
  EXPECT_GE(plastic, 4);  // the plastic branch was exercised
}

TEST(SmoothedDomain, TangentMatchesFiniteDifferencesSmallStrain) {
  std::mt19937 rng(3);
  const LinearElastic m{4.0, 1.5};
  for (int trial = 0; trial < 3; ++trial) {
    check_tangent<4, true>(m, random_domain<4>(rng, 0.1), 1e-8);
    check_tangent<3, false>(m, random_domain<3>(rng, 0.1), 1e-8);
  }
}

// R_p = N_p ln J / J V_0 with J = det f J_n, V_0 = V_n / J_n (seed 001 eq 41), and the stress of the domain is
// tau' / J + p I with p the pressure at the edge's midpoint.
TEST(SmoothedDomain, PressureResidualAndStress) {
  std::mt19937 rng(11);
  const HenckyPerzyna m{7.0, 3.0};
  const SmoothedDomain<4> d = random_domain<4>(rng, 0.1);
  SmoothedLayout<4, true>::Vector r = SmoothedLayout<4, true>::Vector::Zero();
  SmoothedDomainState st;
  ASSERT_TRUE((smoothed_domain<4, true>(m, d, r, nullptr, st)));
  Mat3 f = Mat3::Identity();
  f.topLeftCorner<2, 2>() += d.du.transpose() * d.b;
  const double J_n = std::sqrt(d.be_n.determinant()), J = f.determinant() * J_n;
  for (int a = 0; a < 4; ++a) EXPECT_NEAR(r[3 * a + 2], d.Np[a] * std::log(J) / J * d.V_n / J_n, 1e-14);
  const double p = 0.5 * (d.p[0] + d.p[1]);
  EXPECT_NEAR(st.sigma.trace() / 3.0, p, 1e-12);  // tau' is deviatoric
  EXPECT_NEAR(st.j, f.determinant(), 1e-15);
  EXPECT_NEAR(std::sqrt(st.be.determinant()), J, 1e-12);
}

// The entries against seed 001 eqs 42 and 48 written out: K_pp,K,ab = A (1 + d_ab) / (12 K) and
// K_stab,ab = (alpha / G) (A (1 + d_ab) / 12 - A / 9); R_p = -(K_pp,K + K_stab) p.
TEST(TrianglePressureTerms, EntriesAreThoseOfTheSeed) {
  const double A0 = 0.6, inv_K = 0.25, a_over_G = 2.0;
  Mat3 K = Mat3::Zero();
  Vec3 r = Vec3::Zero();
  const Vec3 p(0.3, -1.0, 2.0);
  triangle_pressure_terms(A0, inv_K, a_over_G, p, r, &K);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const double delta = a == b ? 1.0 : 0.0;
      const double expected = -(A0 * (1 + delta) / 12.0 * inv_K + a_over_G * (A0 * (1 + delta) / 12.0 - A0 / 9.0));
      EXPECT_NEAR(K(a, b), expected, 1e-15);
    }
  EXPECT_LT((r - K * p).norm(), 1e-15);
}

TEST(TrianglePressureTerms, MassAndProjectionMatrices) {
  const double A0 = 0.6, inv_K = 0.25, a_over_G = 2.0;
  Mat3 K = Mat3::Zero();
  Vec3 r = Vec3::Zero();
  const Vec3 p(1.0, 1.0, 1.0);  // constant pressure: the projection term vanishes
  triangle_pressure_terms(A0, inv_K, a_over_G, p, r, &K);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(r[a], -inv_K * A0 / 3.0, 1e-15);
  EXPECT_LT((K - K.transpose()).norm(), 1e-15);
  Mat3 K_stab = Mat3::Zero();
  Vec3 r_stab = Vec3::Zero();
  triangle_pressure_terms(A0, 0.0, a_over_G, Vec3(0.3, -1.0, 2.0), r_stab, &K_stab);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(K_stab.row(a).sum(), 0.0, 1e-15);
  EXPECT_LT(Eigen::SelfAdjointEigenSolver<Mat3>(K_stab).eigenvalues().maxCoeff(), 1e-15);  // -K_stab is positive semi-definite
}

TEST(SmoothedDomain3d, TangentMatchesFiniteDifferencesHencky) {
  std::mt19937 rng(17);
  int plastic = 0;
  for (int trial = 0; trial < 6; ++trial)
    for (const double tau0 : {0.05, 1e300}) {
      const HenckyPerzyna m{7.0, 3.0, tau0, 0.5};
      bool pl = false;
      check_tangent<5, true>(m, random_domain<5, 3>(rng, 0.1), 1e-7, &pl);
      plastic += pl;
      check_tangent<4, true>(m, random_domain<4, 3>(rng, 0.1), 1e-7);
      check_tangent<5, false>(m, random_domain<5, 3>(rng, 0.1), 1e-7);
      check_tangent<4, false>(m, random_domain<4, 3>(rng, 0.1), 1e-7);
    }
  EXPECT_GE(plastic, 4);
}

// Hyperelastic materials on the domains (elements/smoothed_hyperelastic.hpp): b_n as history, F = f sqrt(b_n); mixed
// with the deviatoric part and the material's own volumetric law. 2D and 3D, u-p and u.
TEST(SmoothedDomain, TangentMatchesFiniteDifferencesHyperelastic) {
  std::mt19937 rng(31);
  const NeoHooke neo{5.0, 2.0};
  const NeoHookeSplit split{2.0, 1.0 / 8.0};
  for (int trial = 0; trial < 3; ++trial) {
    check_tangent<4, true>(neo, random_domain<4>(rng, 0.1), 1e-7);
    check_tangent<3, false>(neo, random_domain<3>(rng, 0.1), 1e-7);
    check_tangent<4, true>(split, random_domain<4>(rng, 0.1), 1e-7);
    check_tangent<4, false>(split, random_domain<4>(rng, 0.1), 1e-7);
    check_tangent<5, true>(neo, random_domain<5, 3>(rng, 0.1), 1e-7);
    check_tangent<4, false>(neo, random_domain<4, 3>(rng, 0.1), 1e-7);
    check_tangent<5, true>(split, random_domain<5, 3>(rng, 0.1), 1e-7);
    check_tangent<5, false>(split, random_domain<5, 3>(rng, 0.1), 1e-7);
  }
}

// The hyperelastic branch against the material itself: with b_n = F_n F_n^T for a non-symmetric F_n (another root than
// the one the kernel takes), the stress is the Kirchhoff stress tau = P(F) F^T of F = f F_n over J, the node forces
// V_n (tau f^-T / J_n) b~_I; the mixed pressure residual is N_p (J - 1) V_0 for neo_hooke_split and N_p pi / K V_0 for
// neo_hooke (pi its mean Cauchy stress).
TEST(SmoothedDomain, HyperelasticStressIsTheMaterialsAtTheTotalDeformation) {
  std::mt19937 rng(37);
  SmoothedDomain<5, 3> d = random_domain<5, 3>(rng, 0.1);
  Mat3 F_n;
  F_n << 1.1, 0.2, -0.1, 0.05, 0.9, 0.15, -0.1, 0.1, 1.05;  // not symmetric: another root of the same b_n
  d.be_n = F_n * F_n.transpose();
  const Mat3 f = Mat3::Identity() + d.du.transpose() * d.b;
  const Mat3 F = f * F_n;
  const double J = F.determinant(), V0 = d.V_n / F_n.determinant();
  const NeoHooke neo{5.0, 2.0};
  Mat3 P;
  ASSERT_TRUE(neo.stress(F, P));
  const Mat3 tau = P * F.transpose();
  SmoothedLayout<5, false, 3>::Vector r = SmoothedLayout<5, false, 3>::Vector::Zero();
  SmoothedDomainState st;
  ASSERT_TRUE((smoothed_domain<5, false>(neo, d, r, nullptr, st)));
  EXPECT_LT((st.sigma - tau / J).norm(), 1e-13 * tau.norm());
  EXPECT_LT((st.be - F * F.transpose()).norm(), 1e-13);
  // Node forces: V_n (tau f^-T / J_n) b~_I.
  const Mat3 P_f = tau * f.inverse().transpose() / F_n.determinant();
  for (int a = 0; a < 5; ++a) {
    const Vec3 expected = d.V_n * P_f * d.b.row(a).transpose();
    EXPECT_LT((r.segment<3>(3 * a) - expected).norm(), 1e-13 * (1.0 + expected.norm()));
  }
  SmoothedLayout<5, true, 3>::Vector rm = SmoothedLayout<5, true, 3>::Vector::Zero();
  ASSERT_TRUE((smoothed_domain<5, true>(neo, d, rm, nullptr, st)));
  const double pi = tau.trace() / (3.0 * J), K = neo.lambda + 2.0 * neo.mu / 3.0, p = d.Np.dot(d.p);
  for (int a = 0; a < 5; ++a) EXPECT_NEAR(rm[4 * a + 3], d.Np[a] * pi / K * V0, 1e-14);
  EXPECT_LT((st.sigma - (tau / J - pi * Mat3::Identity() + p * Mat3::Identity())).norm(), 1e-13 * tau.norm());
  const NeoHookeSplit split{2.0, 1.0 / 8.0};
  rm.setZero();
  ASSERT_TRUE((smoothed_domain<5, true>(split, d, rm, nullptr, st)));
  for (int a = 0; a < 5; ++a) EXPECT_NEAR(rm[4 * a + 3], d.Np[a] * (J - 1.0) * V0, 1e-14);
  EXPECT_NEAR(st.sigma.trace() / 3.0, p, 1e-13);  // the isochoric part is deviatoric
}

TEST(SmoothedDomain3d, TangentMatchesFiniteDifferencesSmallStrain) {
  std::mt19937 rng(23);
  const LinearElastic m{4.0, 1.5};
  for (int trial = 0; trial < 3; ++trial) {
    check_tangent<5, true>(m, random_domain<5, 3>(rng, 0.1), 1e-8);
    check_tangent<4, false>(m, random_domain<4, 3>(rng, 0.1), 1e-8);
  }
}

// f = lambda I on a tetrahedron domain (du_I = (lambda - 1) x_I, b~ = grad N) from b^e_n = I: the three stretches of
// the trial b^e are equal, where the spectral form of Hencky's tangent has to take its limit; elastic and at yield.
TEST(SmoothedDomain3d, TangentAtThreeEqualStretches) {
  Eigen::Matrix<double, 4, 3> x;
  x << 0.1, 0.0, 0.2, 1.1, 0.1, 0.0, 0.2, 0.9, 0.1, 0.0, 0.3, 1.2;
  Mat3 J;
  for (int j = 0; j < 3; ++j) J.col(j) = (x.row(j + 1) - x.row(0)).transpose();
  SmoothedDomain<4, 3> d;
  d.b.bottomRows<3>() = J.inverse();
  d.b.row(0) = -d.b.bottomRows<3>().colwise().sum();
  d.V_n = J.determinant() / 6.0;
  d.du = 0.02 * x;  // f = 1.02 I
  for (int a = 0; a < 4; ++a) d.p[a] = 0.1 * a, d.Np[a] = 0.25;
  d.dt = 0.1;
  for (const double tau0 : {0.05, 1e300}) {
    const HenckyPerzyna m{7.0, 3.0, tau0, 0.5};
    check_tangent<4, true>(m, d, 1e-7);
    check_tangent<4, false>(m, d, 1e-7);
  }
}

// R_p = N_p ln J / J V_0 in 3D; the stress's mean is the pressure at the face's centroid (a third of each node's).
TEST(SmoothedDomain3d, PressureResidualAndStress) {
  std::mt19937 rng(29);
  const HenckyPerzyna m{7.0, 3.0};
  const SmoothedDomain<5, 3> d = random_domain<5, 3>(rng, 0.1);
  SmoothedLayout<5, true, 3>::Vector r = SmoothedLayout<5, true, 3>::Vector::Zero();
  SmoothedDomainState st;
  ASSERT_TRUE((smoothed_domain<5, true>(m, d, r, nullptr, st)));
  const Mat3 f = Mat3::Identity() + d.du.transpose() * d.b;
  const double J_n = std::sqrt(d.be_n.determinant()), J = f.determinant() * J_n;
  for (int a = 0; a < 5; ++a) EXPECT_NEAR(r[4 * a + 3], d.Np[a] * std::log(J) / J * d.V_n / J_n, 1e-14);
  EXPECT_NEAR(st.sigma.trace() / 3.0, (d.p[0] + d.p[1] + d.p[2]) / 3.0, 1e-12);
  EXPECT_NEAR(std::sqrt(st.be.determinant()), J, 1e-12);
}

// The tetrahedron's terms: K_pp,K,ab = V (1 + d_ab) / (20 K), K_stab,ab = (alpha / G) (V (1 + d_ab) / 20 - V / 16); a
// constant pressure gives -V p / (4 K) per node and no projection term; -K_stab is positive semi-definite.
TEST(TetPressureTerms, EntriesAreThoseOfTheMassAndItsProjection) {
  using V4 = Eigen::Vector4d;
  using M4 = Eigen::Matrix4d;
  const double V0 = 0.6, inv_K = 0.25, a_over_G = 2.0;
  M4 K = M4::Zero();
  V4 r = V4::Zero();
  const V4 p(0.3, -1.0, 2.0, 0.7);
  simplex_pressure_terms<3>(V0, inv_K, a_over_G, p, r, &K);
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      const double delta = a == b ? 1.0 : 0.0;
      EXPECT_NEAR(K(a, b), -(V0 * (1 + delta) / 20.0 * inv_K + a_over_G * (V0 * (1 + delta) / 20.0 - V0 / 16.0)), 1e-15);
    }
  EXPECT_LT((r - K * p).norm(), 1e-15);
  V4 r_const = V4::Zero();
  simplex_pressure_terms<3>(V0, inv_K, a_over_G, V4::Ones(), r_const, nullptr);
  for (int a = 0; a < 4; ++a) EXPECT_NEAR(r_const[a], -inv_K * V0 / 4.0, 1e-15);
  M4 K_stab = M4::Zero();
  V4 r_stab = V4::Zero();
  simplex_pressure_terms<3>(V0, 0.0, a_over_G, p, r_stab, &K_stab);
  for (int a = 0; a < 4; ++a) EXPECT_NEAR(K_stab.row(a).sum(), 0.0, 1e-15);
  EXPECT_LT(Eigen::SelfAdjointEigenSolver<M4>(K_stab).eigenvalues().maxCoeff(), 1e-15);
}

}  // namespace
}  // namespace loom
