// Newmark on the MPM background grid (seed 003 §3.3, beta = 1/4, gamma = 1/2): the grid starts each step
// undeformed with the projected velocity v_n and acceleration a_n; its step displacement u gives
//   a = (u - dt v_n) / (beta dt^2) - (1 / (2 beta) - 1) a_n,   v = v_n + dt ((1 - gamma) a_n + gamma a).
#pragma once

#include "engine/core/types.hpp"
#include "engine/store/nodes.hpp"
#include "systems/map/interpolate_to_particles.hpp"

namespace loom {

// d a / d u of a node: 1 / (beta dt^2).
inline double newmark_stiffness(double dt) { return 1.0 / (kNewmarkBeta * dt * dt); }

template <int D>
Vec<D> newmark_acceleration(const Nodes<D>& g, Index i, double dt) {
  return (g.u[i] - dt * g.v_n[i]) * newmark_stiffness(dt) - (0.5 / kNewmarkBeta - 1.0) * g.a_n[i];
}

template <int D>
Vec<D> newmark_velocity(const Nodes<D>& g, Index i, const Vec<D>& a, double dt) {
  return g.v_n[i] + dt * ((1.0 - kNewmarkGamma) * g.a_n[i] + kNewmarkGamma * a);
}

}  // namespace loom
