#include "systems/assemble/assemble_system.hpp"

#include <array>
#include <atomic>

#include "engine/core/errors.hpp"
#include "engine/core/parallel.hpp"
#include "systems/assemble/assemble_domains.hpp"
#include "systems/assemble/cell_scatterer.hpp"
#include "systems/assemble/elements/element_mass.hpp"
#include "systems/assemble/elements/p1_cell.hpp"
#include "systems/assemble/elements/p1p1_uphi_cell.hpp"
#include "systems/assemble/elements/isoparametric_cell.hpp"
#include "systems/assemble/materials/history_point.hpp"
#include "systems/update/time_integrator.hpp"

namespace loom {
namespace {

struct Inertia {
  bool on = false;
  bool consistent = false;
  TimeIntegrator integrator;
};

Inertia inertia_of(const StepContext& ctx) {
  Inertia in;
  in.integrator = time_integrator_of(ctx.scene->time, ctx.dt);
  in.on = in.integrator.dynamic();
  in.consistent = ctx.scene->time.mass == MassKind::consistent;
  return in;
}

// The acceleration that multiplies the mass at node i (time_integrator.hpp).
template <int D>
Vec<D> acceleration(const Nodes<D>& nodes, Index i, const Inertia& in) {
  return in.integrator.inertial_acceleration<D>(nodes.u[i] - nodes.u_n[i], nodes.v_n[i], nodes.a_n[i]);
}

// Consistent inertia of the displacement dofs: r += M a, K += M / dt^2 (M per unit density given).
template <int NEN, int NE, int D, class MassMatrix>
void add_consistent_inertia(const Nodes<D>& nodes, const Cells& cells, Index c, const Inertia& in, double density,
                            const MassMatrix& M, const int* u_index, Eigen::Matrix<double, NE, 1>& r,
                            Eigen::Matrix<double, NE, NE>* K) {
  for (int a = 0; a < NEN; ++a)
    for (int b = 0; b < NEN; ++b) {
      const double mab = density * M(a, b);
      const Vec<D> acc = acceleration(nodes, cells.node(c, b), in);
      for (int i = 0; i < D; ++i) {
        r[u_index[D * a + i]] += mab * acc[i];
        if (K) (*K)(u_index[D * a + i], u_index[D * b + i]) += mab * in.integrator.stiffness();
      }
    }
}

template <int D>
struct BlockArgs {
  bool tangent;
  const Inertia& inertia;
  const std::vector<BodyMaterial>& materials;
  const Nodes<D>& nodes;
  const Cells& cells;
  const BoundaryConditions<D>& bc;
  QuadPoints<D>& quad;
  const CellScatter& scatter;
  LinearSystem& system;
  std::atomic<Index>& inverted;
  double dt;  // the step, for the return map of materials with history
};

// The history of point q of a block that carries one (be_n used), or none.
template <int D>
PointHistory point_history(const BlockArgs<D>& b, const Mat3& F_n, Index q) {
  return b.quad.be_n.used() ? PointHistory{&F_n, &b.quad.be_n[q], b.dt, &b.quad.be[q]} : PointHistory{};
}

void assemble_p1_block(const BlockArgs<2>& b) {
  const auto map = displacement_map<3>(b.system.dofs.per_node);
  const CellScatterer<6> out(map, b.scatter, b.bc, b.nodes, b.system);
  static constexpr int u_index[6] = {0, 1, 2, 3, 4, 5};
  for_each_cell_prefetching_scatter(b.cells, out, b.tangent, [&](Index c) {
    const P1Cell cell = gather_p1_cell(b.nodes, b.cells, b.quad, c);
    P1Vector gap;
    const bool lagging = out.gap(c, gap);
    const bool need_K = b.tangent || lagging;
    P1Vector r = P1Vector::Zero();
    P1Matrix K = P1Matrix::Zero();
    const BodyMaterial& material = b.materials[std::size_t(b.cells.body[c])];
    const bool ok = visit_point_material(material.model, point_history(b, b.quad.F_n[c], c),
                                         [&](const auto& m) { return p1_internal(m, cell, b.quad.F[c], r, need_K ? &K : nullptr); });
    if (!ok) return void(b.inverted.fetch_add(1, std::memory_order_relaxed));
    if (b.inertia.on && b.inertia.consistent)
      add_consistent_inertia<3, 6>(b.nodes, b.cells, c, b.inertia, material.density, tri3_consistent_mass(cell.volume0), u_index, r,
                                   need_K ? &K : nullptr);
    if (lagging) r += K * gap;
    out.scatter(c, r, b.tangent ? &K : nullptr);
  });
}

// tri6 and quad9, tet4 and tet10: NEN nodes, NQ points; the consistent mass on the reference cell.
template <int NEN, int NQ, int D>
void assemble_isoparametric_block(const BlockArgs<D>& b) {
  constexpr int NE = D * NEN;
  const auto map = displacement_map<NEN, D>(b.system.dofs.per_node);
  const CellScatterer<NE, D> out(map, b.scatter, b.bc, b.nodes, b.system);
  static constexpr auto u_index = [] {
    std::array<int, NE> k{};
    for (int i = 0; i < NE; ++i) k[std::size_t(i)] = i;
    return k;
  }();
  for_each_cell_prefetching_scatter(b.cells, out, b.tangent, [&](Index c) {
    const auto cell = gather_isoparametric_cell<NEN, NQ, D>(b.nodes, b.cells, b.quad, c);
    ElementVector<NEN, D> gap;
    const bool lagging = out.gap(c, gap);
    const bool need_K = b.tangent || lagging;
    ElementVector<NEN, D> r = ElementVector<NEN, D>::Zero();
    ElementMatrix<NEN, D> K = ElementMatrix<NEN, D>::Zero();
    const BodyMaterial& material = b.materials[std::size_t(b.cells.body[c])];
    Mat3* F = &b.quad.F[NQ * c];
    bool ok = true;
    if (b.quad.be_n.used()) {  // a history per point: the material's step at each
      for (int q = 0; q < NQ && ok; ++q)
        ok = visit_point_material(material.model, point_history(b, cell.F_n[q], NQ * c + q), [&](const auto& m) {
          return add_displacement_point<NEN, D>(m, cell.du, cell.dN[q], cell.dV_n[q], cell.F_n[q], F[q], r, need_K ? &K : nullptr);
        });
    } else {
      ok = std::visit([&](const auto& m) { return isoparametric_internal(m, cell, F, r, need_K ? &K : nullptr); }, material.model);
    }
    if (!ok) return void(b.inverted.fetch_add(1, std::memory_order_relaxed));
    if (b.inertia.on && b.inertia.consistent) {
      auto* K_inertia = need_K ? &K : nullptr;
      if constexpr (NEN == 6) {
        add_consistent_inertia<6, 12>(b.nodes, b.cells, c, b.inertia, material.density, tri6_consistent_mass(reference_volume(cell)),
                                      u_index.data(), r, K_inertia);
      } else if constexpr (NEN == 9) {
        double dV0[NQ];
        for (int q = 0; q < NQ; ++q) dV0[q] = cell.dV_n[q] / cell.F_n[q].determinant();
        add_consistent_inertia<9, 18>(b.nodes, b.cells, c, b.inertia, material.density, quad9_consistent_mass(dV0), u_index.data(), r,
                                      K_inertia);
      } else if constexpr (NEN == 4) {
        add_consistent_inertia<4, 12>(b.nodes, b.cells, c, b.inertia, material.density, tet4_consistent_mass(reference_volume(cell)),
                                      u_index.data(), r, K_inertia);
      } else {
        static_assert(NEN == 10);
        add_consistent_inertia<10, 30>(b.nodes, b.cells, c, b.inertia, material.density, tet10_consistent_mass(reference_volume(cell)),
                                       u_index.data(), r, K_inertia);
      }
    }
    if (lagging) r += K * gap;
    out.scatter(c, r, b.tangent ? &K : nullptr);
  });
}

// The mixed simplex (seed 000 §4.2): D + 1 corners with D + 1 dofs each (u, phi), D + 1 points.
template <int D>
void assemble_uphi_block(const BlockArgs<D>& b) {
  constexpr int S = D + 1, NE = S * S;
  LocalMap<NE> map{};
  for (int k = 0; k < NE; ++k) map.to_scatter[k] = k;  // the run has D + 1 dofs per node: same layout
  const CellScatterer<NE, D> out(map, b.scatter, b.bc, b.nodes, b.system);
  static constexpr auto u_index = [] {  // the displacement entries of the element vector
    std::array<int, D * S> k{};
    for (int a = 0; a < S; ++a)
      for (int i = 0; i < D; ++i) k[std::size_t(D * a + i)] = S * a + i;
    return k;
  }();
  for_each_cell_prefetching_scatter(b.cells, out, b.tangent, [&](Index c) {
    UPhiCellT<D> cell;
    for (int a = 0; a < S; ++a) {
      const Index n = b.cells.node(c, a);
      cell.du.row(a) = (b.nodes.u[n] - b.nodes.u_n[n]).transpose();
      cell.phi[a] = b.nodes.phi[n];
    }
    cell.dN = Eigen::Map<const NodalVectors<S, D>>(b.quad.grad(S * c));
    for (int q = 0; q < S; ++q) cell.dV_n[q] = b.quad.weight_n[S * c + q], cell.F_n[q] = b.quad.F_n[S * c + q];
    UPhiVectorT<D> gap;
    const bool lagging = out.gap(c, gap);
    const bool need_K = b.tangent || lagging;
    UPhiVectorT<D> r = UPhiVectorT<D>::Zero();
    UPhiMatrixT<D> K = UPhiMatrixT<D>::Zero();
    const BodyMaterial& material = b.materials[std::size_t(b.cells.body[c])];
    Mat3* Ft = &b.quad.F[S * c];
    const bool ok = std::visit(
        [&](const auto& m) { return uphi_internal<D>(m, material.alpha_over_G, cell, Ft, r, need_K ? &K : nullptr); }, material.model);
    if (!ok) return void(b.inverted.fetch_add(1, std::memory_order_relaxed));
    if (b.inertia.on && b.inertia.consistent) {
      double volume0 = 0.0;
      for (int q = 0; q < S; ++q) volume0 += cell.dV_n[q] / cell.F_n[q].determinant();
      if constexpr (D == 2)
        add_consistent_inertia<3, 9>(b.nodes, b.cells, c, b.inertia, material.density, tri3_consistent_mass(volume0), u_index.data(), r,
                                     need_K ? &K : nullptr);
      else
        add_consistent_inertia<4, 16>(b.nodes, b.cells, c, b.inertia, material.density, tet4_consistent_mass(volume0), u_index.data(), r,
                                      need_K ? &K : nullptr);
    }
    if (lagging) r += K * gap;
    out.scatter(c, r, b.tangent ? &K : nullptr);
  });
}

// The blocks of one dimension: 2D has seed 001's smoothed formulations besides the displacement and mixed
// cells; 3D has the tetrahedra (p1: tet4 at one point, tri6's counterpart tet10 at four, p1p1_uphi: tet4 u-phi).
void assemble_block(const BlockArgs<2>& args, const Cells& cells, bool tangent, const std::vector<BodyMaterial>& materials,
                    const Nodes<2>& nodes, const BoundaryConditions<2>& bc, const CellScatter& scatter, LinearSystem& system,
                    std::atomic<Index>& inverted) {
  switch (cells.formulation) {
    case Formulation::p1: assemble_p1_block(args); break;
    case Formulation::tri6: assemble_isoparametric_block<6, 3>(args); break;
    case Formulation::quad9: assemble_isoparametric_block<9, 9>(args); break;
    case Formulation::p1p1_uphi: assemble_uphi_block(args); break;
    case Formulation::p1p1_up: LOOM_ASSERT(false, "p1p1_up cells live on MPM grids (assemble_grid_system)"); break;
    case Formulation::es_up:
    case Formulation::fem_up: assemble_simplex_pressure_terms<2>(tangent, materials, nodes, bc, cells, scatter, system); break;
    case Formulation::es_u:
    case Formulation::fem_u: break;  // everything is on the domains
  }
  if (integrates_on_domains(cells.formulation)) inverted += inverted_simplices(nodes, cells);
}

void assemble_block(const BlockArgs<3>& args, const Cells& cells, bool tangent, const std::vector<BodyMaterial>& materials,
                    const Nodes<3>& nodes, const BoundaryConditions<3>& bc, const CellScatter& scatter, LinearSystem& system,
                    std::atomic<Index>& inverted) {
  switch (cells.formulation) {
    case Formulation::p1: assemble_isoparametric_block<4, 1>(args); break;
    case Formulation::tri6: assemble_isoparametric_block<10, 4>(args); break;
    case Formulation::p1p1_uphi: assemble_uphi_block(args); break;
    case Formulation::es_up:
    case Formulation::fem_up: assemble_simplex_pressure_terms<3>(tangent, materials, nodes, bc, cells, scatter, system); break;
    case Formulation::es_u:
    case Formulation::fem_u: break;  // everything is on the face (tetrahedron) domains
    default: LOOM_ASSERT(false, "formulation without a 3D element (the scene loader refuses it)"); break;
  }
  if (integrates_on_domains(cells.formulation)) inverted += inverted_simplices(nodes, cells);
}

}  // namespace

template <int D>
AssemblyResult assemble_system(const StepContext& ctx, AssemblyMode mode, const std::vector<BodyMaterial>& materials,
                               const Nodes<D>& nodes, const std::vector<Cells>& cells,
                               const BoundaryConditions<D>& bc, std::vector<QuadPoints<D>>& quad,
                               LinearSystem& system, std::vector<Edges<D>>* domains) {
  const bool tangent = mode == AssemblyMode::residual_and_tangent;
  const Inertia inertia = mode == AssemblyMode::static_residual ? Inertia{} : inertia_of(ctx);
  auto& A = system.pattern.matrix;
  if (tangent) zero_in_parallel(A.valuePtr(), A.nonZeros());
  system.residual_full.setZero();

  std::atomic<Index> inverted{0};
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const BlockArgs<D> args{tangent, inertia, materials, nodes, cells[k], bc, quad[k], system.scatter[k], system, inverted, ctx.dt};
    assemble_block(args, cells[k], tangent, materials, nodes, bc, system.scatter[k], system, inverted);
  }
  if (domains)
    for (std::size_t e = 0; e < domains->size(); ++e)
      assemble_domain_block(ctx, tangent, materials, nodes, bc, (*domains)[e], system.domain_scatter[e], system, inverted);

