#include "systems/assemble/assemble_system.hpp"

#include <atomic>

#include "engine/core/errors.hpp"
#include "engine/core/parallel.hpp"
#include "systems/assemble/elements/element_mass.hpp"
#include "systems/assemble/elements/p1_cell.hpp"
#include "systems/assemble/elements/p1p1_uphi_cell.hpp"
#include "systems/assemble/elements/tri6_cell.hpp"

namespace loom {
namespace {

struct Inertia {
  bool on = false;
  bool consistent = false;
  double inv_dt2 = 0.0, inv_dt = 0.0;
};

Inertia inertia_of(const StepContext& ctx) {
  Inertia in;
  in.on = ctx.scene->time.integrator == Integrator::euler_backward;
  in.consistent = ctx.scene->time.mass == MassKind::consistent;
  in.inv_dt = 1.0 / ctx.dt;
  in.inv_dt2 = in.inv_dt * in.inv_dt;
  return in;
}

// Euler backward acceleration (seed 000 eq 12): a = (u - u_n) / dt^2 - v_n / dt.
Vec2 acceleration(const Nodes<2>& nodes, Index i, const Inertia& in) {
  return (nodes.u[i] - nodes.u_n[i]) * in.inv_dt2 - nodes.v_n[i] * in.inv_dt;
}

// Value of a dof at the iterate: displacement components first, then phi.
double dof_value(const Nodes<2>& nodes, Index dof, int per_node) {
  const Index node = dof / per_node;
  const int comp = dof % per_node;
  return comp < 2 ? nodes.u[node][comp] : nodes.phi[node];
}

// The element's local dofs in its own layout, mapped to the cell's dofs in the scatter (node-major with
// per_node dofs per node): u-only elements skip the dilatation slot when the run carries one.
template <int NE>
struct LocalMap {
  int to_scatter[NE];
};

template <int NEN>
LocalMap<2 * NEN> displacement_map(int per_node) {
  LocalMap<2 * NEN> m{};
  for (int a = 0; a < NEN; ++a)
    for (int i = 0; i < 2; ++i) m.to_scatter[2 * a + i] = a * per_node + i;
  return m;
}

// Scatters a cell's local residual (with the Dirichlet lift) and tangent; see assemble_system.hpp.
template <int NE>
class CellScatterer {
 public:
  using Vector = Eigen::Matrix<double, NE, 1>;
  using Matrix = Eigen::Matrix<double, NE, NE>;

