// Inflow through a disc in 3D (engine/methods/pfem/inlet_flow_3d.hpp) and the probes that measure it (systems/output/
// tet_sections.hpp):
//  - a tetrahedron cut by a plane: the part above it and the area of the cut against closed forms, for a lone corner
//    and for two corners on each side; the cuts of a BCC box tile its cross-section;
//  - a block of paste moving at the inflow velocity v in free space (no gravity, no wall), fed through the disc over its
//    top face: the block and the layers behind it move rigidly, so the volume downstream of the disc is V_0 + |v| A t
//    while the inlet runs (A the top face) and V_0 + |v| A T after it closes, and so is the mass over the density; the
//    layers are round(|v| T / h), each a copy of the top face's particles;
//  - the same with the disc moving along x at w (a nozzle): the block and the layers move at v + w, the volume
//    downstream of the moving disc grows as before, and no particle is left behind (the body's extent along x is the
//    block's moved by w t at every step).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>

#include "engine/mesh/tet_generators.hpp"
#include "systems/output/tet_sections.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

TEST(TetSections, LoneCornerAndTwoByTwoCutsMatchClosedForms) {
  const std::array<Vec3, 4> unit = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  // z >= 1/2: the corner tetrahedron scaled by 1/2 (1/8 of the volume); the cut, a right triangle of legs 1/2.
  EXPECT_NEAR(tet_fraction_downstream(unit, Vec3(0, 0, 0.5), Vec3(0, 0, 1)), 0.125, 1e-15);
  EXPECT_NEAR(tet_fraction_downstream(unit, Vec3(0, 0, 0.5), Vec3(0, 0, -1)), 0.875, 1e-15);
  EXPECT_NEAR(cut_tet(unit, Vec3(0, 0, 0.5), Vec3(0, 0, 1)).area(), 0.125, 1e-15);
  // x + y >= 1/2 (two corners each side): the volume below is the integral of (1 - u) u over u in [0, 1/2], 1/12, half
  // the tetrahedron's; the cut, a rectangle of sqrt(2) / 2 by 1/2.
  const Vec3 n = Vec3(1, 1, 0).normalized();
  EXPECT_NEAR(tet_fraction_downstream(unit, Vec3(0.25, 0.25, 0), n), 0.5, 1e-15);
  EXPECT_NEAR(cut_tet(unit, Vec3(0.25, 0.25, 0), n).area(), 0.5 * std::sqrt(0.5), 1e-15);
  // x + y >= 1/4: 1 - 6 (s^2 / 2 - s^3 / 3) at s = 1/4.
  EXPECT_NEAR(tet_fraction_downstream(unit, Vec3(0.125, 0.125, 0), n), 1.0 - 6.0 * (0.25 * 0.25 / 2.0 - 0.25 * 0.25 * 0.25 / 3.0), 1e-15);
  // Both sides add up to the whole, for a skewed tetrahedron and a skew plane.
  const std::array<Vec3, 4> skew = {Vec3(0.1, -0.2, 0.3), Vec3(1.3, 0.1, -0.2), Vec3(0.2, 1.1, 0.4), Vec3(-0.3, 0.4, 1.2)};
  const Vec3 m = Vec3(0.3, -0.7, 0.5).normalized();
  for (double s : {-0.4, -0.1, 0.0, 0.2, 0.5})
    EXPECT_NEAR(tet_fraction_downstream(skew, s * m, m) + tet_fraction_downstream(skew, s * m, -m), 1.0, 1e-14) << s;
}

TEST(TetSections, CutsOfABoxTileItsCrossSection) {
  BoxSpec box;
  box.origin = Vec3(0, 0, 0), box.size = Vec3(0.3, 0.2, 0.1), box.nx = 3, box.ny = 2, box.nz = 2;
  const TetMeshData mesh = generate_bcc_box(box);
  // (point, normal, area of the cut, volume on the side the normal points to)
  for (const auto& [point, normal, area_expected, volume_expected] :
       {std::tuple{Vec3(0.1234, 0, 0), Vec3(1, 0, 0), 0.2 * 0.1, (0.3 - 0.1234) * 0.2 * 0.1},
        std::tuple{Vec3(0, 0.1, 0), Vec3(0, 1, 0), 0.3 * 0.1, 0.3 * 0.1 * 0.1},  // through lattice points
        std::tuple{Vec3(0, 0, 0.05), Vec3(0, 0, -1), 0.3 * 0.2, 0.3 * 0.2 * 0.05}}) {
    double area = 0.0, volume = 0.0;
    for (std::size_t t = 0; t + 3 < mesh.tets.size(); t += 4) {
      const std::array<Vec3, 4> x = {mesh.X[std::size_t(mesh.tets[t])], mesh.X[std::size_t(mesh.tets[t + 1])], mesh.X[std::size_t(mesh.tets[t + 2])],
                                     mesh.X[std::size_t(mesh.tets[t + 3])]};
      area += cut_tet(x, point, normal).area();
      volume += tet_fraction_downstream(x, point, normal) * std::abs(tet_volume(x[0], x[1], x[2], x[3]));
    }
    EXPECT_NEAR(area, area_expected, 1e-14);
    EXPECT_NEAR(volume, volume_expected, 1e-15);
  }
}

