// body[].initial_velocity (engine/methods/model/initial_velocity.hpp). A free body given a uniform velocity v0 and
// no force translates rigidly: F = I, no internal force, zero acceleration, so every integrator's update
// (Newmark, Bossak, Euler backward on the nodes; Newmark on the MPM grid) keeps v = v0 and gives
// u(t_n) = v0 t_n at every node or particle, to round-off, with fem, pfem (remeshed every step) and mpm. A
// field (a rotation about the origin) is evaluated at each point's reference position for every kind of
// point that carries a velocity: fem nodes, mpm particles (grid and particle Newmark) and the nodes of
// mpm_fem's FEM bodies. A static scene refuses the key, and a field that is not finite names it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "engine/core/errors.hpp"
#include "engine/scene/scene_loader.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

const Vec2 kV0(2.0, -1.0);
constexpr double kDt = 0.05;
constexpr int kSteps = 10;

std::string block_text(const std::string& method, const std::string& integrator, const std::string& velocity) {
  std::string s = "[scene]\nname = \"moving-block\"\nmethod = \"" + method + "\"\n"
                  "[time]\nintegrator = \"" + integrator + "\"\ndt = 0.05\nsteps = 10\n"
                  "[solver]\nresidual_relative = 1e-12\n"
                  "[[material]]\nname = \"m\"\nmodel = \"neo_hooke\"\nE = 100.0\nnu = 0.3\ndensity = 2.0\n"
                  "[[body]]\nname = \"block\"\nmaterial = \"m\"\nelement = \"p1\"\n"
                  "mesh = { generator = \"rectangle\", origin = [1.0, 2.0], size = [1.0, 0.5], divisions = [6, 3], pattern = \"alternating\" }\n"
                  "initial_velocity = " + velocity + "\n"
                  "[output]\nevery = 0\n";
  if (method == "mpm")
    s += "[grid]\ngenerator = \"rectangle\"\norigin = [0.0, 0.0]\nsize = [4.0, 4.0]\ndivisions = [16, 16]\npattern = \"right\"\n";
  return s;
}

constexpr const char* kUniform = "{ x = \"2\", y = \"-1\" }";
constexpr const char* kRotation = "{ x = \"0.5 * y\", y = \"-0.5 * x\" }";

void check_translation(const std::string& method, const std::string& integrator) {
  SCOPED_TRACE(method + ", " + integrator);
  const SceneSpec scene = testing::scene_from_text(block_text(method, integrator, kUniform));
  const Vec2 u_exact = kV0 * kDt * kSteps;
  double worst_u = 0.0, worst_v = 0.0;
  RunSummary summary;
  if (method == "mpm") {
    auto run = testing::make_mpm_run(scene);
    summary = run->run();
    const auto& p = run->model().particles;
    for (Index k = 0; k < p.X.size(); ++k)
      worst_u = std::max(worst_u, (p.u[k] - u_exact).norm() / u_exact.norm()), worst_v = std::max(worst_v, (p.v[k] - kV0).norm() / kV0.norm());
  } else {
    auto run = testing::make_fem_run(scene);
    summary = run->run();
    const Nodes<2>& n = run->nodes();
    for (Index i = 0; i < n.size(); ++i)
      worst_u = std::max(worst_u, (n.u_n[i] - u_exact).norm() / u_exact.norm()), worst_v = std::max(worst_v, (n.v_n[i] - kV0).norm() / kV0.norm());
  }
  ASSERT_TRUE(summary.converged) << summary.failure;
  EXPECT_LE(worst_u, 1e-12);
  EXPECT_LE(worst_v, 1e-12);
  std::printf("[initial velocity] %-4s %-14s translation after %d steps: u %.1e, v %.1e (relative)\n", method.c_str(), integrator.c_str(),
              kSteps, worst_u, worst_v);
}

}  // namespace

TEST(InitialVelocity, FreeBodyTranslatesRigidlyWithEveryIntegrator) {
  for (const char* integrator : {"newmark", "bossak", "euler_backward"}) check_translation("fem", integrator);
  check_translation("pfem", "euler_backward");
  check_translation("mpm", "newmark");
}

TEST(InitialVelocity, FieldIsEvaluatedAtEveryPointsReferencePosition) {
  auto rotation = [](const Vec2& X) { return Vec2(0.5 * X.y(), -0.5 * X.x()); };
  {
    auto run = testing::make_fem_run(testing::scene_from_text(block_text("fem", "newmark", kRotation)));
    const Nodes<2>& n = run->nodes();
    for (Index i = 0; i < n.size(); ++i) ASSERT_EQ(n.v_n[i], rotation(n.X[i])) << "node " << i;
  }
  {
    auto run = testing::make_mpm_run(testing::scene_from_text(block_text("mpm", "newmark", kRotation)));
    const auto& p = run->model().particles;
    for (Index k = 0; k < p.X.size(); ++k) ASSERT_EQ(p.v[k], rotation(p.X[k])) << "particle " << k;
  }
  {  // particle Newmark: the particles carry the Newmark state
    const SceneSpec scene = load_scene(std::string(LOOM_SOURCE_DIR) + "/scenes/cantilever_mpm_particle.toml",
                                       {"body[0].initial_velocity.x=\"0.5 * y\"", "body[0].initial_velocity.y=\"-0.5 * x\""});
    auto run = testing::make_mpm_run(scene);
    const auto& p = run->model().particles;
    for (Index k = 0; k < p.X.size(); ++k) ASSERT_EQ(p.v[k], rotation(p.X[k])) << "particle " << k;
  }
  {  // mpm_fem: the plate's nodes (body 1); the disk (body 0) has none
    const SceneSpec scene = load_scene(std::string(LOOM_SOURCE_DIR) + "/scenes/bouncing_disk.toml",
                                       {"body[1].initial_velocity.x=\"0.5 * y\"", "body[1].initial_velocity.y=\"-0.5 * x\""});
    auto run = testing::make_mpm_run(scene);
    const MpmModel& m = run->model();
    Index fem_nodes = 0;
    std::vector<char> in_plate(std::size_t(m.grid_nodes.size()), 0);
    for (Index c = m.coupled_mesh.grid_cells; c < m.grid.size(); ++c)
      for (int a = 0; a < m.grid.stride; ++a) in_plate[std::size_t(m.grid.node(c, a))] = 1;
    for (Index i = 0; i < m.grid_nodes.size(); ++i) {
      if (!in_plate[std::size_t(i)]) continue;
      ++fem_nodes;
      ASSERT_EQ(m.grid_nodes.v[i], rotation(m.grid_nodes.X[i])) << "plate node " << i;
    }
    EXPECT_GT(fem_nodes, 100);
    for (Index k = 0; k < m.particles.X.size(); ++k) ASSERT_EQ(m.particles.v[k], Vec2::Zero()) << "disk particle " << k;
  }
}

TEST(InitialVelocity, StaticSceneRefusesTheKeyAndANonFiniteFieldNamesIt) {
  try {
    testing::scene_from_text(block_text("fem", "static", kUniform));
    FAIL() << "a static scene took an initial velocity";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("body[0].initial_velocity"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("static"), std::string::npos) << e.what();
  }
  try {  // the loader's check of expressions finds it (at the mesh's nodes); the model's would too
    testing::make_fem_run(testing::scene_from_text(block_text("fem", "newmark", "{ x = \"sqrt(1.5 - x)\" }")));
    FAIL() << "a field that is not finite was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("body[0].initial_velocity.x"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
  }
}

}  // namespace loom
