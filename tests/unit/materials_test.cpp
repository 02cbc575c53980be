// Materials (systems/assemble/materials): the stress is the derivative of the strain energy and the 9x9
// tangent the derivative of the stress, both checked by central finite differences of energies written
// here from their formulas (seed 000 eq 48-51; seed 003 §2.2; small-strain Hooke), at random F with det F > 0.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "systems/assemble/materials/material.hpp"
#include "tests/support/stress_derivative.hpp"

namespace loom {
namespace {

constexpr double kLambda = 2.3, kMu = 0.7;

// seed 000 eq (48): psi_0 = lambda/2 ln^2 J + mu/2 (F:F - 3) - mu ln J
double neo_hooke_energy(const Mat3& F, double lambda, double mu) {
  const double lnJ = std::log(F.determinant());
  return 0.5 * lambda * lnJ * lnJ + 0.5 * mu * (F.squaredNorm() - 3.0) - mu * lnJ;
}

// Small strain: psi = lambda/2 tr(eps)^2 + mu eps:eps with eps = sym(F) - I.
double linear_elastic_energy(const Mat3& F, double lambda, double mu) {
  const Mat3 eps = 0.5 * (F + F.transpose()) - Mat3::Identity();
  return 0.5 * lambda * eps.trace() * eps.trace() + mu * eps.squaredNorm();
}

Mat3 unit(int k, int l) {
  Mat3 E = Mat3::Zero();
  E(k, l) = 1.0;
  return E;
}

template <class Energy>
Mat3 energy_derivative(const Energy& psi, const Mat3& F, double h = 1e-5) {
  Mat3 P;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) P(k, l) = (psi(F + h * unit(k, l)) - psi(F - h * unit(k, l))) / (2 * h);
  return P;
}

using testing::stress_derivative;

// Random deformation gradients with det F > 0.5: plane strain (F33 = 1, no out-of-plane shear) or general.
std::vector<Mat3> random_deformations(bool plane_strain, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-0.4, 0.4);
  std::vector<Mat3> r;
  while (int(r.size()) < n) {
    Mat3 F = Mat3::Identity();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) F(i, j) += d(rng);
    if (plane_strain) F.row(2) = Vec3(0, 0, 1).transpose(), F.col(2) = Vec3(0, 0, 1);
    if (F.determinant() > 0.5) r.push_back(F);
  }
  return r;
}

double relative_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& reference) {
  return (a - reference).norm() / reference.norm();
}

struct Case {
  bool plane_strain;
  unsigned seed;
};
const Case kCases[] = {{true, 11}, {false, 12}};

}  // namespace

TEST(NeoHooke, StressIsTheDerivativeOfTheEnergy) {
  const NeoHooke m{kLambda, kMu};
  for (const Case& c : kCases)
    for (const Mat3& F : random_deformations(c.plane_strain, 5, c.seed)) {
      Mat3 P;
      ASSERT_TRUE(m.stress(F, P));
      const Mat3 P_fd = energy_derivative([](const Mat3& G) { return neo_hooke_energy(G, kLambda, kMu); }, F);
      EXPECT_LE(relative_error(P, P_fd), 1e-6) << "F =\n" << F;
    }
}

TEST(NeoHooke, TangentIsTheDerivativeOfTheStress) {
  for (const double lambda : {kLambda, 1e3}) {  // compressible and nearly incompressible
    const NeoHooke m{lambda, kMu};
    for (const Case& c : kCases)
      for (const Mat3& F : random_deformations(c.plane_strain, 5, c.seed)) {
        Mat3 P, P_stress;
        Mat9 A;
        ASSERT_TRUE(m.stress_tangent(F, P, A));
        ASSERT_TRUE(m.stress(F, P_stress));
        EXPECT_LE((P - P_stress).norm(), 1e-14 * P.norm());  // both entry points agree
        EXPECT_LE(relative_error(A, stress_derivative(m, F)), 1e-6) << "lambda = " << lambda << ", F =\n" << F;
      }
  }
}