  CellScatterer(const LocalMap<NE>& map, const CellScatter& sc, const BoundaryConditions<2>& bc, const Nodes<2>& nodes,
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
  int from_scatter_[18];  // scatter-local index (at most 6 nodes x 3 dofs) -> element-local index (-1: not the element's)
  const LocalMap<NE>& map_;
  const CellScatter& sc_;
  const BoundaryConditions<2>& bc_;
  const Nodes<2>& nodes_;
  LinearSystem& system_;
};

// Runs `cell_body(c)` over the cells colour by colour, the cells of one colour in parallel.
template <class Body>
void for_each_cell_by_colour(const Cells& cells, Body&& cell_body) {
  for (Index k = 0; k < cells.n_colours(); ++k) {
    const Index begin = cells.colour_offsets[std::size_t(k)], end = cells.colour_offsets[std::size_t(k) + 1];
    for_each_in(cells.by_colour.data() + begin, end - begin, cell_body);
  }
}

// Consistent inertia of the displacement dofs: r += M a, K += M / dt^2 (M per unit density given).
template <int NEN, int NE, class MassMatrix>
void add_consistent_inertia(const Nodes<2>& nodes, const Cells& cells, Index c, const Inertia& in, double density,
                            const MassMatrix& M, const int* u_index, Eigen::Matrix<double, NE, 1>& r,
                            Eigen::Matrix<double, NE, NE>* K) {
  for (int a = 0; a < NEN; ++a)
    for (int b = 0; b < NEN; ++b) {
      const double mab = density * M(a, b);
      const Vec2 acc = acceleration(nodes, cells.node(c, b), in);
      for (int i = 0; i < 2; ++i) {
        r[u_index[2 * a + i]] += mab * acc[i];
        if (K) (*K)(u_index[2 * a + i], u_index[2 * b + i]) += mab * in.inv_dt2;
      }
    }
}

struct BlockArgs {
  bool tangent;
  const Inertia& inertia;
  const std::vector<BodyMaterial>& materials;
  const Nodes<2>& nodes;
  const Cells& cells;
  const BoundaryConditions<2>& bc;
  QuadPoints<2>& quad;
  const CellScatter& scatter;
  LinearSystem& system;
  std::atomic<Index>& inverted;
};

void assemble_p1_block(const BlockArgs& b) {
  const auto map = displacement_map<3>(b.system.dofs.per_node);
  const CellScatterer<6> out(map, b.scatter, b.bc, b.nodes, b.system);
  static constexpr int u_index[6] = {0, 1, 2, 3, 4, 5};
  for_each_cell_by_colour(b.cells, [&](Index c) {
    const P1Cell cell = gather_p1_cell(b.nodes, b.cells, b.quad, c);
    P1Vector gap;
    const bool lagging = out.gap(c, gap);
    const bool need_K = b.tangent || lagging;
    P1Vector r = P1Vector::Zero();
    P1Matrix K = P1Matrix::Zero();
    const BodyMaterial& material = b.materials[std::size_t(b.cells.body[c])];
    const bool ok = std::visit([&](const auto& m) { return p1_internal(m, cell, b.quad.F[c], r, need_K ? &K : nullptr); }, material.model);
    if (!ok) return void(b.inverted.fetch_add(1, std::memory_order_relaxed));
    if (b.inertia.on && b.inertia.consistent)
      add_consistent_inertia<3, 6>(b.nodes, b.cells, c, b.inertia, material.density, tri3_consistent_mass(cell.volume0), u_index, r,
                                   need_K ? &K : nullptr);
    if (lagging) r += K * gap;
    out.scatter(c, r, b.tangent ? &K : nullptr);
  });
}

void assemble_tri6_block(const BlockArgs& b) {
  const auto map = displacement_map<6>(b.system.dofs.per_node);
  const CellScatterer<12> out(map, b.scatter, b.bc, b.nodes, b.system);
  static constexpr int u_index[12] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
  for_each_cell_by_colour(b.cells, [&](Index c) {
    const Tri6Cell cell = gather_tri6_cell(b.nodes, b.cells, b.quad, c);
    Tri6Vector gap;
    const bool lagging = out.gap(c, gap);
    const bool need_K = b.tangent || lagging;
    Tri6Vector r = Tri6Vector::Zero();
    Tri6Matrix K = Tri6Matrix::Zero();
    const BodyMaterial& material = b.materials[std::size_t(b.cells.body[c])];
    Mat3* F = &b.quad.F[3 * c];
    const bool ok = std::visit([&](const auto& m) { return tri6_internal(m, cell, F, r, need_K ? &K : nullptr); }, material.model);
    if (!ok) return void(b.inverted.fetch_add(1, std::memory_order_relaxed));
    if (b.inertia.on && b.inertia.consistent) {
      double volume0 = 0.0;
      for (int q = 0; q < 3; ++q) volume0 += cell.dV_n[q] / cell.F_n[q].determinant();
      add_consistent_inertia<6, 12>(b.nodes, b.cells, c, b.inertia, material.density, tri6_consistent_mass(volume0), u_index, r,
                                    need_K ? &K : nullptr);
    }
    if (lagging) r += K * gap;
    out.scatter(c, r, b.tangent ? &K : nullptr);
  });
}

void assemble_uphi_block(const BlockArgs& b) {
  LocalMap<9> map{};
  for (int k = 0; k < 9; ++k) map.to_scatter[k] = k;  // the run has three dofs per node: same layout
  const CellScatterer<9> out(map, b.scatter, b.bc, b.nodes, b.system);
  static constexpr int u_index[6] = {0, 1, 3, 4, 6, 7};
  for_each_cell_by_colour(b.cells, [&](Index c) {
    UPhiCell cell;
    for (int a = 0; a < 3; ++a) {
      const Index n = b.cells.node(c, a);
      cell.du.row(a) = (b.nodes.u[n] - b.nodes.u_n[n]).transpose();
      cell.phi[a] = b.nodes.phi[n];
    }
    cell.dN = Eigen::Map<const NodalVectors<3>>(b.quad.grad(3 * c));
    for (int q = 0; q < 3; ++q) cell.dV_n[q] = b.quad.weight_n[3 * c + q], cell.F_n[q] = b.quad.F_n[3 * c + q];
    UPhiVector gap;
    const bool lagging = out.gap(c, gap);
    const bool need_K = b.tangent || lagging;
    UPhiVector r = UPhiVector::Zero();
    UPhiMatrix K = UPhiMatrix::Zero();
    const BodyMaterial& material = b.materials[std::size_t(b.cells.body[c])];
    Mat3* Ft = &b.quad.F[3 * c];
    const bool ok = std::visit(
        [&](const auto& m) { return uphi_internal(m, material.alpha_over_G, cell, Ft, r, need_K ? &K : nullptr); }, material.model);
    if (!ok) return void(b.inverted.fetch_add(1, std::memory_order_relaxed));
    if (b.inertia.on && b.inertia.consistent) {
      double volume0 = 0.0;
      for (int q = 0; q < 3; ++q) volume0 += cell.dV_n[q] / cell.F_n[q].determinant();
      add_consistent_inertia<3, 9>(b.nodes, b.cells, c, b.inertia, material.density, tri3_consistent_mass(volume0), u_index, r,
                                   need_K ? &K : nullptr);
    }
    if (lagging) r += K * gap;
    out.scatter(c, r, b.tangent ? &K : nullptr);
  });
}

}  // namespace

AssemblyResult assemble_system(const StepContext& ctx, AssemblyMode mode, const std::vector<BodyMaterial>& materials,
                               const Nodes<2>& nodes, const std::vector<Cells>& cells,
                               const BoundaryConditions<2>& bc, std::vector<QuadPoints<2>>& quad,
                               LinearSystem& system) {
  const bool tangent = mode == AssemblyMode::residual_and_tangent;
  const Inertia inertia = inertia_of(ctx);
  auto& A = system.pattern.matrix;
  if (tangent) std::fill(A.valuePtr(), A.valuePtr() + A.nonZeros(), 0.0);
  system.residual_full.setZero();

  std::atomic<Index> inverted{0};
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const BlockArgs args{tangent, inertia, materials, nodes, cells[k], bc, quad[k], system.scatter[k], system, inverted};
    switch (cells[k].formulation) {
      case Formulation::p1: assemble_p1_block(args); break;
      case Formulation::tri6: assemble_tri6_block(args); break;
      case Formulation::p1p1_uphi: assemble_uphi_block(args); break;
      case Formulation::p1p1_up: LOOM_ASSERT(false, "p1p1_up cells live on MPM grids (assemble_grid_system)"); break;
    }
  }

