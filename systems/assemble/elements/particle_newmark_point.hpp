// A material point of seed 004's implicit MPM (Aulisa & Capodaglio §3.2-3.3, eqs 19-25): the particle is a
// quadrature point of weight m_p and carries the Newmark state (v_p, a_p). The unknown is the grid
// displacement of the step u~ (the grid starts every step undeformed); at the point
//   u~_p = sum_A N_A u~_A                                                         (eq 22)
//   a_p  = c u~_p - v_p^n / (beta dt) - (1 - 2 beta) / (2 beta) a_p^n,  c = 1 / (beta dt^2)   (eq 21)
//   r_A += m_p N_A (a_p - b_p) + V_0 P(F) G_A,  F = (I + sum_B u~_B (x) dN*_B) F_p^n         (eqs 20, 24)
// with G_A = F_n^T dN_A (so m_p sigma^s : grad_x N_A = V_0 P : grad_X N_A, spec remark to eq 15) and the
// trial gradients dN* (= dN, or T^T dN under receding contact). Tangent: the consistent particle mass
// m_p c N_A N_B I plus the material part of displacement_point.hpp.
#pragma once

#include "systems/assemble/elements/displacement_point.hpp"

namespace loom {

// Newmark at the particles: beta, gamma and the step.
struct ParticleNewmark {
  double beta = 0.25, gamma = 0.5, dt = 1.0;
  double stiffness() const { return 1.0 / (beta * dt * dt); }
  Vec2 acceleration(const Vec2& du, const Vec2& v_n, const Vec2& a_n) const {
    return du * stiffness() - v_n / (beta * dt) - (1.0 - 2.0 * beta) / (2.0 * beta) * a_n;
  }
  Vec2 velocity(const Vec2& v_n, const Vec2& a_n, const Vec2& a) const { return v_n + dt * ((1.0 - gamma) * a_n + gamma * a); }
};

template <int NEN>
struct ParticlePoint {
  Eigen::Matrix<double, NEN, 1> N;  // shape values at x_p^n
  NodalVectors<NEN> dN;             // d N / d x at x_p^n (the grid at the step's start)
  NodalVectors<NEN> dN_trial;       // the gradients F is built from (dN, or T^T dN)
  double mass = 0, V0 = 0;
  Mat3 F_n = Mat3::Identity();
  Vec2 v_n = Vec2::Zero(), a_n = Vec2::Zero(), b = Vec2::Zero();
};

template <int NEN, class MaterialT>
bool add_particle_newmark_point(const MaterialT& material, const ParticleNewmark& tn, const ParticlePoint<NEN>& pt,
                                const NodalVectors<NEN>& du, Mat3& F, ElementVector<NEN>& r, ElementMatrix<NEN>* K) {
  if (!add_displacement_point<NEN>(material, du, pt.dN, pt.dN_trial, pt.V0 * pt.F_n.determinant(), pt.F_n, F, r, K)) return false;
  const Vec2 u_p = du.transpose() * pt.N;
  const Vec2 f = pt.mass * (tn.acceleration(u_p, pt.v_n, pt.a_n) - pt.b);
  for (int a = 0; a < NEN; ++a) r.template segment<2>(2 * a) += pt.N[a] * f;
  if (K) {
    const Eigen::Matrix<double, NEN, NEN> M = (pt.mass * tn.stiffness()) * pt.N * pt.N.transpose();
    for (int a = 0; a < NEN; ++a)
      for (int b = 0; b < NEN; ++b) (*K)(2 * a, 2 * b) += M(a, b), (*K)(2 * a + 1, 2 * b + 1) += M(a, b);
  }
  return true;
}

}  // namespace loom
