// Seed 004's particle kernel and edge terms (systems/assemble/elements/particle_newmark_point.hpp,
// soft_stiffness.hpp, receding_contact.hpp) on one quad9 cell: every tangent against central differences of
// its residual (with a non-identity history F_n, Newmark state and body force; with receding contact, whose
// tangent is unsymmetric); the soft stiffness is symmetric, positive semi-definite with exactly the rigid
// modes as null space and leaves a translation alone; the receding extrapolation at C_c = 1 has zero normal
// derivative on the wall side, and C_c = 0 restores the plain gradients.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "engine/mesh/quad9_shape.hpp"
#include "systems/assemble/elements/particle_newmark_point.hpp"
#include "systems/assemble/elements/receding_contact.hpp"
#include "systems/assemble/elements/soft_stiffness.hpp"
#include "systems/assemble/materials/neo_hooke.hpp"

namespace loom {
namespace {

// An axis-aligned cell [0.2, 0.8] x [-0.1, 0.3] as the grid builds it.
Quad9Coordinates grid_cell() {
  const Vec2 lattice[9] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, -1}, {1, 0}, {0, 1}, {-1, 0}, {0, 0}};
  Quad9Coordinates X;
  for (int a = 0; a < 9; ++a) X.row(a) << 0.5 + 0.3 * lattice[a].x(), 0.1 + 0.2 * lattice[a].y();
  return X;
}

ParticlePoint<9> particle(const Vec2& xi, Index receding_side, double c_c) {
  ParticlePoint<9> pt;
  pt.N = quad9_shape(xi);
  pt.dN = quad9_gradients(grid_cell(), xi);
  pt.dN_trial = receding_side == kNoIndex ? pt.dN : receding_trial_gradients(pt.dN, int(receding_side), c_c);
  pt.mass = 2.5, pt.V0 = 0.01;
  pt.F_n.topLeftCorner<2, 2>() << 1.1, 0.2, -0.05, 0.95;
  pt.v_n = Vec2(0.3, -1.2), pt.a_n = Vec2(-0.4, 2.0), pt.b = Vec2(0.0, -9.81);
  return pt;
}

NodalVectors<9> random_increment(unsigned seed, double size) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-size, size);
  NodalVectors<9> du;
  for (int a = 0; a < 9; ++a) du.row(a) << d(rng), d(rng);
  return du;
}

ElementVector<9> flat(const NodalVectors<9>& u) {
  ElementVector<9> v;
  for (int a = 0; a < 9; ++a) v.segment<2>(2 * a) = u.row(a).transpose();
  return v;
}

void expect_tangent_matches_differences(Index side, double c_c) {
  const NeoHooke m{3.0e3, 1.0e3};
  const ParticleNewmark tn{0.3, 0.5, 0.01};
  for (unsigned seed : {1u, 2u}) {
    const ParticlePoint<9> pt = particle(Vec2(0.3, -0.6), side, c_c);
    const NodalVectors<9> du = random_increment(seed, 0.02);
    ElementVector<9> r = ElementVector<9>::Zero();
    ElementMatrix<9> K = ElementMatrix<9>::Zero();
    Mat3 F;
    ASSERT_TRUE(add_particle_newmark_point<9>(m, tn, pt, du, F, r, &K));
    const double h = 1e-7;
    double worst = 0.0;
    for (int b = 0; b < 9; ++b)
      for (int k = 0; k < 2; ++k) {
        NodalVectors<9> up = du, um = du;
        up(b, k) += h, um(b, k) -= h;
        ElementVector<9> rp = ElementVector<9>::Zero(), rm = ElementVector<9>::Zero();
        ASSERT_TRUE(add_particle_newmark_point<9>(m, tn, pt, up, F, rp, nullptr));
        ASSERT_TRUE(add_particle_newmark_point<9>(m, tn, pt, um, F, rm, nullptr));
        worst = std::max(worst, ((rp - rm) / (2 * h) - K.col(2 * b + k)).cwiseAbs().maxCoeff());
      }
    EXPECT_LE(worst, 1e-6 * K.cwiseAbs().maxCoeff()) << "side " << side << " C_c " << c_c;
    const double asymmetry = (K - K.transpose()).cwiseAbs().maxCoeff() / K.cwiseAbs().maxCoeff();
    if (side == kNoIndex) EXPECT_LE(asymmetry, 1e-12);
    else EXPECT_GT(asymmetry, 1e-3);  // K T: the reason receding contact needs UMFPACK
  }
}

TEST(ParticleNewmarkPoint, TangentMatchesFiniteDifferences) { expect_tangent_matches_differences(kNoIndex, 0.0); }

