#include "systems/update/coupled_fem.hpp"

#include "engine/core/errors.hpp"
#include "engine/mesh/grid_point_shape.hpp"
#include "systems/assemble/elements/soft_stiffness.hpp"

namespace loom {

void build_reset_field(const Cells& grid, Index grid_cells, const Nodes<2>& nodes, const std::vector<char>& fem_node,
                       const BoundaryConditions<2>& bc, ResetField& out) {
  const Index n_dofs = 2 * nodes.size();
  std::vector<char> held(std::size_t(n_dofs), 0);
  for (Index i = 0; i < nodes.size(); ++i)
    if (fem_node[std::size_t(i)]) held[std::size_t(2 * i)] = held[std::size_t(2 * i + 1)] = 1;
  for (const auto& p : bc.prescribed)
    if (p.dof % bc.per_node < 2) held[std::size_t(2 * p.node + p.dof % bc.per_node)] = 1;
  out.free_index.assign(std::size_t(n_dofs), kNoIndex);
  out.held_index.assign(std::size_t(n_dofs), kNoIndex);
  out.held_dof.clear();
  Index n_free = 0;
  for (Index d = 0; d < n_dofs; ++d) {
    if (held[std::size_t(d)]) out.held_index[std::size_t(d)] = Index(out.held_dof.size()), out.held_dof.push_back(d);
    else out.free_index[std::size_t(d)] = n_free++;
  }
  // int (grad u + grad u^T) : grad phi on the undeformed grid cells (the soft-stiffness integrand with weight one).
  std::vector<Eigen::Triplet<double>> ff, fp;
  for (Index c = 0; c < grid_cells; ++c) {
    ElementMatrix<9> Ke = ElementMatrix<9>::Zero();
    for_each_cell_gauss_point<9>(grid, nodes, c, [&](const NodalVectors<9>& dN, double w) { add_soft_stiffness_point<9>(dN, w, Ke); });
    for (int a = 0; a < 18; ++a) {
      const Index row = out.free_index[std::size_t(2 * grid.node(c, a / 2) + a % 2)];
      if (row == kNoIndex) continue;
      for (int b = 0; b < 18; ++b) {
        const Index dof = 2 * grid.node(c, b / 2) + b % 2;
        if (out.free_index[std::size_t(dof)] != kNoIndex) ff.emplace_back(row, out.free_index[std::size_t(dof)], Ke(a, b));
        else fp.emplace_back(row, out.held_index[std::size_t(dof)], Ke(a, b));
      }
    }
  }
  out.K_ff.reset();
  out.K_fp.resize(n_free, Index(out.held_dof.size()));
  out.K_fp.setFromTriplets(fp.begin(), fp.end());
  if (n_free == 0) return;
  Eigen::SparseMatrix<double> K(n_free, n_free);
  K.setFromTriplets(ff.begin(), ff.end());
  out.K_ff = std::make_shared<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(K);
  LOOM_CHECK(out.K_ff->info() == Eigen::Success, RunError,
             "the grid's reset field ([Aulisa 2019] eq 8) is singular: a part of the grid is held neither by an FEM body nor by a boundary");
}

void reset_grid(const StepContext&, const ResetField& reset, const std::vector<char>& fem_node, Nodes<2>& nodes) {
  for (Index i = 0; i < nodes.size(); ++i) nodes.u[i].setZero();
  if (!reset.any_free()) return;
  Eigen::VectorXd held(Index(reset.held_dof.size()));
  for (Index k = 0; k < held.size(); ++k) {
    const Index dof = reset.held_dof[std::size_t(k)], i = dof / 2;
    held[k] = fem_node[std::size_t(i)] ? nodes.u_n[i][dof % 2] : 0.0;
  }
  const Eigen::VectorXd u = reset.K_ff->solve(-(reset.K_fp * held));
  for (Index i = 0; i < nodes.size(); ++i) {
    if (fem_node[std::size_t(i)]) continue;
    Vec2 r = Vec2::Zero();
    for (int d = 0; d < 2; ++d) {
      const Index f = reset.free_index[std::size_t(2 * i + d)];
      r[d] = f == kNoIndex ? 0.0 : u[f];
    }
    nodes.X[i] += r - nodes.u_n[i];
    nodes.u_n[i] = r;
  }
}

void commit_fem_nodes(const StepContext& ctx, const std::vector<char>& fem_node, Nodes<2>& nodes) {
  const SceneSpec& scene = *ctx.scene;
  const double beta = scene.time.beta, gamma = scene.time.gamma, dt = ctx.dt;
  for (Index i = 0; i < nodes.size(); ++i) {
    if (!fem_node[std::size_t(i)]) continue;
    const Vec2 du = nodes.u[i], v_n = nodes.v[i], a_n = nodes.a[i];
    const Vec2 a = du / (beta * dt * dt) - v_n / (beta * dt) - (1.0 - 2.0 * beta) / (2.0 * beta) * a_n;
    nodes.a[i] = a;
    nodes.v[i] = v_n + dt * ((1.0 - gamma) * a_n + gamma * a);
    nodes.u_n[i] += du;
    nodes.X[i] += du;
    nodes.u[i].setZero();  // now in X and u_n
  }
}

}  // namespace loom