TEST(NeoHooke, IsStressFreeAtTheIdentity) {
  const NeoHooke m{kLambda, kMu};
  Mat3 P;
  ASSERT_TRUE(m.stress(Mat3::Identity(), P));
  EXPECT_LE(P.norm(), 1e-15);
}

TEST(NeoHooke, TangentAtTheIdentityIsHookesTensor) {
  const NeoHooke nh{kLambda, kMu};
  Mat3 P;
  Mat9 A;
  ASSERT_TRUE(nh.stress_tangent(Mat3::Identity(), P, A));
  Mat9 hooke;  // lambda d_ij d_kl + mu (d_ik d_jl + d_il d_jk)
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          hooke(ij(i, j), ij(k, l)) = kLambda * (i == j) * (k == l) + kMu * ((i == k) * (j == l) + (i == l) * (j == k));
  EXPECT_LE((A - hooke).norm(), 1e-14);
}

TEST(NeoHooke, RejectsNonPositiveJacobian) {
  const NeoHooke m{kLambda, kMu};
  Mat3 P;
  Mat9 A;
  const Mat3 inverted = Vec3(-1.0, 1.0, 1.0).asDiagonal();
  const Mat3 flat = Vec3(1.0, 0.0, 1.0).asDiagonal();
  EXPECT_FALSE(m.stress(inverted, P));
  EXPECT_FALSE(m.stress(flat, P));
  EXPECT_FALSE(m.stress_tangent(inverted, P, A));
  EXPECT_FALSE(m.stress_tangent(flat, P, A));
  Mat3 sigma;
  EXPECT_FALSE(cauchy_stress(Material(m), inverted, sigma));
}

TEST(NeoHooke, CauchyStressIsSymmetricAndMatchesTheSpatialForm) {
  const NeoHooke m{kLambda, kMu};
  for (const Case& c : kCases)
    for (const Mat3& F : random_deformations(c.plane_strain, 5, c.seed + 100)) {
      Mat3 sigma;
      ASSERT_TRUE(cauchy_stress(Material(m), F, sigma));
      EXPECT_LE((sigma - sigma.transpose()).norm(), 1e-13 * sigma.norm());
      // sigma = (mu (b - I) + lambda ln J I) / J, b = F F^T
      const double J = F.determinant();
      const Mat3 expected = (kMu * (F * F.transpose() - Mat3::Identity()) + kLambda * std::log(J) * Mat3::Identity()) / J;
      EXPECT_LE((sigma - expected).norm(), 1e-13 * expected.norm());
    }
}

TEST(LinearElastic, StressIsTheDerivativeOfTheEnergy) {
  const LinearElastic m{kLambda, kMu};
  for (const Case& c : kCases)
    for (const Mat3& F : random_deformations(c.plane_strain, 5, c.seed)) {
      Mat3 P;
      ASSERT_TRUE(m.stress(F, P));
      const Mat3 P_fd = energy_derivative([](const Mat3& G) { return linear_elastic_energy(G, kLambda, kMu); }, F);
      EXPECT_LE(relative_error(P, P_fd), 1e-6) << "F =\n" << F;
    }
}

TEST(LinearElastic, TangentIsTheDerivativeOfTheStress) {
  const LinearElastic m{kLambda, kMu};
  for (const Case& c : kCases)
    for (const Mat3& F : random_deformations(c.plane_strain, 5, c.seed)) {
      Mat3 P;
      Mat9 A;
      ASSERT_TRUE(m.stress_tangent(F, P, A));
      EXPECT_LE(relative_error(A, stress_derivative(m, F)), 1e-6) << "F =\n" << F;
    }
}

TEST(LinearElastic, IsStressFreeAtTheIdentityAndUnderInfinitesimalRotation) {
  const LinearElastic m{kLambda, kMu};
  Mat3 P;
  ASSERT_TRUE(m.stress(Mat3::Identity(), P));
  EXPECT_LE(P.norm(), 1e-15);
  Mat3 W = Mat3::Zero();  // skew: F = I + W has no small strain
  W(0, 1) = 0.1, W(1, 0) = -0.1;
  ASSERT_TRUE(m.stress(Mat3::Identity() + W, P));
  EXPECT_LE(P.norm(), 1e-15);
}

