// The assembled Newton system of seed 001's elements against central finite differences of the assembled
// residual: everything a step assembles at once (edge kernels of interior and boundary edges, the triangles'
// pressure terms K_pp,K and K_stab, the Bossak inertia of the lumped mass, external loads), for es_up, es_u,
// fem_up and fem_u, at a random state with viscoplastic flow under way (tests/unit/smoothed_domain_test.cpp
// checks the kernels alone). The prescribed dofs sit at their targets: the Dirichlet lift (K times the gap)
// is not a derivative of the residual. Each block (u-u, u-p, p-u, p-p) is compared against its own largest
// entry, so that the small pressure blocks are not hidden by the mass term. The same on tetrahedra (face domains of
// 5 and 4 nodes, the tetrahedra's pressure terms) in 3D.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "engine/methods/model/fem_model.hpp"
#include "systems/assemble/assemble_system.hpp"
#include "systems/loads/apply_boundary_conditions.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

std::string scene_text(const std::string& element, int dimension) {
  std::string s = "[scene]\nname = \"tangent\"\ndimension = " + std::to_string(dimension) + "\n[time]\nintegrator = \"bossak\"\nalpha = -0.2\ndt = 0.05\nsteps = 1\n";
  s += "[[material]]\nname = \"m\"\nmodel = \"hencky_perzyna\"\nE = 10.0\nnu = 0.45\ntau0 = 0.02\nviscosity = 0.3\ndensity = 2.0\n";
  s += "[[body]]\nname = \"b\"\nmaterial = \"m\"\nelement = \"" + element + "\"\n";
  if (element == "es_up" || element == "fem_up") s += "alpha_stab = 0.5\n";
  if (dimension == 2) {
    s += "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [1.0, 0.6], divisions = [4, 3], pattern = \"alternating\", distortion = 0.2 }\n";
    s += "body_force = { y = -1.0 }\n";
    s += "[[boundary]]\nname = \"left\"\nregion = { box = [[0.0, 0.0], [0.0, 0.6]] }\ndisplacement = { x = 0.0, y = \"0.01 * t\" }\n";
    s += "[[boundary]]\nname = \"right\"\nregion = { box = [[1.0, 0.0], [1.0, 0.6]] }\ntraction = { x = 0.1, y = 0.05 }\n";
  } else {
    s += "mesh = { generator = \"box\", origin = [0.0, 0.0, 0.0], size = [1.0, 0.6, 0.5], divisions = [3, 2, 2] }\n";
    s += "body_force = { y = -1.0 }\n";
    s += "[[boundary]]\nname = \"left\"\nregion = { box = [[0.0, 0.0, 0.0], [0.0, 0.6, 0.5]] }\n";
    s += "displacement = { x = 0.0, y = \"0.01 * t\", z = 0.0 }\n";
    s += "[[boundary]]\nname = \"right\"\nregion = { box = [[1.0, 0.0, 0.0], [1.0, 0.6, 0.5]] }\ntraction = { x = 0.1, y = 0.05, z = -0.02 }\n";
  }
  s += "[output]\nevery = 0\n";
  return s;
}

