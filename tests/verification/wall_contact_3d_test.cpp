// Rigid walls as planes in 3D (systems/assemble/wall_contact.hpp: the boundary faces' area vectors share the
// penalty; engine/store/walls.hpp), against the closed forms of the 2D tests (wall_contact_test.cpp):
//  - a linear elastic tet10 block with nu = 0 on a frictionless ground, held by rollers on x = 0 and y = 0: the exact
//    solution (sigma_zz = -rho g (H - z), u_z quadratic in z) is in tet10's span and its base is flat, so the contact
//    pressure is uniform and every base node sinks by p / k_N (a quadratic face's load goes to its mid-edge nodes,
//    A / 3 each, and so does its contact share); the wall carries the weight;
//  - a BCC block of linear tetrahedra on a stick ground carries rho g V to round-off and sinks below 1 % of a cell,
//    with the default penalty k_N = 100 E / h (h the mean edge of the surface triangles);
//  - a quarter of a block on the ground and two frictionless symmetry walls carries a quarter of the whole block's
//    weight, and its symmetry walls hold it (penetration below 1 % of a cell);
//  - the BCC block as a pfem body remeshed before every step rests on the ground: the weight at every step, and the mesh
//    kept once the block has settled.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "tests/support/test_support.hpp"

namespace loom {
namespace {

constexpr double kRho = 2000.0, kG = 9.81, kE = 1e5;

std::string header(const std::string& method, int steps) {
  return "[scene]\nname = \"wall-3d\"\nmethod = \"" + method + "\"\ndimension = 3\n"
         "[time]\nintegrator = \"static\"\ndt = 1.0\nsteps = " + std::to_string(steps) + "\n"
         "[solver]\nresidual_relative = 1e-12\n"
         "[[material]]\nname = \"m\"\nmodel = \"linear_elastic\"\nE = 1e5\nnu = 0.3\ndensity = 2000.0\n"
         "[body_force]\nz = -9.81\n[output]\nevery = 0\n";
}

std::string wall(const std::string& name, const std::string& point, const std::string& normal, const std::string& extra = "") {
  return "[[wall]]\nname = \"" + name + "\"\npoint = " + point + "\nnormal = " + normal + "\n" + extra +
         "[[probe]]\nname = \"" + name + "_x\"\nkind = \"wall_force\"\nwall = \"" + name + "\"\ncomponent = \"x\"\n"
         "[[probe]]\nname = \"" + name + "_y\"\nkind = \"wall_force\"\nwall = \"" + name + "\"\ncomponent = \"y\"\n"
         "[[probe]]\nname = \"" + name + "_z\"\nkind = \"wall_force\"\nwall = \"" + name + "\"\ncomponent = \"z\"\n"
         "[[probe]]\nname = \"" + name + "_gap\"\nkind = \"penetration\"\nwall = \"" + name + "\"\n";
}

std::string block(const std::string& element, const std::string& origin, const std::string& size, const std::string& divisions,
                  const std::string& lattice) {
  return "[[body]]\nname = \"block\"\nmaterial = \"m\"\nelement = \"" + element + "\"\n"
         "mesh = { generator = \"box\", origin = " + origin + ", size = " + size + ", divisions = " + divisions + ", lattice = \"" + lattice +
         "\" }\n";
}

TEST(WallContact3d, ElasticBlockOnAFrictionlessGroundSinksUniformlyByPOverK) {
  std::string text = header("fem", 1) + block("tet10", "[0.0, 0.0, 0.0]", "[0.2, 0.3, 0.1]", "[2, 3, 2]", "kuhn") +
                     wall("ground", "[0.0, 0.0, 0.0]", "[0.0, 0.0, 3.0]", "penalty = 1e9\n") +
                     "[[boundary]]\nname = \"x_roller\"\nregion = { box = [[0.0, 0.0, 0.0], [0.0, 0.3, 0.1]] }\ndisplacement = { x = 0.0 }\n"
                     "[[boundary]]\nname = \"y_roller\"\nregion = { box = [[0.0, 0.0, 0.0], [0.2, 0.0, 0.1]] }\ndisplacement = { y = 0.0 }\n";
  text.replace(text.find("nu = 0.3"), 8, "nu = 0.0");
  const SceneSpec scene = testing::scene_from_text(text);
  auto run = testing::make_fem_run<3>(scene);
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto& v = run->probe_values();
  const double weight = kRho * kG * 0.2 * 0.3 * 0.1, p = kRho * kG * 0.1, sink = p / 1e9;
  EXPECT_NEAR(v[2], weight, 1e-9 * weight);
  EXPECT_NEAR(v[0], 0.0, 1e-9 * weight);
  EXPECT_NEAR(v[1], 0.0, 1e-9 * weight);
  EXPECT_NEAR(v[3], sink, 1e-8 * sink);
  const Nodes<3>& nodes = run->nodes();
  double worst = 0.0;
  for (Index i = 0; i < nodes.size(); ++i)
    if (nodes.X[i].z() == 0.0) worst = std::max(worst, std::abs(nodes.u_n[i].z() + sink));
  EXPECT_LE(worst, 1e-8 * sink);
  std::printf("[wall 3d] tet10 block, nu = 0: wall force %.12g (weight %.12g), penetration %.6e (p / k_N %.6e), worst base node %.1e\n", v[2],
              weight, v[3], sink, worst);
}

TEST(WallContact3d, BccBlockOnAStickGroundCarriesItsWeight) {
  const SceneSpec scene = testing::scene_from_text(header("fem", 2) + block("p1", "[0.0, 0.0, 0.0]", "[0.2, 0.3, 0.1]", "[4, 6, 2]", "bcc") +
                                                   wall("ground", "[0.0, 0.0, 0.0]", "[0.0, 0.0, 1.0]", "slip = \"stick\"\n"));
  auto run = testing::make_fem_run<3>(scene);
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto& v = run->probe_values();
  const double weight = kRho * kG * 0.2 * 0.3 * 0.1, h = 0.05;
  EXPECT_NEAR(v[2], weight, 1e-10 * weight);
  EXPECT_NEAR(v[0], 0.0, 1e-10 * weight);
  EXPECT_NEAR(v[1], 0.0, 1e-10 * weight);
  EXPECT_GT(v[3], 0.0);
  EXPECT_LT(v[3], 0.01 * h);
  std::printf("[wall 3d] BCC block on a stick ground: wall force %.12g (weight %.12g), penetration %.2e of a cell\n", v[2], weight, v[3] / h);
}

TEST(WallContact3d, QuarterBlockOnSymmetryWallsCarriesAQuarterOfTheWeight) {
  const std::string ground = wall("ground", "[0.0, 0.0, 0.0]", "[0.0, 0.0, 1.0]", "slip = \"stick\"\n");
  const SceneSpec whole = testing::scene_from_text(header("fem", 1) +
                                                   block("p1", "[-0.2, -0.2, 0.0]", "[0.4, 0.4, 0.1]", "[8, 8, 2]", "bcc") + ground);
  const SceneSpec quarter = testing::scene_from_text(header("fem", 1) + block("p1", "[0.0, 0.0, 0.0]", "[0.2, 0.2, 0.1]", "[4, 4, 2]", "bcc") +
                                                     ground + wall("symmetry_x", "[0.0, 0.0, 0.0]", "[1.0, 0.0, 0.0]") +
                                                     wall("symmetry_y", "[0.0, 0.0, 0.0]", "[0.0, 1.0, 0.0]"));
  auto full_run = testing::make_fem_run<3>(whole), quarter_run = testing::make_fem_run<3>(quarter);
  ASSERT_TRUE(full_run->run().converged);
  const RunSummary summary = quarter_run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto& f = full_run->probe_values();
  const auto& q = quarter_run->probe_values();
  const double h = 0.05;
  EXPECT_NEAR(q[2], 0.25 * f[2], 1e-10 * f[2]);
  EXPECT_NEAR(q[2], kRho * kG * 0.2 * 0.2 * 0.1, 1e-10 * q[2]);
  // The symmetry walls push on the quarter along their normals only (frictionless), and hold it within 1 % of a cell.
  EXPECT_GT(q[4], 0.0);
  EXPECT_NEAR(q[5], 0.0, 1e-10 * q[2]);
  EXPECT_NEAR(q[6], 0.0, 1e-10 * q[2]);
  EXPECT_NEAR(q[8], 0.0, 1e-10 * q[2]);
  EXPECT_GT(q[9], 0.0);
  EXPECT_NEAR(q[10], 0.0, 1e-10 * q[2]);
  EXPECT_LT(q[7], 0.01 * h);
  EXPECT_LT(q[11], 0.01 * h);
  std::printf("[wall 3d] quarter block: ground %.12g = %.12g of the whole block's %.12g; symmetry walls push %.4g (x), %.4g (y), "
              "penetrations %.1e, %.1e of a cell\n",
              q[2], q[2] / f[2], f[2], q[4], q[9], q[7] / h, q[11] / h);
}

TEST(WallContact3d, PfemBlockRemeshedEveryStepRestsOnTheGround) {
  std::string text = header("pfem", 10) + block("p1p1_uphi", "[0.0, 0.0, 0.0]", "[0.2, 0.3, 0.1]", "[4, 6, 2]", "bcc") +
                     wall("ground", "[0.0, 0.0, 0.0]", "[0.0, 0.0, 1.0]", "slip = \"stick\"\n") +
                     "[[probe]]\nname = \"changed\"\nkind = \"remesh\"\nquantity = \"changed\"\n";
  text.replace(text.find("model = \"linear_elastic\""), 24, "model = \"neo_hooke\"");
  const SceneSpec scene = testing::scene_from_text(text);
  testing::TempDir dir("wall_pfem_3d");
  auto run = testing::make_fem_run<3>(scene, dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  const auto fz = probes.column("ground_z"), changed = probes.column("changed");
  const double weight = kRho * kG * 0.2 * 0.3 * 0.1;
  // The lattice's surface pyramids have two Delaunay cuts each (five cospherical points): the first deformation under
  // the weight decides some of them (observed: steps 2 and 3); once settled, the mesh is kept.
  for (std::size_t s = 1; s < fz.size(); ++s) {
    EXPECT_NEAR(fz[s], weight, 1e-10 * weight) << "step " << s;
    if (s > 3) {
      EXPECT_EQ(changed[s], 0.0) << "step " << s;
    }
  }
  std::printf("[wall 3d] pfem BCC block, %zu remeshes: wall force %.12g (weight %.12g)\n", fz.size() - 1, fz.back(), weight);
}

}  // namespace
}  // namespace loom