TEST(ParticleNewmarkPoint, RecedingTangentMatchesFiniteDifferences) {
  for (Index side = 0; side < 4; ++side) expect_tangent_matches_differences(side, 0.5);
}

// A rigid translation of the step, u~ = c everywhere: F = F_n, and the inertia is m (c / (beta dt^2) - ...) N.
TEST(ParticleNewmarkPoint, TranslationCarriesOnlyInertia) {
  const NeoHooke m{3.0e3, 1.0e3};
  const ParticleNewmark tn{0.3, 0.5, 0.01};
  ParticlePoint<9> pt = particle(Vec2(-0.2, 0.7), kNoIndex, 0.0);
  pt.F_n.setIdentity();
  NodalVectors<9> du;
  for (int a = 0; a < 9; ++a) du.row(a) << 0.01, -0.02;
  ElementVector<9> r = ElementVector<9>::Zero();
  Mat3 F;
  ASSERT_TRUE(add_particle_newmark_point<9>(m, tn, pt, du, F, r, nullptr));
  EXPECT_LE((F - Mat3::Identity()).norm(), 1e-15);
  const Vec2 a = tn.acceleration(Vec2(0.01, -0.02), pt.v_n, pt.a_n);
  for (int k = 0; k < 9; ++k) EXPECT_NEAR((r.segment<2>(2 * k) - pt.mass * pt.N[k] * (a - pt.b)).norm(), 0.0, 1e-12);
}

TEST(SoftStiffness, SymmetricRigidModesAsNullSpace) {
  const Quad9Coordinates X = grid_cell();
  ElementMatrix<9> K = ElementMatrix<9>::Zero();
  const Quad9Gauss& rule = quad9_gauss();
  for (std::size_t q = 0; q < 9; ++q) {
    double det = 0.0;
    const Quad9Gradients dN = quad9_gradients(X, rule.xi[q], &det);
    add_soft_stiffness_point<9>(dN, rule.weight[q] * det, K);
  }
  EXPECT_LE((K - K.transpose()).cwiseAbs().maxCoeff(), 1e-14 * K.cwiseAbs().maxCoeff());
  NodalVectors<9> tx, ty, rot;
  for (int a = 0; a < 9; ++a) tx.row(a) << 1, 0, ty.row(a) << 0, 1, rot.row(a) << -X(a, 1), X(a, 0);
  for (const auto* u : {&tx, &ty, &rot}) EXPECT_LE((K * flat(*u)).norm(), 1e-12 * K.norm());
  const Eigen::SelfAdjointEigenSolver<ElementMatrix<9>> eig(K);
  const auto& ev = eig.eigenvalues();  // ascending
  EXPECT_LE(std::abs(ev[2]), 1e-12 * ev[17]);
  EXPECT_GT(ev[3], 1e-6 * ev[17]);
  // The flag rule of the paper's tables: C1 below 5 inside nodes, C2 from 5 to 8, nothing in a full cell.
  const SoftStiffness s{1e-3, 1e-7};
  EXPECT_EQ(s.factor(1, 9), 1e-3);
  EXPECT_EQ(s.factor(4, 9), 1e-3);
  EXPECT_EQ(s.factor(5, 9), 1e-7);
  EXPECT_EQ(s.factor(8, 9), 1e-7);
  EXPECT_EQ(s.factor(9, 9), 0.0);
}

// u* = T u at C_c = 1: the quadratic extrapolation from the two inner rows has zero normal derivative on the
// wall side, for any u; at C_c = 0 the gradients are the plain ones.
TEST(RecedingContact, FullExtrapolationHasZeroNormalSlopeOnTheWall) {
  const Quad9Coordinates X = grid_cell();
  const NodalVectors<9> u = random_increment(7, 1.0);
  const Vec2 on_side[4][2] = {{{-0.4, -1}, {0.7, -1}}, {{1, -0.3}, {1, 0.6}}, {{0.2, 1}, {-0.8, 1}}, {{-1, 0.1}, {-1, -0.9}}};
  const Vec2 normal[4] = {{0, 1}, {-1, 0}, {0, -1}, {1, 0}};
  for (int side = 0; side < 4; ++side)
    for (const Vec2& xi : on_side[side]) {
      const Quad9Gradients dN = quad9_gradients(X, xi);
      const Eigen::Matrix2d grad = u.transpose() * receding_trial_gradients(dN, side, 1.0);  // d u*_i / d x_j
      EXPECT_LE((grad * normal[side]).norm(), 1e-12 * (u.transpose() * dN).norm()) << "side " << side;
      EXPECT_EQ(receding_trial_gradients(dN, side, 0.0), dN);
    }
}

}  // namespace
}  // namespace loom
