// Method pfem on tetrahedra (engine/methods/pfem/pfem_remesh_3d.cpp; spec 3d-free-surface §9, stages 1 and 2).
//  - A body at rest is not remeshed (its mesh is still Delaunay): a BCC block on rollers under its weight (E = 1e8 Pa:
//    strains of 4e-5, below the keep rule's margin of 1e-3; at E = 1e5 Pa, 4 % strain, it is remeshed), remeshed
//    before each of 1000 Bossak steps, computes what method fem computes on the same mesh, bit for bit.
//  - A homogeneous finite deformation through 50 remeshes that change the connectivity: the block of
//    homogeneous_compression_3d.toml compressed to half its height stays on the closed form at every step for every
//    element (p1, tet10, p1p1_uphi) and every transfer (CPM, BTM-ISO0/1/2): F_n is the same at every quadrature
//    point, so any transfer carries it exactly; tet10 mid-nodes re-created on the straight edges carry the affine
//    field exactly; the nodal phi of p1p1_uphi is the constant J.
//  - The extruded constrained block (scenes/constrained_block_pfem_3d.toml, stage 3) pressed 100 times more slowly:
//    the remesh keeps the mesh in all 40 steps and pfem computes what fem computes on it, bit for bit. (At the
//    scene's rate the first change comes at step 2: docs/pfem_3d.md §4.)
//  - The result does not depend on the thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "tests/support/test_support.hpp"
#include "tests/verification/homogeneous_compression_exact.hpp"
#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

std::string resting_block(const std::string& method) {
  return "[scene]\nname = \"resting-block\"\nmethod = \"" + method + "\"\ndimension = 3\n"
         "[time]\nintegrator = \"bossak\"\ndt = 0.002\nsteps = 1000\n"
         "[solver]\nresidual_relative = 1e-10\n"
         "[[material]]\nname = \"m\"\nmodel = \"neo_hooke\"\nE = 1.0e8\nnu = 0.45\ndensity = 1000.0\n"
         "[[body]]\nname = \"block\"\nmaterial = \"m\"\nelement = \"p1p1_uphi\"\n"
         "mesh = { generator = \"box\", size = [0.4, 0.4, 0.4], divisions = [4, 4, 4], lattice = \"bcc\" }\n"
         "body_force = { z = -9.81 }\n"
         "[[boundary]]\nname = \"bottom\"\nregion = { box = [[0.0, 0.0, 0.0], [0.4, 0.4, 0.0]] }\ndisplacement = { z = 0.0 }\n"
         "[[boundary]]\nname = \"left\"\nregion = { box = [[0.0, 0.0, 0.0], [0.0, 0.4, 0.4]] }\ndisplacement = { x = 0.0 }\n"
         "[[boundary]]\nname = \"back\"\nregion = { box = [[0.0, 0.0, 0.0], [0.4, 0.0, 0.4]] }\ndisplacement = { y = 0.0 }\n"
         "[[probe]]\nname = \"uz_top\"\nkind = \"point\"\nat = [0.4, 0.4, 0.4]\ncomponent = \"z\"\n"
         "[[probe]]\nname = \"ux_top\"\nkind = \"point\"\nat = [0.4, 0.4, 0.4]\ncomponent = \"x\"\n"
         "[[probe]]\nname = \"reaction\"\nkind = \"reaction\"\nboundary = \"bottom\"\ncomponent = \"z\"\n"
         "[[probe]]\nname = \"newton\"\nkind = \"newton\"\n" +
         (method == "pfem" ? "[[probe]]\nname = \"changed\"\nkind = \"remesh\"\nquantity = \"changed\"\n" : "") + "[output]\nevery = 0\n";
}

TEST(Pfem3d, ABodyAtRestIsNotRemeshedAndComputesWhatFemDoes) {
  const auto pfem = testing::run_for_probes(testing::scene_from_text(resting_block("pfem")), "pfem_3d_resting");
  const auto fem = testing::run_for_probes(testing::scene_from_text(resting_block("fem")), "pfem_3d_resting_fem");
  ASSERT_EQ(pfem.rows.size(), 1001u);
  ASSERT_EQ(fem.rows.size(), 1001u);
  const auto changed = pfem.column("changed");
  EXPECT_EQ(std::count(changed.begin(), changed.end(), 1.0), 0);
  for (const char* name : {"uz_top", "ux_top", "reaction", "newton"}) EXPECT_EQ(pfem.column(name), fem.column(name)) << name;
  const auto uz = pfem.column("uz_top");
  EXPECT_LT(*std::min_element(uz.begin(), uz.end()), 0.0);  // the block does sag and bounce
  std::printf("[pfem 3d] resting BCC block, 1000 remeshes: 0 connectivity changes, probes equal to fem's bit for bit (u_z(top) %.4g m)\n",
              uz.back());
}

