// Loads of the 3D fem: face tractions on 3-node (tet4) and 6-node (tet10) faces, body forces on tet4 and tet10
// cells, and physical groups of a gmsh file as boundary regions.
//  - Uniaxial tension of a box [0, 2] x [0, 1] x [0, 1] of Kuhn tetrahedra (interior nodes distorted), linear
//    elastic E = 200, nu = 0.25, rollers on x = 0, y = 0, z = 0, traction t_x = s on x = 2: the exact state is
//    homogeneous (sigma_xx = s), so u_x(2) = s L / E and u_y(1) = -nu s H / E at every node, and the rollers' reaction is
//    -s A (A = 1). Exact for every element: the traction's consistent nodal forces are exact for a constant t.
//  - A linear traction t_x = s y (a bending load) is integrated exactly as well: the reaction is -s/2.
//  - Self-weight of gmsh's unit cube (tests/meshes/cube_tet4.msh, cube_tet10.msh) clamped on its physical surface
//    "bottom": the reaction balances rho g V = 2 x 9.81 x 1.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "engine/scene/scene_loader.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

constexpr double kE = 200.0, kNu = 0.25, kS = 3.0;

std::string box_scene(const std::string& element, const std::string& traction) {
  return R"(
[scene]
name = "uniaxial-3d"
method = "fem"
dimension = 3
[time]
integrator = "static"
dt = 1.0
steps = 1
[solver]
residual_relative = 1e-12
[[material]]
name = "m"
model = "linear_elastic"
E = 200.0
nu = 0.25
[[body]]
name = "box"
material = "m"
element = ")" + element + R"("
mesh = { generator = "box", size = [2.0, 1.0, 1.0], divisions = [4, 2, 3], distortion = 0.2, seed = 3 }
[[boundary]]
name = "x0"
region = { box = [[0.0, 0.0, 0.0], [0.0, 1.0, 1.0]] }
displacement = { x = 0.0 }
[[boundary]]
name = "y0"
region = { box = [[0.0, 0.0, 0.0], [2.0, 0.0, 1.0]] }
displacement = { y = 0.0 }
[[boundary]]
name = "z0"
region = { box = [[0.0, 0.0, 0.0], [2.0, 1.0, 0.0]] }
displacement = { z = 0.0 }
[[boundary]]
name = "loaded"
region = { box = [[2.0, 0.0, 0.0], [2.0, 1.0, 1.0]] }
traction = { x = ")" + traction + R"(" }
[[probe]]
name = "ux_end"
kind = "point"
at = [2.0, 0.5, 0.5]
component = "x"
[[probe]]
name = "uy_top"
kind = "point"
at = [1.0, 1.0, 0.5]
component = "y"
[[probe]]
name = "reaction_x"
kind = "reaction"
boundary = "x0"
component = "x"
)";
}

testing::ProbeTable run_text(const std::string& text, const std::string& name) {
  const SceneSpec scene = load_scene_text(text, name + ".toml");
  testing::TempDir dir(name);
  const RunSummary summary = testing::make_fem_run<3>(scene, dir.path())->run();
  EXPECT_TRUE(summary.converged) << summary.failure;
  return testing::read_probes(dir.file("probes.csv"));
}

TEST(Solid3dLoads, UniformFaceTractionGivesTheExactUniaxialState) {
  for (const std::string element : {"p1", "tet10"}) {  // (p1p1_uphi is finite-strain only: see the compression test)
    const testing::ProbeTable p = run_text(box_scene(element, std::to_string(kS)), "uniaxial_" + element);
    const double ux = p.column("ux_end").back(), uy = p.column("uy_top").back(), r = p.column("reaction_x").back();
    std::printf("[loads 3d] %-6s u_x(L) = %.15f (exact %.15f), u_y(H) = %.15f (exact %.15f), reaction %.15f\n", element.c_str(), ux,
                kS * 2.0 / kE, uy, -kNu * kS / kE, r);
    EXPECT_NEAR(ux, kS * 2.0 / kE, 1e-12);
    EXPECT_NEAR(uy, -kNu * kS / kE, 1e-12);
    EXPECT_NEAR(r, -kS * 1.0, 1e-10);
  }
}