const std::string kPaste =
    "[[material]]\nname = \"paste\"\nmodel = \"hencky_perzyna\"\nE = 1.0e5\nnu = 0.3\ntau0 = 50.0\nviscosity = 50.0\ndensity = 2300.0\n";

// A 40 mm cube of paste (BCC lattice of 20 mm cubes) moving at v + w, fed at v through a disc over its top face that
// moves at w; h = 5 mm layers for 1 s at |v| = 20 mm/s.
std::string inflow_scene(const std::string& section_velocity) {
  return "[scene]\nname = \"inflow-3d\"\nmethod = \"es_pfem\"\ndimension = 3\n"
         "[time]\nintegrator = \"bossak\"\ndt = 0.01\nsteps = 120\n"
         "[solver]\nresidual_relative = 1e-10\n" + kPaste +
         "[[body]]\nname = \"paste\"\nmaterial = \"paste\"\nelement = \"es_up\"\nalpha_stab = 20.0\nj_projection = true\n"
         "mesh = { generator = \"box\", origin = [0.0, 0.0, 0.0], size = [0.04, 0.04, 0.04], divisions = [2, 2, 2], lattice = \"bcc\" }\n"
         "initial_velocity = { x = \"" + section_velocity + "\", y = \"0\", z = \"-0.02\" }\n"
         "[[inlet]]\nname = \"nozzle\"\ncentre = [0.02, 0.02, 0.04]\nradius = 0.03\nvelocity = [0.0, 0.0, -0.02]\n"
         "section_velocity = [" + section_velocity + ", 0.0, 0.0]\nduration = 1.0\nspacing = 0.005\n"
         "[[probe]]\nname = \"volume\"\nkind = \"volume\"\ninlet = \"nozzle\"\n"
         "[[probe]]\nname = \"mass\"\nkind = \"mass\"\ninlet = \"nozzle\"\n"
         "[[probe]]\nname = \"inserted\"\nkind = \"remesh\"\nquantity = \"inserted\"\n"
         "[[probe]]\nname = \"x_min\"\nkind = \"extent\"\ncomponent = \"x\"\nbound = \"min\"\n"
         "[[probe]]\nname = \"x_max\"\nkind = \"extent\"\ncomponent = \"x\"\n"
         "[output]\nevery = 0\n";
}

void expect_rigid_pour(double w) {
  testing::TempDir dir("inflow_3d");
  auto run = testing::make_fem_run<3>(testing::scene_from_text(inflow_scene(std::to_string(w))), dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  const auto t = probes.column("time"), volume = probes.column("volume"), mass = probes.column("mass"), inserted = probes.column("inserted"),
             x_min = probes.column("x_min"), x_max = probes.column("x_max");
  const double V0 = 0.04 * 0.04 * 0.04, Q = 0.02 * 0.04 * 0.04, T = 1.0, rho = 2300.0;
  double worst_volume = 0.0, worst_mass = 0.0, worst_x = 0.0;
  int layers = 0;
  for (std::size_t k = 1; k < t.size(); ++k) {
    const double poured = V0 + Q * std::min(t[k], T);
    worst_volume = std::max(worst_volume, std::abs(volume[k] - poured) / poured);
    worst_mass = std::max(worst_mass, std::abs(mass[k] / rho - poured) / poured);
    worst_x = std::max({worst_x, std::abs(x_min[k] - w * t[k]), std::abs(x_max[k] - 0.04 - w * t[k])});
    layers += inserted[k] > 0;
    EXPECT_EQ(inserted[k], inserted[k] > 0 ? 9.0 : 0.0) << t[k];  // a layer: the 3 x 3 particles of the top face
  }
  std::printf("[inflow 3D, w = %g] %d layers; max relative error of the poured volume %.1e, of the mass %.1e; particles off the rigid "
              "motion along x by %.1e m\n", w, layers, worst_volume, worst_mass, worst_x);
  EXPECT_EQ(layers, int(std::lround(0.02 * T / 0.005)));
  EXPECT_LT(worst_volume, 1e-9);
  EXPECT_LT(worst_mass, 1e-9);
  EXPECT_LT(worst_x, 1e-9);
}

TEST(Inflow3d, PoursTheFlowRateTimesTheTime) { expect_rigid_pour(0.0); }

TEST(Inflow3d, AMovingDiscLeavesNoParticleBehind) { expect_rigid_pour(0.01); }

}  // namespace
}  // namespace loom
