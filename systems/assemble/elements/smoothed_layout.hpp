// The data of one integration domain of seed 001's smoothed elements (an edge's or a face's smoothing domain, or
// a whole simplex), its local dof layout, and the first-Piola assembly that every material branch of the kernel
// (elements/smoothed_domain.hpp, elements/smoothed_hyperelastic.hpp) shares.
#pragma once

#include "systems/assemble/elements/displacement_point.hpp"
#include "systems/assemble/materials/tensor9.hpp"

namespace loom {

template <int NEN, int D = 2>
struct SmoothedDomain {
  NodalVectors<NEN, D> du;              // u - u_n at the stencil nodes
  Eigen::Matrix<double, NEN, 1> p;      // nodal pressures (mixed)
  NodalVectors<NEN, D> b;               // b~_I at x_n, one row per stencil node
  Eigen::Matrix<double, NEN, 1> Np;     // N_p^k: the pressure interpolation at the domain's point
  double V_n = 0.0;                     // domain volume in B_n
  Mat3 be_n = Mat3::Identity();         // history
  double dt = 1.0;
};

// What the kernel leaves for the stores: the updated history and the stress for output.
struct SmoothedDomainState {
  Mat3 be = Mat3::Identity();
  Mat3 sigma = Mat3::Zero();
  double j = 1.0;  // det f
};

template <int NEN, bool Mixed, int D = 2>
struct SmoothedLayout {
  static constexpr int per_node = Mixed ? D + 1 : D;
  static constexpr int size = per_node * NEN;
  static constexpr int u(int a, int i) { return per_node * a + i; }
  static constexpr int p(int a) { return (D + 1) * a + D; }
  using Vector = Eigen::Matrix<double, size, 1>;
  using Matrix = Eigen::Matrix<double, size, size>;
};

namespace detail {

// r_u += V_n P b~, K_uu += V_n b~ A b~ (2D: the in-plane rows and columns).
template <int NEN, bool Mixed, int D>
void add_first_piola(const SmoothedDomain<NEN, D>& d, const Mat3& P, const Mat9* A, typename SmoothedLayout<NEN, Mixed, D>::Vector& r,
                     typename SmoothedLayout<NEN, Mixed, D>::Matrix* K) {
  using L = SmoothedLayout<NEN, Mixed, D>;
  const NodalVectors<NEN, D> f = d.V_n * d.b * P.template topLeftCorner<D, D>().transpose();  // f(I, i) = P_ij b~_Ij
  for (int a = 0; a < NEN; ++a)
    for (int i = 0; i < D; ++i) r[L::u(a, i)] += f(a, i);
  if (!K) return;
  for (int i = 0; i < D; ++i)
    for (int k = 0; k < D; ++k) {
      Eigen::Matrix<double, D, D> C;  // C_jl = A_ijkl for fixed i, k
      for (int j = 0; j < D; ++j)
        for (int l = 0; l < D; ++l) C(j, l) = (*A)(ij(i, j), ij(k, l));
      const Eigen::Matrix<double, NEN, NEN> block = d.V_n * d.b * C * d.b.transpose();
      for (int a = 0; a < NEN; ++a)
        for (int c = 0; c < NEN; ++c) (*K)(L::u(a, i), L::u(c, k)) += block(a, c);
    }
}

}  // namespace detail

}  // namespace loom