  // Nodal terms: lumped inertia and external loads; every node writes only its own entries.
  const DofMap& dofs = system.dofs;
  const bool lumped = inertia.on && !inertia.consistent;
  double* values = A.valuePtr();
  for_each_index(nodes.size(), [&](Index i) {
    const Vec2 acc = lumped ? acceleration(nodes, i, inertia) : Vec2::Zero();
    for (int d = 0; d < 2; ++d) {
      const Index dof = dofs.dof(i, d);
      double r = -bc.external[dof];
      if (lumped) {
        r += nodes.lumped_mass[i] * acc[d];
        const Index eq = dofs.equation[std::size_t(dof)];
        if (tangent && eq != kNoIndex) values[system.pattern.diagonal_slot[std::size_t(eq)]] += nodes.lumped_mass[i] * inertia.inv_dt2;
      }
      system.residual_full[dof] += r;
    }
  });
  // Nodal terms of tied dofs go to their masters (T^T r, T^T M T): serial, ties are few.
  for (const Tie& tie : dofs.ties) {
    double& r_tied = system.residual_full[tie.dof];
    for (Index m : tie.master) system.residual_full[m] += 0.5 * r_tied;
    r_tied = 0.0;
    if (lumped && tangent) {
      const Index node = tie.dof / dofs.per_node;
      const double m4 = 0.25 * nodes.lumped_mass[node] * inertia.inv_dt2;
      for (Index a : tie.master)
        for (Index b : tie.master) {
          const Index ea = dofs.equation[std::size_t(a)], eb = dofs.equation[std::size_t(b)];
          if (ea != kNoIndex && eb != kNoIndex) values[find_slot(system.pattern, ea, eb)] += m4;
        }
    }
  }
  for_each_index(dofs.n_dofs(), [&](Index dof) {
    const Index eq = dofs.equation[std::size_t(dof)];
    if (eq != kNoIndex) system.residual[eq] = system.residual_full[dof];
  });
  return {inverted.load()};
}

}  // namespace loom