TEST(Solid3dLoads, LinearFaceTractionIsIntegratedExactly) {
  for (const std::string element : {"p1", "tet10"}) {
    const testing::ProbeTable p = run_text(box_scene(element, std::to_string(kS) + " * y"), "bending_" + element);
    EXPECT_NEAR(p.column("reaction_x").back(), -kS / 2.0, 1e-10) << element;
  }
}

TEST(Solid3dLoads, SelfWeightOfAGmshCubeClampedOnItsBottomGroup) {
  for (const auto& [element, file] : {std::pair<std::string, std::string>{"p1", "cube_tet4.msh"}, {"tet10", "cube_tet10.msh"},
                                             {"tet10", "cube_tet4.msh"}}) {
    const std::string text = R"(
[scene]
name = "cube-weight"
method = "fem"
dimension = 3
[time]
integrator = "static"
dt = 1.0
steps = 1
[solver]
residual_relative = 1e-12
[[material]]
name = "m"
model = "neo_hooke"
E = 1.0e4
nu = 0.3
density = 2.0
[[body]]
name = "cube"
material = "m"
element = ")" + element + R"("
mesh = { file = ")" + std::string(LOOM_SOURCE_DIR) + "/tests/meshes/" + file + R"(", group = "cube" }
[[boundary]]
name = "bottom"
region = { group = "bottom" }
displacement = { x = 0.0, y = 0.0, z = 0.0 }
[body_force]
z = -9.81
[[probe]]
name = "reaction_z"
kind = "reaction"
boundary = "bottom"
component = "z"
[[probe]]
name = "volume"
kind = "volume"
)";
    const testing::ProbeTable p = run_text(text, "cube_weight_" + element);
    std::printf("[loads 3d] %-6s %-14s reaction_z = %.12f (rho g V = %.12f)\n", element.c_str(), file.c_str(), p.column("reaction_z").back(),
                2.0 * 9.81);
    EXPECT_NEAR(p.column("reaction_z").back(), 2.0 * 9.81, 1e-9) << element << " " << file;
  }
}

}  // namespace
}  // namespace loom

namespace loom {
namespace {

// The 3D system solved by each back-end (CHOLMOD, UMFPACK, conjugate gradients at its default tolerance 1e-10):
// extruded Cook's membrane, tet10, linear, nu = 0.3 (at the scene's nu = 0.4999 Jacobi-preconditioned CG does not
// converge within 2n iterations and says so: the direct back-ends are the ones for nearly incompressible systems,
// docs/solvers_3d.md). The answers agree to the solver tolerance: 1e-7 relative asserted.
TEST(Solid3dLoads, BackEndsAgreeOnA3dSystem) {
  double reference = 0.0;
  for (const std::string linear : {"cholmod", "umfpack", "cg"}) {
    const SceneSpec scene = load_scene(std::string(LOOM_SOURCE_DIR) + "/scenes/cooks_membrane_3d.toml",
                                       {"output.every=0", "material[0].nu=0.3", "solver.linear=\"" + linear + "\""});
    testing::TempDir dir("backend_3d_" + linear);
    const RunSummary summary = testing::make_fem_run<3>(scene, dir.path())->run();
    ASSERT_TRUE(summary.converged) << linear << ": " << summary.failure;
    const double uy = testing::read_probes(dir.file("probes.csv")).column("uy_C").back();
    if (linear == "cholmod") reference = uy;
    std::printf("[loads 3d] back-end %-8s u_y(C) = %.12f (relative difference to CHOLMOD %.1e)\n", linear.c_str(), uy,
                std::abs(uy - reference) / std::abs(reference));
    EXPECT_NEAR(uy, reference, 1e-7 * std::abs(reference)) << linear;
  }
}

}  // namespace
}  // namespace loom
