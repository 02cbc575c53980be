// commit_step in 3D (systems/update/commit_step.cpp, D = 3) on a tet4 box under Newmark (beta = 1/4, gamma = 1/2):
// every node's acceleration and velocity follow the Newmark update of its own increment, the iterate becomes
// the history (u_n, F_n), and the reference B_n moves: the weights then add up to the deformed volume det(I + H) V.
#include <gtest/gtest.h>

#include "engine/mesh/tet_generators.hpp"
#include "systems/assemble/compute_geometry.hpp"
#include "systems/update/commit_step.hpp"

namespace loom {

TEST(CommitStep3D, NewmarkHistoryAndTheMovedReference) {
  BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 2;
  const TetMeshData mesh = generate_box(spec);
  Nodes<3> nodes;
  for (auto* c : {&nodes.v, &nodes.v_n, &nodes.a, &nodes.a_n}) c->use();
  nodes.resize(Index(mesh.X.size()));
  for (Index i = 0; i < nodes.size(); ++i) nodes.X[i] = mesh.X[std::size_t(i)];
  Cells cells;
  cells.type = CellType::tet4;
  cells.stride = 4;
  cells.nodes.values() = mesh.tets;
  cells.body.values().assign(mesh.tets.size() / 4, 0);
  std::vector<Cells> blocks = {cells};
  std::vector<QuadPoints<3>> quad;
  allocate_quad_points(blocks, quad);
  ASSERT_EQ(compute_geometry(nodes, blocks, quad), 0);

  Mat3 H;
  H << 0.1, 0.02, -0.03, 0.0, -0.05, 0.04, 0.01, 0.0, 0.08;
  const Vec3 v0(0.3, -0.1, 0.2), a0(0.0, 0.0, -9.81);
  for (Index i = 0; i < nodes.size(); ++i) {
    nodes.u[i] = H * nodes.X[i];
    nodes.v_n[i] = v0 + 0.1 * nodes.X[i];
    nodes.a_n[i] = a0;
  }
  for (Index p = 0; p < quad[0].size(); ++p) quad[0].F[p] = Mat3::Identity() + H;

  SceneSpec scene;
  scene.time.integrator = Integrator::newmark;
  StepContext ctx;
  ctx.scene = &scene;
  ctx.dt = 0.1;
  const Nodes<3> before = nodes;
  commit_step(ctx, blocks, nodes, quad);

  const double dt = 0.1, beta = 0.25, gamma = 0.5;
  for (Index i = 0; i < nodes.size(); ++i) {
    const Vec3 du = before.u[i];
    const Vec3 a = (du - dt * before.v_n[i]) / (beta * dt * dt) - (0.5 / beta - 1.0) * before.a_n[i];
    const Vec3 v = before.v_n[i] + dt * ((1 - gamma) * before.a_n[i] + gamma * a);
    EXPECT_LE((nodes.a_n[i] - a).norm(), 1e-12 * a.norm());
    EXPECT_LE((nodes.v_n[i] - v).norm(), 1e-12 * v.norm());
    EXPECT_EQ(nodes.u_n[i], before.u[i]);
  }
  double volume = 0.0;
  for (Index p = 0; p < quad[0].size(); ++p) {
    volume += quad[0].weight_n[p];
    EXPECT_EQ(quad[0].F_n[p], Mat3(Mat3::Identity() + H));
  }
  EXPECT_NEAR(volume, (Mat3::Identity() + H).determinant(), 1e-14);
}

}  // namespace loom
