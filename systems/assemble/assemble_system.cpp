#include "systems/assemble/assemble_system.hpp"

#include <atomic>

#include "engine/core/parallel.hpp"
#include "systems/assemble/elements/p1_cell.hpp"

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

template <int NDOF>
void scatter_cell(Index c, const CellScatter& sc, const Eigen::Matrix<double, NDOF, 1>& r,
                  const Eigen::Matrix<double, NDOF, NDOF>* K, LinearSystem& system) {
  for (int a = 0; a < NDOF; ++a) system.residual_full[sc.cell_dof(c, a)] += r[a];
  if (!K) return;
  double* values = system.pattern.matrix.valuePtr();
  for (int a = 0; a < NDOF; ++a)
    for (int b = 0; b < NDOF; ++b) {
      const Index s = sc.matrix_slot(c, a, b);
      if (s != kNoIndex) values[s] += (*K)(a, b);
    }
}

void assemble_p1_block(bool tangent, const Inertia& inertia, const std::vector<BodyMaterial>& materials,
                       const Nodes<2>& nodes, const Cells& cells, const BoundaryConditions<2>& bc, QuadPoints<2>& quad,
                       const CellScatter& sc, LinearSystem& system, std::atomic<Index>& inverted) {
  for (Index k = 0; k < cells.n_colours(); ++k) {
    const Index begin = cells.colour_offsets[std::size_t(k)], end = cells.colour_offsets[std::size_t(k) + 1];
    for_each_in(cells.by_colour.data() + begin, end - begin, [&](Index c) {
      P1Cell cell = gather_p1_cell(nodes, cells, quad, c);
      // Dirichlet gap of the cell's prescribed dofs (zero once they have reached their targets).
      P1Vector gap = P1Vector::Zero();
      bool lagging = false;
      for (int a = 0; a < 6; ++a) {
        const Index dof = sc.cell_dof(c, a);
        if (system.dofs.kind[std::size_t(dof)] != DofKind::prescribed) continue;
        gap[a] = bc.target[dof] - nodes.u[dof / system.dofs.per_node][dof % system.dofs.per_node];
        lagging = lagging || gap[a] != 0.0;
      }
      const bool need_K = tangent || lagging;
      P1Vector r = P1Vector::Zero();
      P1Matrix K = P1Matrix::Zero();
      const BodyMaterial& material = materials[std::size_t(cells.body[c])];
      const bool ok = std::visit(
          [&](const auto& m) { return p1_internal(m, cell, quad.F[c], r, need_K ? &K : nullptr); }, material.model);
      if (!ok) {
        inverted.fetch_add(1, std::memory_order_relaxed);
        return;
      }
      if (inertia.on && inertia.consistent) {
        const double m = material.density * cell.volume0 / 12.0;  // consistent P1 mass: rho_0 A_0 (1 + d_ab) / 12
        P1Vector acc;
        for (int a = 0; a < 3; ++a) acc.segment<2>(2 * a) = acceleration(nodes, cells.node(c, a), inertia);
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) {
            const double mab = m * (a == b ? 2.0 : 1.0);
            r.segment<2>(2 * a) += mab * acc.segment<2>(2 * b);
            if (need_K) K(2 * a, 2 * b) += mab * inertia.inv_dt2, K(2 * a + 1, 2 * b + 1) += mab * inertia.inv_dt2;
          }
      }
      if (lagging) r += K * gap;
      scatter_cell<6>(c, sc, r, tangent ? &K : nullptr, system);
    });
  }
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
  for (std::size_t b = 0; b < cells.size(); ++b) {
    switch (cells[b].formulation) {
      case Formulation::p1:
        assemble_p1_block(tangent, inertia, materials, nodes, cells[b], bc, quad[b], system.scatter[b], system, inverted);
        break;
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
  for_each_index(dofs.n_dofs(), [&](Index dof) {
    const Index eq = dofs.equation[std::size_t(dof)];
    if (eq != kNoIndex) system.residual[eq] = system.residual_full[dof];
  });
  return {inverted.load()};
}

}  // namespace loom
