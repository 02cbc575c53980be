// The implicit time integrators of mesh-based runs as one family (DESIGN §3): static, Euler backward
// (seed 000 eq 12), Newmark and alpha-Bossak (Wood, Bossak & Zienkiewicz 1980; seed 001 §3.6). The unknown
// of a step is the displacement increment du = u - u_n; each integrator gives the acceleration at the
// iterate, the acceleration that multiplies the mass in the residual, its derivative d/d du (the inertia
// tangent is M times it) and the velocity at commit.
//   Euler backward: a = (du / dt - v_n) / dt,  v = du / dt.
//   Bossak (alpha in [-1/3, 0]; alpha = 0 is Newmark's average acceleration):
//     beta = (1 - alpha)^2 / 4, gamma = 1/2 - alpha,
//     a = (du - dt v_n) / (beta dt^2) - (1 / (2 beta) - 1) a_n,   v = v_n + dt ((1 - gamma) a_n + gamma a),
//     inertia M ((1 - alpha) a + alpha a_n), tangent (1 - alpha) M / (beta dt^2).
// Second order and unconditionally stable for linear problems; alpha < 0 damps the high frequencies.
// A constant acceleration is integrated exactly when a_0 is the initial equilibrium one (free fall).
#pragma once

#include <type_traits>

#include "engine/core/types.hpp"
#include "engine/scene/scene_spec.hpp"

namespace loom {

struct TimeIntegrator {
  Integrator kind = Integrator::static_;
  double dt = 1.0;
  double alpha = 0.0, beta = 0.25, gamma = 0.5;

  bool dynamic() const { return kind != Integrator::static_; }
  bool second_order() const { return kind == Integrator::newmark || kind == Integrator::bossak; }

  // Per node in D dimensions (default 2, never deduced, as the element kernels: 3D callers write <3>).
  template <int D = 2>
  Vec<D> acceleration(const std::type_identity_t<Vec<D>>& du, const std::type_identity_t<Vec<D>>& v_n,
                      const std::type_identity_t<Vec<D>>& a_n) const {
    if (!second_order()) return (du / dt - v_n) / dt;
    return (du - dt * v_n) / (beta * dt * dt) - (0.5 / beta - 1.0) * a_n;
  }
  // What multiplies M in the residual.
  template <int D = 2>
  Vec<D> inertial_acceleration(const std::type_identity_t<Vec<D>>& du, const std::type_identity_t<Vec<D>>& v_n,
                               const std::type_identity_t<Vec<D>>& a_n) const {
    if (!second_order()) {  // the expression of earlier Euler runs, bit for bit
      const double inv_dt = 1.0 / dt;
      return du * (inv_dt * inv_dt) - v_n * inv_dt;
    }
    return (1.0 - alpha) * acceleration<D>(du, v_n, a_n) + alpha * a_n;
  }
  // d (inertial acceleration) / d du.
  double stiffness() const {
    if (!second_order()) {
      const double inv_dt = 1.0 / dt;
      return inv_dt * inv_dt;
    }
    return (1.0 - alpha) / (beta * dt * dt);
  }
  template <int D = 2>
  Vec<D> velocity(const std::type_identity_t<Vec<D>>& du, const std::type_identity_t<Vec<D>>& v_n,
                  const std::type_identity_t<Vec<D>>& a_n, const std::type_identity_t<Vec<D>>& a) const {
    if (!second_order()) return du / dt;
    return v_n + dt * ((1.0 - gamma) * a_n + gamma * a);
  }
};

inline TimeIntegrator time_integrator_of(const TimeSpec& time, double dt) {
  TimeIntegrator t;
  t.kind = time.integrator;
  t.dt = dt;
  if (t.kind == Integrator::bossak) t.alpha = time.alpha;
  t.beta = 0.25 * (1.0 - t.alpha) * (1.0 - t.alpha);
  t.gamma = 0.5 - t.alpha;
  if (t.kind == Integrator::newmark) t.beta = time.beta, t.gamma = time.gamma;  // default 1/4, 1/2: the same
  return t;
}

}  // namespace loom