TEST(LinearElastic, UniaxialStrainGivesTheConstrainedModulus) {
  const LinearElastic m{kLambda, kMu};
  const double e = 1e-3;
  Mat3 F = Mat3::Identity();
  F(0, 0) += e;
  Mat3 sigma;
  ASSERT_TRUE(cauchy_stress(Material(m), F, sigma));
  EXPECT_NEAR(sigma(0, 0), (kLambda + 2 * kMu) * e, 1e-15);
  EXPECT_NEAR(sigma(1, 1), kLambda * e, 1e-15);
  EXPECT_NEAR(sigma(2, 2), kLambda * e, 1e-15);
  EXPECT_EQ(sigma(0, 1), 0.0);
}

// seed 003 §2.2: psi = mu/2 (J^(-2/3) F:F - 3) + kappa/2 (J - 1)^2, written here from the formula.
constexpr double kKappa = 5.0;
double split_deviatoric_energy(const Mat3& F, double mu) { return 0.5 * mu * (std::pow(F.determinant(), -2.0 / 3.0) * F.squaredNorm() - 3.0); }
double split_energy(const Mat3& F, double mu, double kappa) {
  const double J = F.determinant();
  return split_deviatoric_energy(F, mu) + 0.5 * kappa * (J - 1.0) * (J - 1.0);
}

// Central differences of a stress-like function of F (9x9 derivative).
template <class StressFn>
Mat9 fd_tangent(const StressFn& stress, const Mat3& F, double h = 1e-6) {
  Mat9 A;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      const Mat3 dP = (stress(F + h * unit(k, l)) - stress(F - h * unit(k, l))) / (2 * h);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) A(ij(i, j), ij(k, l)) = dP(i, j);
    }
  return A;
}

TEST(NeoHookeSplit, StressesAreTheDerivativesOfTheEnergies) {
  const NeoHookeSplit m{kMu, 1.0 / kKappa};
  for (const Case& c : kCases)
    for (const Mat3& F : random_deformations(c.plane_strain, 5, c.seed)) {
      Mat3 P, P_dev;
      ASSERT_TRUE(m.stress(F, P));
      ASSERT_TRUE(m.deviatoric_stress(F, P_dev));
      const Mat3 P_fd = energy_derivative([](const Mat3& G) { return split_energy(G, kMu, kKappa); }, F);
      const Mat3 P_dev_fd = energy_derivative([](const Mat3& G) { return split_deviatoric_energy(G, kMu); }, F);
      EXPECT_LE(relative_error(P, P_fd), 1e-6) << "F =\n" << F;
      EXPECT_LE(relative_error(P_dev, P_dev_fd), 1e-6) << "F =\n" << F;
      EXPECT_NEAR(m.energy(F), split_energy(F, kMu, kKappa), 1e-13);
    }
}

TEST(NeoHookeSplit, TangentsAreTheDerivativesOfTheStresses) {
  for (const double kappa : {kKappa, 1e4}) {
    const NeoHookeSplit m{kMu, 1.0 / kappa};
    for (const Case& c : kCases)
      for (const Mat3& F : random_deformations(c.plane_strain, 5, c.seed + 7)) {
        Mat3 P, P_dev;
        Mat9 A, A_dev, B;
        ASSERT_TRUE(m.stress_tangent(F, P, A));
        ASSERT_TRUE(m.deviatoric_stress_tangent(F, P_dev, A_dev));
        NeoHookeSplit::volume_tangent(F, B);
        EXPECT_LE(relative_error(A, stress_derivative(m, F)), 1e-6) << "kappa = " << kappa << ", F =\n" << F;
        const auto dev = [&](const Mat3& G) { Mat3 Q; EXPECT_TRUE(m.deviatoric_stress(G, Q)); return Q; };
        EXPECT_LE(relative_error(A_dev, fd_tangent(dev, F)), 1e-6) << "F =\n" << F;
        const auto vol = [](const Mat3& G) { return Mat3(G.determinant() * G.inverse().transpose()); };
        EXPECT_LE(relative_error(B, fd_tangent(vol, F)), 1e-6) << "F =\n" << F;
      }
  }
}

