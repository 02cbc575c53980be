// Points: particles that persist across steps (PFEM nodes that outlive remeshing, MPM material points).
// The FEM method keeps its state on Nodes and QuadPoints and allocates no Points; the store exists so
// that PFEM and MPM recipes share one layout (DESIGN §2). Structural operations permute all used
// columns together.
#pragma once

#include <algorithm>
#include <type_traits>
#include <vector>

#include "engine/core/types.hpp"
#include "engine/store/column.hpp"

namespace loom {

template <int D>
struct Points {
  using V = Vec<D>;

  Column<V> X;            // reference position
  Column<V> u;            // displacement
  Column<V> v;            // velocity
  Column<V> a;            // acceleration
  Column<double> mass;    // M
  Column<double> volume;  // reference volume, L^D
  Column<Mat3> F;         // deformation gradient
  Column<double> pressure;  // mixed u-p (seed 003): p of sigma = sigma_dev + p I, positive in tension
  Column<Index> body;
  Column<V> proj_u;         // OSGS (seed 003 §5): residual projections P_u, P_p carried between steps
  Column<double> proj_p;
  Column<Mat3> be;          // materials with history (hencky_perzyna): converged elastic left Cauchy-Green b^e_n

  Index size() const {
    Index n = 0;
    for_each_column([&](const char*, const auto& c) { n = std::max(n, c.size()); });
    return n;
  }

  template <class Visit>
  void for_each_column(Visit&& f) {
    f("X", X), f("u", u), f("v", v), f("a", a), f("mass", mass), f("volume", volume), f("F", F),
        f("pressure", pressure), f("body", body), f("proj_u", proj_u), f("proj_p", proj_p), f("be", be);
  }
  template <class Visit>
  void for_each_column(Visit&& f) const {
    const_cast<Points*>(this)->for_each_column([&](const char* name, const auto& c) { f(name, c); });
  }

  // Sizes every used column to n points (new entries zero, F the identity).
  void resize(Index n) {
    for_each_column([n](const char*, auto& c) {
      using T = typename std::decay_t<decltype(c)>::value_type;
      if constexpr (std::is_arithmetic_v<T>) c.resize(n, T(0));
      else if constexpr (std::is_same_v<T, Mat3>) c.resize(n, Mat3::Identity());
      else c.resize(n, T::Zero());
    });
  }

  Vec<D> position(Index i) const { return X[i] + u[i]; }

  // Removes point i by moving the last point into its place, in every used column.
  void swap_remove(Index i) {
    for_each_column([i](const char*, auto& c) {
      if (!c.used()) return;
      c[i] = c.values().back();
      c.values().pop_back();
    });
  }

  // Reorders every used column so that new entry k is old entry order[k].
  void permute(const std::vector<Index>& order) {
    for_each_column([&](const char*, auto& c) {
      if (!c.used()) return;
      auto old = c.values();
      for (std::size_t k = 0; k < order.size(); ++k) c.values()[k] = old[static_cast<std::size_t>(order[k])];
    });
  }
};

}  // namespace loom
