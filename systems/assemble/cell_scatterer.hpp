// Scattering of local cell (or domain) vectors and matrices into the Newton system of a mesh-based run,
// with the Dirichlet lift and the elimination of tied dofs (assemble_system.hpp says why), and the
// colour-by-colour loop that makes assembly race-free and independent of the thread count.
#pragma once

#include <algorithm>
#include <iterator>

#include "engine/core/parallel.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "systems/assemble/scatter_prefetch.hpp"

namespace loom {

// Value of a dof at the iterate: the D displacement components first, then phi or p.
template <int D>
inline double dof_value(const Nodes<D>& nodes, Index dof, int per_node) {
  const Index node = dof / per_node;
  const int comp = dof % per_node;
  return comp < D ? nodes.u[node][comp] : nodes.phi.used() ? nodes.phi[node] : nodes.p[node];
}

// The element's local dofs in its own layout, mapped to the cell's dofs in the scatter (node-major with
// per_node dofs per node): u-only elements skip the dilatation slot when the run carries one.
template <int NE>
struct LocalMap {
  int to_scatter[NE];
};

template <int NEN, int D = 2>
inline LocalMap<D * NEN> displacement_map(int per_node) {
  LocalMap<D * NEN> m{};
  for (int a = 0; a < NEN; ++a)
    for (int i = 0; i < D; ++i) m.to_scatter[D * a + i] = a * per_node + i;
  return m;
}

// Scatters a cell's local residual (with the Dirichlet lift) and tangent; see assemble_system.hpp.
template <int NE, int D = 2>
class CellScatterer {
 public:
  using Vector = Eigen::Matrix<double, NE, 1>;
  using Matrix = Eigen::Matrix<double, NE, NE>;

  CellScatterer(const LocalMap<NE>& map, const CellScatter& sc, const BoundaryConditions<D>& bc, const Nodes<D>& nodes,
                LinearSystem& system)
      : map_(map), sc_(sc), bc_(bc), nodes_(nodes), system_(system) {
    std::fill(std::begin(from_scatter_), std::end(from_scatter_), -1);
    for (int k = 0; k < NE; ++k) from_scatter_[map_.to_scatter[k]] = k;
  }

  // Gap (target - value) of the cell's prescribed dofs, and of its tied dofs (the mean of their masters'
  // gaps); returns true if any is non-zero.
  bool gap(Index c, Vector& g) const {
    g.setZero();
    bool lagging = false;
    const int pn = system_.dofs.per_node;
    for (int k = 0; k < NE; ++k) {
      const Index dof = sc_.cell_dof(c, map_.to_scatter[k]);
      if (system_.dofs.kind[std::size_t(dof)] != DofKind::prescribed) continue;
      g[k] = bc_.target[dof] - dof_value(nodes_, dof, pn);
      lagging = lagging || g[k] != 0.0;
    }
    if (lagging)
      for (Index t = sc_.tie_offset.empty() ? 0 : sc_.tie_offset[std::size_t(c)]; !sc_.tie_offset.empty() && t < sc_.tie_offset[std::size_t(c) + 1]; ++t) {
        const auto& tie = sc_.local_ties[std::size_t(t)];
        g[from_scatter_[tie[0]]] = 0.5 * (g[from_scatter_[tie[1]]] + g[from_scatter_[tie[2]]]);
      }
    return lagging;
  }

  // Look-ahead (scatter_prefetch.hpp): the next cell's scatter row; a cell's matrix entries before it is integrated.
  void prefetch_row(Index c) const { prefetch_scatter_row(c, sc_); }
  void prefetch_entries(Index c) const { prefetch_scatter_entries(c, sc_, system_); }

  void scatter(Index c, const Vector& r_in, const Matrix* K_in) const {
    const Vector* r = &r_in;
    const Matrix* K = K_in;
    Vector r_tied;
    Matrix K_tied;
    if (!sc_.tie_offset.empty() && sc_.tie_offset[std::size_t(c)] != sc_.tie_offset[std::size_t(c) + 1]) {
      // Eliminate the ties (u_t = (u_m1 + u_m2) / 2): r <- T^T r, K <- T^T K T.
      r_tied = r_in;
      if (K_in) K_tied = *K_in;
      for (Index t = sc_.tie_offset[std::size_t(c)]; t < sc_.tie_offset[std::size_t(c) + 1]; ++t) {
        const auto& tie = sc_.local_ties[std::size_t(t)];
        const int a = from_scatter_[tie[0]], m1 = from_scatter_[tie[1]], m2 = from_scatter_[tie[2]];
        r_tied[m1] += 0.5 * r_tied[a], r_tied[m2] += 0.5 * r_tied[a], r_tied[a] = 0.0;
        if (!K_in) continue;
        K_tied.row(m1) += 0.5 * K_tied.row(a), K_tied.row(m2) += 0.5 * K_tied.row(a), K_tied.row(a).setZero();
        K_tied.col(m1) += 0.5 * K_tied.col(a), K_tied.col(m2) += 0.5 * K_tied.col(a), K_tied.col(a).setZero();
      }
      r = &r_tied;
      if (K_in) K = &K_tied;
    }
    for (int a = 0; a < NE; ++a) system_.residual_full[sc_.cell_dof(c, map_.to_scatter[a])] += (*r)[a];
    if (!K) return;
    double* values = system_.pattern.matrix.valuePtr();
    for (int a = 0; a < NE; ++a)
      for (int b = 0; b < NE; ++b) {
        const Index s = sc_.matrix_slot(c, map_.to_scatter[a], map_.to_scatter[b]);
        if (s != kNoIndex) values[s] += (*K)(a, b);
      }
  }

 private:
  int from_scatter_[40];  // scatter-local index (at most 10 nodes x 4 dofs) -> element-local index (-1: not the element's)
  const LocalMap<NE>& map_;
  const CellScatter& sc_;
  const BoundaryConditions<D>& bc_;
  const Nodes<D>& nodes_;
  LinearSystem& system_;
};

// Runs `cell_body(c)` over the cells colour by colour, the cells of one colour in parallel.
template <class Body>
inline void for_each_cell_by_colour(const Cells& cells, Body&& cell_body) {
  for (Index k = 0; k < cells.n_colours(); ++k) {
    const Index begin = cells.colour_offsets[std::size_t(k)], end = cells.colour_offsets[std::size_t(k) + 1];
    for_each_in(cells.by_colour.data() + begin, end - begin, cell_body);
  }
}
// The same, calling ahead(c') for the next cell of the colour before cell_body(c) (prefetches).
template <class Ahead, class Body>
inline void for_each_cell_by_colour_looking_ahead(const Cells& cells, Ahead&& ahead, Body&& cell_body) {
  for (Index k = 0; k < cells.n_colours(); ++k) {
    const Index begin = cells.colour_offsets[std::size_t(k)], end = cells.colour_offsets[std::size_t(k) + 1];
    for_each_in_looking_ahead(cells.by_colour.data() + begin, end - begin, ahead, cell_body);
  }
}
// The cell loop of an assembly that scatters through `out`: with the tangent, the next cell's scatter row is
// prefetched, and a cell's matrix entries before cell_body(c) integrates it.
template <int NE, int D, class Body>
inline void for_each_cell_prefetching_scatter(const Cells& cells, const CellScatterer<NE, D>& out, bool tangent, Body&& cell_body) {
  const auto ahead = [&](Index c) {
    if (tangent) out.prefetch_row(c);
  };
  for_each_cell_by_colour_looking_ahead(cells, ahead, [&](Index c) {
    if (tangent) out.prefetch_entries(c);
    cell_body(c);
  });
}

}  // namespace loom