constexpr double kE = 10.0, kNu = 0.3, kW = 2.0, kH = 1.0, kT = 1.0, kDepth = 0.5;
constexpr int kSteps = 50;

std::string compression_text() {
  std::string text = testing::read_text(verification::scene_path("homogeneous_compression_3d.toml"));
  text +=
      "\n[remesh]\nalpha = 100.0\nlchar = 1.0\n"
      "\n[map]\nscheme = \"cpm\"\n"
      "\n[[probe]]\nname = \"changed\"\nkind = \"remesh\"\nquantity = \"changed\"\n"
      "\n[[probe]]\nname = \"volume_change\"\nkind = \"remesh\"\nquantity = \"area_change\"\n"
      "\n[[probe]]\nname = \"volume\"\nkind = \"volume\"\n";
  return text;
}

std::vector<std::string> compression_sets(const std::string& element, const std::string& scheme, int iso) {
  return {"scene.method=pfem", "output.every=0", "body[0].element=" + element, "body[0].mesh.divisions=[8,4,4]",
          "time.steps=" + std::to_string(kSteps), "time.dt=" + std::to_string(1.0 / kSteps), "boundary[top].displacement.y=\"-0.5 * t\"",
          "map.scheme=" + scheme, "map.iso=" + std::to_string(iso)};
}