  // Nodal terms: lumped inertia and external loads; every node writes only its own entries.
  const DofMap& dofs = system.dofs;
  const bool lumped = inertia.on && !inertia.consistent;
  double* values = A.valuePtr();
  for_each_index(nodes.size(), [&](Index i) {
    const Vec<D> acc = lumped ? acceleration(nodes, i, inertia) : Vec<D>::Zero();
    for (int d = 0; d < D; ++d) {
      const Index dof = dofs.dof(i, d);
      double r = -bc.external[dof];
      if (lumped) {
        r += nodes.lumped_mass[i] * acc[d];
        const Index eq = dofs.equation[std::size_t(dof)];
        if (tangent && eq != kNoIndex) values[system.pattern.diagonal_slot[std::size_t(eq)]] += nodes.lumped_mass[i] * inertia.integrator.stiffness();
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
      const double m4 = 0.25 * nodes.lumped_mass[node] * inertia.integrator.stiffness();
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

template AssemblyResult assemble_system<2>(const StepContext&, AssemblyMode, const std::vector<BodyMaterial>&, const Nodes<2>&,
                                           const std::vector<Cells>&, const BoundaryConditions<2>&, std::vector<QuadPoints<2>>&,
                                           LinearSystem&, std::vector<Edges<2>>*);
template AssemblyResult assemble_system<3>(const StepContext&, AssemblyMode, const std::vector<BodyMaterial>&, const Nodes<3>&,
                                           const std::vector<Cells>&, const BoundaryConditions<3>&, std::vector<QuadPoints<3>>&,
                                           LinearSystem&, std::vector<Edges<3>>*);

}  // namespace loom
