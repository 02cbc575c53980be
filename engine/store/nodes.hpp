// Nodes: the carriers of the solution (mesh nodes of FEM/PFEM, later the MPM background grid).
// Units are the scene's: lengths L, time T. Displacements are total (u = x - X); the converged values of
// the last step carry the suffix _n (seed 000 eq 1: u = u_n + du).
#pragma once

#include "engine/core/types.hpp"
#include "engine/store/column.hpp"
#include "engine/store/walls.hpp"

namespace loom {

template <int D>
struct Nodes {
  using V = Vec<D>;

  Column<V> X;       // reference coordinates (always)
  Column<V> u;       // displacement iterate (always)
  Column<V> u_n;     // converged displacement of the previous step (always)
  Column<V> v;       // velocity iterate (dynamic integrators)
  Column<V> v_n;     // converged velocity (dynamic integrators)
  Column<V> a;       // acceleration iterate (dynamic integrators)
  Column<V> a_n;     // converged acceleration (dynamic integrators)
  Column<double> lumped_mass;  // lumped mass, M (dynamic with lumped mass)
  Column<double> phi;          // volume dilatation iterate (mixed u-phi formulations; 1 elsewhere)
  Column<double> phi_n;        // converged volume dilatation
  // MPM background grids (seed 003 Algorithm 1): u is the displacement of the step (the grid starts
  // undeformed), v_n and a_n the projected particle velocity and acceleration, lumped_mass the projected mass.
  Column<double> p;            // pressure iterate (mixed u-p), sigma = sigma_dev + p I
  Column<double> p_n;          // converged pressure (mixed u-p on a mesh: a nodal unknown that persists)
  Column<double> J_node;       // nodal volume ratio J^l of the particles (es_pfem, seed 001 eq 56; 1 at the start)
  Column<Vec<D>> proj_u;       // OSGS projections of the momentum and pressure residuals (seed 003 §5)
  Column<double> proj_p;
  Column<double> lumped_volume;  // OSGS: sum_p N_I V_p^n, the lumped matrix of the L2 projection
  // Rigid walls (engine/store/walls.hpp): the node's share of the boundary in B_n that faces each wall plane (entry
  // p: the sum over its boundary edges of its share of the edge's length projected on plane p, max(0, -a_e . n_p)
  // with a_e that share times the edge's outward normal; 0 inside the body), and, with stick walls, whether it was
  // in contact at the last converged step and where it first touched.
  Column<WallShares> contact_share;
  Column<double> in_contact;  // 1: in contact with a stick wall, 0: not
  Column<Vec<D>> contact_point;

  Nodes() {
    X.use();
    u.use();
    u_n.use();
  }

  Index size() const { return X.size(); }

  template <class Visit>
  void for_each_column(Visit&& f) {
    f("X", X), f("u", u), f("u_n", u_n), f("v", v), f("v_n", v_n), f("a", a), f("a_n", a_n),
        f("lumped_mass", lumped_mass), f("phi", phi), f("phi_n", phi_n), f("p", p), f("p_n", p_n), f("J_node", J_node), f("proj_u", proj_u), f("proj_p", proj_p),
        f("lumped_volume", lumped_volume), f("contact_share", contact_share), f("in_contact", in_contact), f("contact_point", contact_point);
  }
  template <class Visit>
  void for_each_column(Visit&& f) const {
    const_cast<Nodes*>(this)->for_each_column([&](const char* name, const auto& c) { f(name, c); });
  }

  // Sizes every used column to n entities (new entries are zero, phi and J_node one: undeformed).
  void resize(Index n) {
    for_each_column([this, n](const char*, auto& c) {
      using T = typename std::decay_t<decltype(c)>::value_type;
      if constexpr (std::is_arithmetic_v<T>) {
        const void* column = &c;
        c.resize(n, column == &phi || column == &phi_n || column == &J_node ? T(1) : T(0));
      } else {
        c.resize(n, T::Zero());
      }
    });
  }

  Vec<D> position(Index i) const { return X[i] + u[i]; }
  Vec<D> position_n(Index i) const { return X[i] + u_n[i]; }
};

}  // namespace loom