template <int D>
void check(const std::string& element) {
  SCOPED_TRACE(element + " in " + std::to_string(D) + "D");
  const SceneSpec scene = testing::scene_from_text(scene_text(element, D));
  FemModelT<D> m(scene);
  StepContext ctx;
  ctx.scene = &m.scene, ctx.step = 1, ctx.dt = scene.time.dt, ctx.t = ctx.dt;
  apply_boundary_conditions(ctx, m.nodes, m.cells, m.materials, m.bc);
  // A random state: a history b^e_n, velocities, accelerations, a displacement increment and pressures.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> r(-1.0, 1.0);
  const auto random_vector = [&] {
    Vec<D> v;
    for (int d = 0; d < D; ++d) v[d] = r(rng);
    return v;
  };
  for (Edges<D>& e : m.edges)
    for (Index k = 0; k < e.size(); ++k) {
      Mat3 X = Mat3::Zero();
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) X(i, j) = 0.1 * r(rng);
      e.be_n[k] = Mat3::Identity() + X * X.transpose();
    }
  for (Index i = 0; i < m.nodes.size(); ++i) {
    m.nodes.u[i] = m.nodes.u_n[i] + 0.03 * random_vector();
    m.nodes.v_n[i] = random_vector(), m.nodes.a_n[i] = random_vector();
    if (m.nodes.p.used()) m.nodes.p[i] = 0.1 * r(rng);
  }
  // The prescribed dofs at their targets (no lift), so that the residual is a function of the free dofs.
  for (const auto& p : m.bc.prescribed) m.nodes.u[p.node][p.dof % m.bc.per_node] = m.bc.target[p.dof];
  auto dof_ref = [&](Index dof) -> double& {
    const Index node = dof / m.system.dofs.per_node;
    const int c = dof % m.system.dofs.per_node;
    return c < D ? m.nodes.u[node][c] : m.nodes.p[node];
  };
  ASSERT_EQ(assemble_system(ctx, AssemblyMode::residual_and_tangent, m.materials, m.nodes, m.cells, m.bc, m.quad, m.system, &m.edges).inverted_cells, 0);
  Index plastic = 0;
  for (const Edges<D>& e : m.edges)
    for (Index k = 0; k < e.size(); ++k) {
      const Mat3 s = e.stress[k] - e.stress[k].trace() / 3.0 * Mat3::Identity();
      plastic += std::sqrt(0.5 * s.squaredNorm()) > 0.99 * 0.02 ? 1 : 0;  // at the yield surface after the return map
    }
  const Eigen::MatrixXd K(m.system.pattern.matrix);
  const Eigen::VectorXd r0 = m.system.residual;
  const double h = 1e-7;
  // Block of equation / unknown: 0 displacement, 1 pressure.
  std::vector<int> kind_of_eq(std::size_t(m.system.dofs.n_free), 0);
  for (Index dof = 0; dof < m.system.dofs.n_dofs(); ++dof)
    if (const Index eq = m.system.dofs.equation[std::size_t(dof)]; eq != kNoIndex) kind_of_eq[std::size_t(eq)] = dof % m.system.dofs.per_node == D;
  double block_max[2][2] = {{0, 0}, {0, 0}}, block_error[2][2] = {{0, 0}, {0, 0}};
  for (Index j = 0; j < K.cols(); ++j)
    for (Index i = 0; i < K.rows(); ++i)
      block_max[kind_of_eq[std::size_t(i)]][kind_of_eq[std::size_t(j)]] =
          std::max(block_max[kind_of_eq[std::size_t(i)]][kind_of_eq[std::size_t(j)]], std::abs(K(i, j)));
  double worst = 0.0;
  for (Index dof = 0; dof < m.system.dofs.n_dofs(); ++dof) {
    const Index eq = m.system.dofs.equation[std::size_t(dof)];
    if (eq == kNoIndex) continue;
    const double saved = dof_ref(dof);
    dof_ref(dof) = saved + h;
    assemble_system(ctx, AssemblyMode::residual, m.materials, m.nodes, m.cells, m.bc, m.quad, m.system, &m.edges);
    const Eigen::VectorXd rp = m.system.residual;
    dof_ref(dof) = saved - h;
    assemble_system(ctx, AssemblyMode::residual, m.materials, m.nodes, m.cells, m.bc, m.quad, m.system, &m.edges);
    const Eigen::VectorXd rm = m.system.residual;
    dof_ref(dof) = saved;
    const Eigen::VectorXd error = ((rp - rm) / (2 * h) - K.col(eq)).cwiseAbs();
    worst = std::max(worst, error.maxCoeff());
    for (Index i = 0; i < error.size(); ++i) {
      double& e = block_error[kind_of_eq[std::size_t(i)]][kind_of_eq[std::size_t(eq)]];
      e = std::max(e, error[i]);
    }
  }
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      if (block_max[a][b] > 0.0) {
        EXPECT_LT(block_error[a][b], 1e-6 * block_max[a][b]) << "block " << a << b;
      }
  const double scale = K.cwiseAbs().maxCoeff();
  std::printf("[system tangent %dD] %-6s: %lld free dofs, %lld plastic domains, max |K - K_fd| %.1e (max |K| %.1e)\n", D, element.c_str(),
              (long long)m.system.dofs.n_free, (long long)plastic, worst, scale);
  EXPECT_LT(worst, 1e-6 * scale);
  EXPECT_GT(plastic, 0);
}

TEST(SmoothedSystemTangent, MatchesFiniteDifferencesOfTheAssembledResidual) {
  for (const char* element : {"es_up", "es_u", "fem_up", "fem_u"}) check<2>(element);
}

// Face domains (5 nodes inside, 4 on the surface) and the tetrahedra's pressure terms: the same identity.
TEST(SmoothedSystemTangent, MatchesFiniteDifferencesOfTheAssembledResidualOnTetrahedra) {
  for (const char* element : {"es_up", "es_u", "fem_up", "fem_u"}) check<3>(element);
}

}  // namespace
}  // namespace loom
