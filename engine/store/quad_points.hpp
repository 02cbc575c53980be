// QuadPoints: integration points of the cells of one Cells store (DESIGN §2).
// The points of cell c are c * per_cell .. c * per_cell + per_cell - 1. Geometry is that of the previous
// configuration B_n (seed 000 §2): shape gradients dN/dX_n and weights dV_n are cached until the next
// commit or remesh. F_n is the total deformation gradient at the last converged step (the history that
// PFEM transfers between meshes); F is the current iterate.
#pragma once

#include "engine/core/types.hpp"
#include "engine/store/column.hpp"

namespace loom {

template <int D>
struct QuadPoints {
  int per_cell = 1;         // points per cell
  int nodes_per_cell = 3;   // stride of dN is nodes_per_cell * D

  Column<double> weight_n;  // integration weight in B_n: dV_n = w_q * (cell measure in B_n), L^D
  Column<double> dN;        // shape gradients dN^A/dX_n, nodes_per_cell * D per point, 1/L
  Column<Mat3> F_n;         // converged total deformation gradient (history)
  Column<Mat3> F;           // deformation gradient at the current iterate
  // Converged Cauchy stress, kept where the stress is not a function of F (history materials; seed 001's
  // triangles carry the mean of their smoothing domains' stress). Unused otherwise.
  Column<Mat3> stress_n;
  // Materials with history at the points of p1, tri6, quad9 and tet10 (a yielding hencky_perzyna in methods fem and pfem): the converged
  // elastic left Cauchy-Green b^e_n and the iterate's b^e (committed with F).
  Column<Mat3> be_n;
  Column<Mat3> be;

  QuadPoints() {
    weight_n.use();
    dN.use();
    F_n.use();
    F.use();
  }

  Index size() const { return weight_n.size(); }

  void resize(Index n) {
    weight_n.resize(n, 0.0);
    dN.resize_strided(n, nodes_per_cell * D, 0.0);
    F_n.resize(n, Mat3::Identity());
    F.resize(n, Mat3::Identity());
    stress_n.resize(n, Mat3::Zero());
    be_n.resize(n, Mat3::Identity());
    be.resize(n, Mat3::Identity());
  }

  double* grad(Index q) { return dN.data() + static_cast<std::size_t>(q) * nodes_per_cell * D; }
  const double* grad(Index q) const { return dN.data() + static_cast<std::size_t>(q) * nodes_per_cell * D; }

  template <class Visit>
  void for_each_column(Visit&& f) {
    f("weight_n", weight_n), f("dN", dN), f("F_n", F_n), f("F", F), f("stress_n", stress_n), f("be_n", be_n), f("be", be);
  }
  template <class Visit>
  void for_each_column(Visit&& f) const {
    const_cast<QuadPoints*>(this)->for_each_column([&](const char* name, const auto& c) { f(name, c); });
  }
};

}  // namespace loom