void check_compression(const std::string& element, const std::string& scheme, int iso) {
  const std::string name = element + " " + scheme + (scheme == "btm" ? "-iso" + std::to_string(iso) : "");
  SCOPED_TRACE(name);
  const SceneSpec scene = testing::scene_from_text(compression_text(), compression_sets(element, scheme, iso));
  ASSERT_EQ(scene.scene.method, Method::pfem);
  testing::TempDir dir("pfem_3d_homogeneous_" + element + "_" + scheme + std::to_string(iso));
  auto run = testing::make_fem_run<3>(scene, dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  ASSERT_EQ(probes.rows.size(), std::size_t(kSteps) + 1);
  const auto time = probes.column("time"), reaction = probes.column("reaction_top_y"), ux = probes.column("ux_right");
  const auto changed = probes.column("changed"), volume = probes.column("volume"), volume_change = probes.column("volume_change");
  int n_changed = 0;
  double worst = 0.0;
  for (int n = 1; n <= kSteps; ++n) {
    const auto k = std::size_t(n);
    const auto s = verification::homogeneous_compression_3d_exact(kE, kNu, kW, kH, kT, kDepth * kH * time[k]);
    const double er = verification::relative_error(reaction[k], s.reaction), eu = verification::relative_error(ux[k], s.ux_right);
    EXPECT_LE(er, 1e-8) << "step " << n;
    EXPECT_LE(eu, 1e-8) << "step " << n;
    EXPECT_LE(std::abs(volume_change[k]), 1e-12) << "step " << n;
    EXPECT_NEAR(volume[k], s.l * s.l2 * s.l * kW * kH * kT, 1e-10) << "step " << n;
    n_changed += changed[k] == 1.0;
    worst = std::max({worst, er, eu});
  }
  EXPECT_GE(n_changed, kSteps / 3);
  const MapStats& map = run->last_remesh().map;
  if (scheme == "cpm") {
    EXPECT_EQ(map.interpolated, 0);
  }
  // The whole final state: every node's displacement, every point's F_n, the nodal phi.
  const auto last = verification::homogeneous_compression_3d_exact(kE, kNu, kW, kH, kT, kDepth * kH);
  double max_u = 0.0, max_F = 0.0, max_phi = 0.0;
  for (Index i = 0; i < run->nodes().size(); ++i) {
    const Vec3 X = run->nodes().X[i];
    max_u = std::max(max_u, (run->nodes().u_n[i] - Vec3((last.l - 1.0) * X.x(), (last.l2 - 1.0) * X.y(), (last.l - 1.0) * X.z())).norm());
    if (run->nodes().phi_n.used()) max_phi = std::max(max_phi, std::abs(run->nodes().phi_n[i] - last.l * last.l2 * last.l));
  }
  const Mat3 F_exact = Vec3(last.l, last.l2, last.l).asDiagonal();
  for (const auto& q : run->quad_points())
    for (Index p = 0; p < q.size(); ++p) max_F = std::max(max_F, (q.F_n[p] - F_exact).cwiseAbs().maxCoeff());
  EXPECT_LE(max_u, 1e-10);
  EXPECT_LE(max_F, 1e-10);
  EXPECT_LE(max_phi, 1e-10);
  std::printf("[pfem 3d homogeneous] %-9s %-8s: %d of %d steps changed the connectivity (last remesh: %d kept, %d copied, %d interpolated, "
              "%d fallback points); worst relative error %.1e; final |u - u_exact| %.1e, |F_n - F| %.1e, |phi - J| %.1e\n",
              element.c_str(), (scheme + (scheme == "btm" ? "-iso" + std::to_string(iso) : "")).c_str(), n_changed, kSteps, int(map.kept),
              int(map.copied), int(map.interpolated), int(map.fallback), worst, max_u, max_F, max_phi);
}

class Pfem3dHomogeneous : public ::testing::TestWithParam<const char*> {};

TEST_P(Pfem3dHomogeneous, StaysExactThrough50RemeshesWithCpm) { check_compression(GetParam(), "cpm", 0); }
TEST_P(Pfem3dHomogeneous, StaysExactThrough50RemeshesWithBtmIso0) { check_compression(GetParam(), "btm", 0); }
TEST_P(Pfem3dHomogeneous, StaysExactThrough50RemeshesWithBtmIso1) { check_compression(GetParam(), "btm", 1); }
TEST_P(Pfem3dHomogeneous, StaysExactThrough50RemeshesWithBtmIso2) { check_compression(GetParam(), "btm", 2); }

INSTANTIATE_TEST_SUITE_P(Elements, Pfem3dHomogeneous, ::testing::Values("p1", "tet10", "p1p1_uphi"));

std::string erase_between(std::string text, const std::string& from, const std::string& to) {
  const auto a = text.find(from), b = text.find(to, a);
  if (a == std::string::npos || b == std::string::npos) ADD_FAILURE() << "the scene has no '" << from << "' before '" << to << "'";
  else text.erase(a, b - a);
  return text;
}

TEST(Pfem3d, TheExtrudedConstrainedBlockPressedSlowlyKeepsItsMeshAndIsFem) {
  const std::string pfem_text = testing::read_text(verification::scene_path("constrained_block_pfem_3d.toml"));
  std::string fem_text = erase_between(pfem_text, "[remesh]", "[[probe]]\nname = \"reaction\"");
  fem_text = erase_between(fem_text, "[[probe]]\nname = \"changed\"", "[[probe]]\nname = \"newton\"");
  fem_text.replace(fem_text.find("method = \"pfem\""), 15, "method = \"fem\"");
  // Observed at 1e-4 mm per step: the first change at step 9 (the extruded prisms are cospherical and the keep rule's
  // margin is 0.1 % of R^2, reached at about 1e-3 of strain).
  const std::vector<std::string> sets = {"time.steps=40", "output.every=0", "boundary[indenter].displacement.y=\"-0.00001 * t\""};
  const auto pfem = testing::run_for_probes(testing::scene_from_text(pfem_text, sets), "pfem_3d_block");
  const auto fem = testing::run_for_probes(testing::scene_from_text(fem_text, sets), "pfem_3d_block_fem");
  ASSERT_EQ(pfem.rows.size(), 41u);
  ASSERT_EQ(fem.rows.size(), 41u);
  const auto changed = pfem.column("changed");
  EXPECT_EQ(std::count(changed.begin(), changed.end(), 1.0), 0);
  for (const char* name : {"reaction", "top_right", "newton"}) EXPECT_EQ(pfem.column(name), fem.column(name)) << name;
  EXPECT_LT(pfem.column("reaction").back(), 0.0);  // the indenter does press
  std::printf("[pfem 3d] extruded constrained block at 1e-5 mm per step: 40 remeshes, no change, pfem = fem bit for bit "
              "(reaction %.6g N per 0.25 mm)\n", pfem.column("reaction").back());
}

// The shipped scene (200 steps at 1e-3 mm, remesh.repair = true) against 3D fem on the same mesh: the repair flips
// where the prisms' cut stops being Delaunay instead of triangulating the block again, so fewer steps change the
// connectivity and the reaction stays closer to fem's than without it (measured: 68 against 196 changes; 6.461 and
// 6.310 N per mm against fem's 6.602; the spec's stage 3 asks for none and fem bit for bit, which this mesh's
// cospherical prisms do not allow: docs/pfem_3d.md §4).
TEST(Pfem3d, TheRepairKeepsTheExtrudedConstrainedBlockCloserToFem) {
  const std::string pfem_text = testing::read_text(verification::scene_path("constrained_block_pfem_3d.toml"));
  std::string fem_text = erase_between(pfem_text, "[remesh]", "[[probe]]\nname = \"reaction\"");
  fem_text = erase_between(fem_text, "[[probe]]\nname = \"changed\"", "[[probe]]\nname = \"newton\"");
  fem_text.replace(fem_text.find("method = \"pfem\""), 15, "method = \"fem\"");
  const std::vector<std::string> sets = {"output.every=0"};
  std::vector<std::string> off = sets;
  off.push_back("remesh.repair=false");
  const auto fem = testing::run_for_probes(testing::scene_from_text(fem_text, sets), "pfem_3d_repair_fem");
  const auto repaired = testing::run_for_probes(testing::scene_from_text(pfem_text, sets), "pfem_3d_repair_on");
  const auto triangulated = testing::run_for_probes(testing::scene_from_text(pfem_text, off), "pfem_3d_repair_off");
  ASSERT_EQ(repaired.rows.size(), 201u);
  ASSERT_EQ(triangulated.rows.size(), 201u);
  ASSERT_EQ(fem.rows.size(), 201u);
  const auto count = [](const std::vector<double>& v) { return std::count_if(v.begin(), v.end(), [](double c) { return c > 0.0; }); };
  const auto changes_on = count(repaired.column("changed")), changes_off = count(triangulated.column("changed"));
  const auto repairs = count(repaired.column("repaired"));
  const double r_fem = fem.column("reaction").back(), r_on = repaired.column("reaction").back(), r_off = triangulated.column("reaction").back();
  const double err_on = std::abs(r_on / r_fem - 1.0), err_off = std::abs(r_off / r_fem - 1.0);
  std::printf("[pfem 3d] extruded constrained block, 200 steps: with the repair %ld changes (%ld by repair flips), reaction %.4f N per mm "
              "(%.2f %% from fem's %.4f); without %ld changes, %.4f N (%.2f %%)\n", long(changes_on), long(repairs), -4.0 * r_on,
              100.0 * err_on, -4.0 * r_fem, long(changes_off), -4.0 * r_off, 100.0 * err_off);
  EXPECT_GT(repairs, 0);
  EXPECT_LT(2 * changes_on, changes_off);
  EXPECT_LT(err_on, err_off);
  EXPECT_LT(err_on, 0.03);
  // Every change of the repaired run keeps the block's volume: flips do not move the surface.
  for (double dv : repaired.column("volume_change")) EXPECT_LT(std::abs(dv), 1e-12);
}

TEST(Pfem3d, TheResultDoesNotDependOnTheThreadCount) {
  const std::vector<std::string> sets = compression_sets("tet10", "btm", 2);
  testing::TempDir dir("pfem_3d_threads");
  const std::string scene = dir.file("scene.toml");
  testing::write_text(scene, compression_text());
  std::string last_frame[2], probes[2];
  for (int threads : {1, 2}) {
    std::vector<std::string> a = {"run", scene, "--quiet", "--threads", std::to_string(threads), "--out", dir.file(std::to_string(threads))};
    for (const auto& s : sets) a.push_back("--set"), a.push_back(s == "output.every=0" ? "output.every=50" : s);
    const auto c = testing::run_loom(a);
    ASSERT_EQ(c.exit_code, 0) << c.err;
    probes[threads - 1] = testing::read_text(dir.file(std::to_string(threads)) + "/probes.csv");
    last_frame[threads - 1] = testing::read_text(dir.file(std::to_string(threads)) + "/homogeneous-compression-3d_000050.vtu");
  }
  EXPECT_EQ(probes[0], probes[1]);
  EXPECT_EQ(last_frame[0], last_frame[1]);
  EXPECT_FALSE(last_frame[0].empty());
}

}  // namespace
}  // namespace loom
