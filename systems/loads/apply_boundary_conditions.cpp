#include "systems/loads/apply_boundary_conditions.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "engine/mesh/quad9_shape.hpp"
#include "systems/assemble/elements/tet10.hpp"
#include "systems/assemble/elements/tet4.hpp"
#include "systems/assemble/elements/tri3.hpp"
#include "systems/assemble/elements/tri6.hpp"

namespace loom {
namespace {

// Three-point Gauss rule on [0, 1]: exact for N^A t(x) with quadratic N^A and t up to cubic.
constexpr double kGaussPoints3[3] = {0.5 - 0.3872983346207417, 0.5, 0.5 + 0.3872983346207417};
constexpr double kGaussWeights3[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};

void add_tractions(double t, const Nodes<2>& nodes, BoundaryConditions<2>& bc) {
  for (const auto& e : bc.traction_edges) {
    const Vec2 Xa = nodes.X[e.a], Xb = nodes.X[e.b];
    const double length = (Xb - Xa).norm();  // reference length: dead load (eq 8 pulled back to B_0)
    for (int g = 0; g < 3; ++g) {
      const double s = kGaussPoints3[g], w = kGaussWeights3[g] * length;
      const Vec2 X = (1 - s) * Xa + s * Xb;
      // Shape functions along the edge: linear, or quadratic with the mid-node.
      const bool quadratic = e.mid != kNoIndex;
      const double Na = quadratic ? (1 - s) * (1 - 2 * s) : 1 - s;
      const double Nb = quadratic ? s * (2 * s - 1) : s;
      const double Nm = quadratic ? 4 * s * (1 - s) : 0.0;
      for (int d = 0; d < 2; ++d) {
        if (e.expression[std::size_t(d)] == kNoIndex) continue;
        const double value = w * bc.expressions[std::size_t(e.expression[std::size_t(d)])](t, X.x(), X.y());
        bc.external[bc.per_node * e.a + d] += Na * value;
        bc.external[bc.per_node * e.b + d] += Nb * value;
        if (quadratic) bc.external[bc.per_node * e.mid + d] += Nm * value;
      }
    }
  }
}

// quad9: the 3 x 3 Gauss rule on the isoparametric reference cell.
template <class Exprs>
void add_quad9_body_force(double t, const Nodes<2>& nodes, const Index* n, double rho, const Exprs& exprs, BoundaryConditions<2>& bc) {
  Quad9Coordinates X;
  for (int a = 0; a < 9; ++a) X.row(a) = nodes.X[n[a]].transpose();
  const Quad9Gauss& rule = quad9_gauss();
  for (int q = 0; q < 9; ++q) {
    const Vec2& xi = rule.xi[std::size_t(q)];
    const Quad9Values N = quad9_shape(xi);
    const double dV0 = (X.transpose() * quad9_reference_gradients(xi)).determinant() * rule.weight[std::size_t(q)];
    const Vec2 Xq = X.transpose() * N;
    for (int d = 0; d < 2; ++d) {
      if (exprs[std::size_t(d)] == kNoIndex) continue;
      const double b = bc.expressions[std::size_t(exprs[std::size_t(d)])](t, Xq.x(), Xq.y());
      for (int a = 0; a < 9; ++a) bc.external[bc.per_node * n[a] + d] += rho * b * N[a] * dV0;
    }
  }
}

// f_vol^A = int rho_0 N^A b dV_0 (eq 7) on the reference cell (straight, mid-nodes at the midpoints):
// three-point rule for linear cells, the degree-4 rule for quadratic ones.
void add_body_forces(double t, const Nodes<2>& nodes, const std::vector<Cells>& cells,
                     const std::vector<BodyMaterial>& materials, BoundaryConditions<2>& bc) {
  for (const Cells& cb : cells)
    for (Index c = 0; c < cb.size(); ++c) {
      const Index body = cb.body[c];
      const auto& exprs = bc.body_force[std::size_t(body)];
      if (exprs[0] == kNoIndex && exprs[1] == kNoIndex) continue;
      const Index* n = cb.cell_nodes(c);
      const double rho = materials[std::size_t(body)].density;
      if (cb.type == CellType::quad9) {
        add_quad9_body_force(t, nodes, n, rho, exprs, bc);
        continue;
      }
      const Vec2 X[3] = {nodes.X[n[0]], nodes.X[n[1]], nodes.X[n[2]]};
      // Seed 001's triangles know their reference area; a remeshed triangle's corners in X need not form one.
      const double area = integrates_on_domains(cb.formulation) && cb.measure.used()
                              ? cb.measure[c]
                              : 0.5 * ((X[1] - X[0]).x() * (X[2] - X[0]).y() - (X[2] - X[0]).x() * (X[1] - X[0]).y());
      auto add_point = [&](const double* l, double weight, const double* N, int n_nodes) {
        const Vec2 Xq = l[0] * X[0] + l[1] * X[1] + l[2] * X[2];
        for (int d = 0; d < 2; ++d) {
          if (exprs[std::size_t(d)] == kNoIndex) continue;
          const double b = bc.expressions[std::size_t(exprs[std::size_t(d)])](t, Xq.x(), Xq.y());
          for (int a = 0; a < n_nodes; ++a) bc.external[bc.per_node * n[a] + d] += rho * b * N[a] * weight * area;
        }
      };
      if (cb.type == CellType::tri6) {
        for (const auto& p : kTriangleRule6) {
          const Tri6Values N = tri6_values(p.l[0], p.l[1], p.l[2]);
          add_point(p.l, p.w, N.data(), 6);
        }
      } else {
        for (const auto& l : kTri3Rule3) add_point(l, 1.0 / 3.0, l, 3);
      }
    }
}

// 3D: dead-load tractions on the faces (area in the reference configuration, flat faces), by the degree-4
// triangle rule: exact for the quadratic shape functions times tractions up to quadratic.
void add_tractions(double t, const Nodes<3>& nodes, BoundaryConditions<3>& bc) {
  for (const TractionFace& f : bc.traction_faces) {
    const Vec3 &X0 = nodes.X[f.nodes[0]], &X1 = nodes.X[f.nodes[1]], &X2 = nodes.X[f.nodes[2]];
    const double area = 0.5 * (X1 - X0).cross(X2 - X0).norm();
    const bool quadratic = f.nodes[3] != kNoIndex;
    for (const auto& p : kTriangleRule6) {
      const Vec3 X = p.l[0] * X0 + p.l[1] * X1 + p.l[2] * X2;
      const Tri6Values N6 = tri6_values(p.l[0], p.l[1], p.l[2]);
      const int n = quadratic ? 6 : 3;
      for (int d = 0; d < 3; ++d) {
        if (f.expression[std::size_t(d)] == kNoIndex) continue;
        const double value = p.w * area * bc.expressions[std::size_t(f.expression[std::size_t(d)])](t, X.x(), X.y(), X.z());
        for (int a = 0; a < n; ++a) bc.external[bc.per_node * f.nodes[std::size_t(a)] + d] += (quadratic ? N6[a] : p.l[a]) * value;
      }
    }
  }
}

// 3D: f^A = int rho_0 N^A b dV_0 on the straight reference tetrahedron; tet4 by the four-point rule (degree 2),
// tet10 by the fourteen-point one (degree 5).
void add_body_forces(double t, const Nodes<3>& nodes, const std::vector<Cells>& cells, const std::vector<BodyMaterial>& materials,
                     BoundaryConditions<3>& bc) {
  for (const Cells& cb : cells)
    for (Index c = 0; c < cb.size(); ++c) {
      const Index body = cb.body[c];
      const auto& exprs = bc.body_force[std::size_t(body)];
      if (exprs[0] == kNoIndex && exprs[1] == kNoIndex && exprs[2] == kNoIndex) continue;
      const Index* n = cb.cell_nodes(c);
      const double rho = materials[std::size_t(body)].density;
      const Vec3 X[4] = {nodes.X[n[0]], nodes.X[n[1]], nodes.X[n[2]], nodes.X[n[3]]};
      const double volume = (X[1] - X[0]).dot((X[2] - X[0]).cross(X[3] - X[0])) / 6.0;
      auto add_point = [&](const double* l, double weight, const double* N, int n_nodes) {
        const Vec3 Xq = l[0] * X[0] + l[1] * X[1] + l[2] * X[2] + l[3] * X[3];
        for (int d = 0; d < 3; ++d) {
          if (exprs[std::size_t(d)] == kNoIndex) continue;
          const double b = bc.expressions[std::size_t(exprs[std::size_t(d)])](t, Xq.x(), Xq.y(), Xq.z());
          for (int a = 0; a < n_nodes; ++a) bc.external[bc.per_node * n[a] + d] += rho * b * N[a] * weight * volume;
        }
      };
      if (cb.type == CellType::tet10) {
        for (const auto& p : kTetrahedronRule14) {
          const Tet10Values N = tet10_values(p.l);
          add_point(p.l, p.w, N.data(), 10);
        }
      } else {
        for (const auto& l : kTet4Rule4) add_point(l, 0.25, l, 4);
      }
    }
}

template <int D>
Vec3 position(const Nodes<D>& nodes, Index i) {
  Vec3 X = Vec3::Zero();
  X.head<D>() = nodes.X[i];
  return X;
}

}  // namespace

template <int D>
void apply_boundary_conditions(const StepContext& ctx, const Nodes<D>& nodes, const std::vector<Cells>& cells,
                               const std::vector<BodyMaterial>& materials, BoundaryConditions<D>& bc) {
  for (const auto& p : bc.prescribed) {
    if (p.expression == kNoIndex) {  // driven at a velocity: u = u_n + dt v
      bc.target[p.dof] = nodes.u_n[p.node][p.dof % bc.per_node] + ctx.dt * p.velocity;
      continue;
    }
    const Vec3 X = position(nodes, p.node);
    bc.target[p.dof] = bc.expressions[std::size_t(p.expression)](ctx.t, X.x(), X.y(), X.z());
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

template void apply_boundary_conditions<2>(const StepContext&, const Nodes<2>&, const std::vector<Cells>&, const std::vector<BodyMaterial>&,
                                           BoundaryConditions<2>&);
template void apply_boundary_conditions<3>(const StepContext&, const Nodes<3>&, const std::vector<Cells>&, const std::vector<BodyMaterial>&,
                                           BoundaryConditions<3>&);

}  // namespace loom