TEST(NeoHookeSplit, DeviatoricCauchyStressIsTracelessAndVolumetricPartIsThePressure) {
  const NeoHookeSplit m{kMu, 1.0 / kKappa};
  for (const Mat3& F : random_deformations(false, 5, 31)) {
    Mat3 P_dev, P;
    ASSERT_TRUE(m.deviatoric_stress(F, P_dev));
    ASSERT_TRUE(m.stress(F, P));
    const double J = F.determinant();
    const Mat3 sigma_dev = P_dev * F.transpose() / J;
    EXPECT_LE(std::abs(sigma_dev.trace()), 1e-13 * sigma_dev.norm());
    // sigma = sigma_dev + p I with p = kappa (J - 1) (seed 003 eq 7).
    const Mat3 sigma = P * F.transpose() / J;
    EXPECT_LE((sigma - sigma_dev - kKappa * (J - 1.0) * Mat3::Identity()).norm(), 1e-12 * sigma.norm());
  }
}

TEST(NeoHookeSplit, SmallStrainLimitIsHookeWithBulkAndShearModuli) {
  const NeoHookeSplit m{kMu, 1.0 / kKappa};
  Mat3 P;
  Mat9 A;
  ASSERT_TRUE(m.stress_tangent(Mat3::Identity(), P, A));
  EXPECT_LE(P.norm(), 1e-14);
  const double lambda = kKappa - 2.0 * kMu / 3.0;
  Mat9 hooke;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          hooke(ij(i, j), ij(k, l)) = lambda * (i == j) * (k == l) + kMu * ((i == k) * (j == l) + (i == l) * (j == k));
  EXPECT_LE((A - hooke).norm(), 1e-13);
}

TEST(NeoHookeSplit, IncompressibleLimitKeepsTheDeviatoricPartAndRejectsInversion) {
  const NeoHookeSplit m{kMu, 0.0};
  const Mat3 F = random_deformations(true, 1, 41)[0];
  Mat3 P_dev, P_ref;
  Mat9 A;
  ASSERT_TRUE(m.deviatoric_stress_tangent(F, P_dev, A));
  ASSERT_TRUE((NeoHookeSplit{kMu, 1.0}).deviatoric_stress(F, P_ref));
  EXPECT_LE((P_dev - P_ref).norm(), 1e-14 * P_ref.norm());  // independent of kappa
  EXPECT_NEAR(m.energy(F), split_deviatoric_energy(F, kMu), 1e-14);
  EXPECT_FALSE(m.deviatoric_stress(Vec3(-1.0, 1.0, 1.0).asDiagonal(), P_dev));
}

TEST(MakeMaterial, MapsTheModelAndLameConstants) {
  MaterialSpec spec;
  spec.model = MaterialModel::linear_elastic;
  spec.lambda = 3.0, spec.mu = 4.0;
  const Material le = make_material(spec);
  ASSERT_TRUE(std::holds_alternative<LinearElastic>(le));
  EXPECT_EQ(std::get<LinearElastic>(le).lambda, 3.0);
  EXPECT_EQ(std::get<LinearElastic>(le).mu, 4.0);
  spec.model = MaterialModel::neo_hooke;
  const Material nh = make_material(spec);
  ASSERT_TRUE(std::holds_alternative<NeoHooke>(nh));
  EXPECT_EQ(std::get<NeoHooke>(nh).mu, 4.0);
  spec.model = MaterialModel::neo_hooke_split;
  spec.K = 8.0;
  const Material split = make_material(spec);
  ASSERT_TRUE(std::holds_alternative<NeoHookeSplit>(split));
  EXPECT_EQ(std::get<NeoHookeSplit>(split).mu, 4.0);
  EXPECT_EQ(std::get<NeoHookeSplit>(split).inv_kappa, 1.0 / 8.0);
  spec.K = std::numeric_limits<double>::infinity();  // nu = 1/2
  EXPECT_EQ(std::get<NeoHookeSplit>(make_material(spec)).inv_kappa, 0.0);
}

}  // namespace loom
