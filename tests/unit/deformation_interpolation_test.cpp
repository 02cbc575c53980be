// Interpolation of deformation gradients (systems/map/deformation_interpolation.hpp; seed 000 eqs 22-23):
// the polar logarithm and its inverse, and what ISO0 / ISO1 / ISO2 preserve.
//
// Fixtures are random but seeded: F = R(axis, angle) U with U symmetric positive definite, det F > 0,
// rotation angles below 3 rad (log R is the principal logarithm; at pi it is not unique).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "systems/map/deformation_interpolation.hpp"

namespace loom {
namespace {

struct Random {
  std::mt19937_64 gen{20240607};
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(gen); }

  Mat3 rotation(double max_angle) {
    Vec3 axis(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    axis.normalize();
    return rotation_from_log(skew(uniform(0.0, max_angle) * axis));
  }
  // Symmetric positive definite with eigenvalues in [lo, hi].
  Mat3 stretch(double lo, double hi) {
    const Mat3 Q = rotation(3.0);
    const Vec3 l(uniform(lo, hi), uniform(lo, hi), uniform(lo, hi));
    return Q * l.asDiagonal() * Q.transpose();
  }
  Mat3 deformation(double max_angle = 3.0) { return rotation(max_angle) * stretch(0.3, 3.0); }
  // A plane-strain gradient: in-plane rotation and stretch, F33 = 1.
  Mat3 plane(double max_angle = 3.0) {
    const double t = uniform(-max_angle, max_angle), c = std::cos(t), s = std::sin(t);
    Mat3 R = Mat3::Identity();
    R(0, 0) = c, R(0, 1) = -s, R(1, 0) = s, R(1, 1) = c;
    const double a = uniform(0.0, 3.0), l1 = uniform(0.3, 3.0), l2 = uniform(0.3, 3.0);
    Mat3 U = Mat3::Identity();
    U(0, 0) = l1 * std::cos(a) * std::cos(a) + l2 * std::sin(a) * std::sin(a);
    U(1, 1) = l1 * std::sin(a) * std::sin(a) + l2 * std::cos(a) * std::cos(a);
    U(0, 1) = U(1, 0) = (l1 - l2) * std::sin(a) * std::cos(a);
    return R * U;
  }
  // Barycentric weights of a random point in a triangle.
  void weights(double (&w)[3]) {
    double a = uniform(0, 1), b = uniform(0, 1);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    w[0] = 1 - a - b, w[1] = a, w[2] = b;
  }
};

Mat3 isochoric(const Mat3& F) { return F / std::cbrt(F.determinant()); }

// exp(log) round trip: F = R U is recovered to round-off; log U is symmetric with tr log U = ln det F
// (eq 23), log R is skew. 1e-12 relative: a 3x3 symmetric eigen-solve and Rodrigues each lose a few ulps
// times the condition of the stretches (<= 10 here).
TEST(PolarLog, RoundTripRecoversTheDeformationGradient) {
  Random rnd;
  double worst = 0.0;
  for (int k = 0; k < 1000; ++k) {
    const Mat3 F = k % 2 ? rnd.deformation() : rnd.plane();
    const PolarLog p = polar_log(F);
    EXPECT_LE((p.log_U - p.log_U.transpose()).norm(), 1e-14 * (1.0 + p.log_U.norm()));
    EXPECT_LE((p.log_R + p.log_R.transpose()).norm(), 1e-14 * (1.0 + p.log_R.norm()));
    EXPECT_NEAR(p.log_U.trace(), std::log(F.determinant()), 1e-13);
    const double err = (from_polar_log(p) - F).norm() / F.norm();
    worst = std::max(worst, err);
    EXPECT_LE(err, 1e-12) << "F =\n" << F;
  }
  std::printf("[polar log] worst relative round-trip error over 1000 gradients: %.1e\n", worst);
}

TEST(PolarLog, OfThePlaneStrainIdentityIsZero) {
  const PolarLog p = polar_log(Mat3::Identity());
  EXPECT_EQ(p.log_U.norm(), 0.0);
  EXPECT_EQ(p.log_R.norm(), 0.0);
  EXPECT_EQ(from_polar_log(p), Mat3::Identity());
}

TEST(Rodrigues, ExponentialOfASkewMatrixIsAProperRotation) {
  Random rnd;
  for (int k = 0; k < 100; ++k) {
    const Mat3 R = rnd.rotation(3.0);
    EXPECT_LE((R.transpose() * R - Mat3::Identity()).norm(), 1e-14);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
    EXPECT_LE((rotation_from_log(log_of_rotation(R)) - R).norm(), 1e-12);
  }
}

// ISO2: tr log U is interpolated linearly, so det F = exp(sum w ln det F_k) = 1 for isochoric inputs, up to
// round-off (1e-12, the figure). ISO0 and ISO1 average the components, which does not keep det F:
// the same inputs lose or gain volume by far more than round-off.
TEST(InterpolateDeformation, Iso2KeepsIsochoricGradientsIsochoricAndIso0DoesNot) {
  Random rnd;
  double worst_iso2 = 0.0, min_iso0 = 1e300, min_iso1 = 1e300;
  for (int k = 0; k < 1000; ++k) {
    const Mat3 F0 = isochoric(rnd.deformation()), F1 = isochoric(rnd.deformation()), F2 = isochoric(rnd.deformation());
    const Mat3* const F[3] = {&F0, &F1, &F2};
    double w[3];
    rnd.weights(w);
    const double d2 = std::abs(interpolate_deformation<3>(F, w, IsoMode::iso2).determinant() - 1.0);
    EXPECT_LE(d2, 1e-12);
    worst_iso2 = std::max(worst_iso2, d2);
    min_iso0 = std::min(min_iso0, std::abs(interpolate_deformation<3>(F, w, IsoMode::iso0).determinant() - 1.0));
    min_iso1 = std::min(min_iso1, std::abs(interpolate_deformation<3>(F, w, IsoMode::iso1).determinant() - 1.0));
  }
  // A hand-checkable case: halfway between the isochoric stretches diag(2, 1/2, 1) and diag(1/2, 2, 1),
  // ISO0 gives diag(5/4, 5/4, 1), det 25/16 (56 % more volume); ISO2 the log-mean, diag(1, 1, 1).
  const Mat3 A = Vec3(2.0, 0.5, 1.0).asDiagonal(), B = Vec3(0.5, 2.0, 1.0).asDiagonal();
  const Mat3* const AB[2] = {&A, &B};
  const double half[2] = {0.5, 0.5};
  EXPECT_DOUBLE_EQ(interpolate_deformation<2>(AB, half, IsoMode::iso0).determinant(), 25.0 / 16.0);
  EXPECT_NEAR(interpolate_deformation<2>(AB, half, IsoMode::iso2).determinant(), 1.0, 1e-15);
  EXPECT_LE((interpolate_deformation<2>(AB, half, IsoMode::iso2) - Mat3::Identity()).norm(), 1e-15);  // log-mean
  std::printf("[iso] isochoric inputs, |det F - 1| after interpolation: ISO2 worst %.1e; ISO0 best %.1e; ISO1 best %.1e\n",
              worst_iso2, min_iso0, min_iso1);
  EXPECT_GT(min_iso0, 1e-9);  // never accidentally isochoric over 1000 random triples
}

// ISO1 interpolates J^(1/3) and F_iso separately: for purely volumetric inputs (F_iso = I) it gives
// J^(1/3) = sum w_k J_k^(1/3) exactly, where ISO0 gives the same (F = J^(1/3) I is linear in J^(1/3)).
// For isochoric inputs with one common F_iso and different volumes, ISO1 keeps F_iso: its result is
// (sum w J_k^(1/3)) F_iso.
TEST(InterpolateDeformation, Iso1SeparatesVolumetricAndIsochoricParts) {
  Random rnd;
  const Mat3 Fiso = isochoric(rnd.deformation());
  const double J[3] = {0.8, 1.0, 1.3};
  const Mat3 F0 = std::cbrt(J[0]) * Fiso, F1 = std::cbrt(J[1]) * Fiso, F2 = std::cbrt(J[2]) * Fiso;
  const Mat3* const F[3] = {&F0, &F1, &F2};
  const double w[3] = {0.2, 0.3, 0.5};
  const double c = w[0] * std::cbrt(J[0]) + w[1] * std::cbrt(J[1]) + w[2] * std::cbrt(J[2]);
  const Mat3 r = interpolate_deformation<3>(F, w, IsoMode::iso1);
  EXPECT_LE((r - c * Fiso).norm(), 1e-13 * Fiso.norm());
  EXPECT_NEAR(r.determinant(), c * c * c, 1e-13);
}

// Every scheme reproduces a constant field (weights sum to one): the homogeneous-deformation invariance
// that tests/verification/pfem_homogeneous_test.cpp relies on, to round-off.
TEST(InterpolateDeformation, EverySchemeReproducesAConstantField) {
  Random rnd;
  for (int k = 0; k < 100; ++k) {
    const Mat3 F0 = k % 2 ? rnd.deformation(2.5) : rnd.plane(2.5);
    const Mat3* const F[3] = {&F0, &F0, &F0};
    double w[3];
    rnd.weights(w);
    for (IsoMode mode : {IsoMode::iso0, IsoMode::iso1, IsoMode::iso2})
      EXPECT_LE((interpolate_deformation<3>(F, w, mode) - F0).norm(), 1e-12 * F0.norm()) << "mode " << int(mode);
  }
}

// Plane-strain inputs (F13 = F23 = F31 = F32 = 0, F33 = 1) stay plane under ISO2: log U and log R keep the
// block structure (the rotation axis is z), and exp(0) = 1 on the out-of-plane diagonal.
TEST(InterpolateDeformation, Iso2KeepsPlaneStrainGradientsPlane) {
  Random rnd;
  for (int k = 0; k < 100; ++k) {
    const Mat3 F0 = rnd.plane(), F1 = rnd.plane(), F2 = rnd.plane();
    const Mat3* const F[3] = {&F0, &F1, &F2};
    double w[3];
    rnd.weights(w);
    const Mat3 r = interpolate_deformation<3>(F, w, IsoMode::iso2);
    EXPECT_NEAR(r(2, 2), 1.0, 1e-13);
    EXPECT_LE(std::abs(r(0, 2)) + std::abs(r(1, 2)) + std::abs(r(2, 0)) + std::abs(r(2, 1)), 1e-13);
    EXPECT_GT(r.determinant(), 0.0);
  }
}

}  // namespace
}  // namespace loom
