#include "systems/loads/apply_boundary_conditions.hpp"

#include <cmath>

#include "systems/assemble/elements/tri3.hpp"

namespace loom {
namespace {

// Two-point Gauss rule on an edge: exact for the cubic integrand N^A t(x) with t quadratic.
constexpr double kGauss2[2] = {0.5 - 0.5 / 1.7320508075688772, 0.5 + 0.5 / 1.7320508075688772};

void add_tractions(double t, const Nodes<2>& nodes, BoundaryConditions<2>& bc) {
  for (const auto& e : bc.traction_edges) {
    const Vec2 Xa = nodes.X[e.a], Xb = nodes.X[e.b];
    const double length = (Xb - Xa).norm();  // reference length: dead load (eq 8 pulled back to B_0)
    for (double s : kGauss2) {
      const Vec2 X = (1 - s) * Xa + s * Xb;
      for (int d = 0; d < 2; ++d) {
        if (e.expression[std::size_t(d)] == kNoIndex) continue;
        const double value = bc.expressions[std::size_t(e.expression[std::size_t(d)])](t, X.x(), X.y());
        bc.external[bc.per_node * e.a + d] += 0.5 * length * (1 - s) * value;
        bc.external[bc.per_node * e.b + d] += 0.5 * length * s * value;
      }
    }
  }
}

// f_vol^A = int rho_0 N^A b dV_0 (eq 7), three-point rule on the reference cell.
void add_body_forces(double t, const Nodes<2>& nodes, const std::vector<Cells>& cells,
                     const std::vector<BodyMaterial>& materials, BoundaryConditions<2>& bc) {
  for (const Cells& cb : cells)
    for (Index c = 0; c < cb.size(); ++c) {
      const Index body = cb.body[c];
      const auto& exprs = bc.body_force[std::size_t(body)];
      if (exprs[0] == kNoIndex && exprs[1] == kNoIndex) continue;
      const Index* n = cb.cell_nodes(c);
      const Vec2 X[3] = {nodes.X[n[0]], nodes.X[n[1]], nodes.X[n[2]]};
      const double area = 0.5 * ((X[1] - X[0]).x() * (X[2] - X[0]).y() - (X[2] - X[0]).x() * (X[1] - X[0]).y());
      const double rho = materials[std::size_t(body)].density;
      for (const auto& bary : kTri3Rule3) {
        const Vec2 Xq = bary[0] * X[0] + bary[1] * X[1] + bary[2] * X[2];
        for (int d = 0; d < 2; ++d) {
          if (exprs[std::size_t(d)] == kNoIndex) continue;
          const double b = bc.expressions[std::size_t(exprs[std::size_t(d)])](t, Xq.x(), Xq.y());
          for (int a = 0; a < 3; ++a) bc.external[bc.per_node * n[a] + d] += rho * b * bary[a] * area / 3.0;
        }
      }
    }
}

}  // namespace

void apply_boundary_conditions(const StepContext& ctx, const Nodes<2>& nodes, const std::vector<Cells>& cells,
                               const std::vector<BodyMaterial>& materials, BoundaryConditions<2>& bc) {
  for (const auto& p : bc.prescribed) {
    const Vec2& X = nodes.X[p.node];
    bc.target[p.dof] = bc.expressions[std::size_t(p.expression)](ctx.t, X.x(), X.y());
  }
  const bool fresh = bc.external_time == ctx.t || (!bc.loads_depend_on_time && !std::isnan(bc.external_time));
  if (fresh) return;
  bc.external.setZero();
  if (bc.has_loads) {
    add_tractions(ctx.t, nodes, bc);
    add_body_forces(ctx.t, nodes, cells, materials, bc);
  }
  bc.external_time = ctx.t;
}

}  // namespace loom
