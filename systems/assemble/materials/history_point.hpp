// A material with history seen, over one step at one point, as a hyperelastic material of the total deformation
// gradient F: with F_n, b^e_n and dt fixed, the step's return map is a function of F alone (through the increment
// f = F F_n^-1), its Kirchhoff stress tau and spatial tangent c^tau give P = tau F^-T and dP/dF by first_piola.hpp
// (c^tau depends on F only through l = df f^-1 = dF F^-1). So the kernels written for hyperelastic materials
// (stress(F, P), stress_tangent(F, P, A)) carry hencky_perzyna at MPM particles unchanged; the step's b^e is left
// where the caller commits it at convergence.
#pragma once

#include <type_traits>
#include <variant>

#include "systems/assemble/materials/first_piola.hpp"
#include "systems/assemble/materials/hencky_perzyna.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {

struct HenckyPerzynaStep {
  const HenckyPerzyna& model;
  Mat3 F_n_inverse;
  Mat3 be_n;
  double dt = 1.0;
  mutable Mat3 be = Mat3::Identity();  // b^e of the last call's return map

  bool stress(const Mat3& F, Mat3& P) const {
    HistoryResponse h;
    if (!model.update(F * F_n_inverse, be_n, dt, false, false, h)) return false;
    be = h.be;
    P = h.tau * F.inverse().transpose();
    return true;
  }
  bool stress_tangent(const Mat3& F, Mat3& P, Mat9& A) const {
    HistoryResponse h;
    if (!model.update(F * F_n_inverse, be_n, dt, false, true, h)) return false;
    be = h.be;
    first_piola(F, h.tau, h.c_tau, 1.0, P, A);
    return true;
  }
};

// The history of one point over the step: F_n and b^e_n in, the step's b^e out; empty (be_n null) for a point
// without history.
struct PointHistory {
  const Mat3* F_n = nullptr;
  const Mat3* be_n = nullptr;
  double dt = 1.0;
  Mat3* be = nullptr;
};

// Calls fn(material) with the point's material: the model itself, or, for a model with history when the point
// carries one, its step at the point. Returns what fn returns.
template <class Fn>
bool visit_point_material(const Material& material, const PointHistory& history, Fn&& fn) {
  return std::visit(
      [&](const auto& m) {
        if constexpr (std::is_same_v<std::decay_t<decltype(m)>, HenckyPerzyna>) {
          if (history.be_n) {
            const HenckyPerzynaStep step{m, history.F_n->inverse(), *history.be_n, history.dt};
            const bool ok = fn(step);
            *history.be = step.be;
            return ok;
          }
        }
        return fn(m);
      },
      material);
}

}  // namespace loom
