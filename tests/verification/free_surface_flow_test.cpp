// Free-surface flows of the remeshed methods (inflow, surfaces that merge, long runs at rest), es_pfem with the
// constrained surface (engine/methods/pfem/inlet_flow, particle_set; systems/remesh):
//  - inflow into free space (no gravity, no wall): the block and the rows entering behind it move rigidly at the
//    inlet velocity v, so the area downstream of the section is A_0 + |v.n| L t exactly while the inlet runs
//    (0.02 m/s through 50 mm, 0.001 m^2/s) and stays A_0 + |v.n| L T after it closes; the mass likewise;
//  - a column falling onto a layer of the same body: the two surfaces merge (triangles added across the gap), and
//    no boundary edge crosses another at any step (the remesh's crossings probe reads the polygon of each step);
//  - a block resting on a stick ground, remeshed before each of 10^4 steps: once the elastic sag has settled, it
//    stays where it is (no creep), its mass and area unchanged;
//  - time.stop_when ends a run as completed once its probe has fallen below the bound (and writes the checkpoint
//    of that step if it is one of output.checkpoint_every's).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>

#include "tests/support/test_support.hpp"

namespace loom {
namespace {

const std::string kPaste =
    "[[material]]\nname = \"paste\"\nmodel = \"hencky_perzyna\"\nE = 1.0e5\nnu = 0.3\ntau0 = 50.0\nviscosity = 50.0\ndensity = 2300.0\n";

std::string inflow_scene() {
  return "[scene]\nname = \"inflow\"\nmethod = \"es_pfem\"\n"
         "[time]\nintegrator = \"bossak\"\ndt = 2e-3\nsteps = 1000\n"
         "[solver]\nresidual_relative = 1e-10\n" + kPaste +
         "[[body]]\nname = \"paste\"\nmaterial = \"paste\"\nelement = \"es_up\"\nalpha_stab = 200.0\n"
         "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [0.025, 0.05], divisions = [4, 8], pattern = \"alternating\" }\n"
         "[[inlet]]\nname = \"inlet\"\nfrom = [0.0, 0.0]\nto = [0.0, 0.05]\nvelocity = [0.02, 0.0]\nduration = 1.5\nspacing = 0.00625\n"
         "[remesh]\nsurface = \"constrained\"\nalpha = 1.3\n"
         "[[probe]]\nname = \"area\"\nkind = \"volume\"\ninlet = \"inlet\"\n"
         "[[probe]]\nname = \"mass\"\nkind = \"mass\"\ninlet = \"inlet\"\n"
         "[[probe]]\nname = \"inserted\"\nkind = \"remesh\"\nquantity = \"inserted\"\n"
         "[[probe]]\nname = \"crossings\"\nkind = \"remesh\"\nquantity = \"crossings\"\n"
         "[output]\nevery = 0\n";
}

TEST(Inflow, PoursTheFlowRateTimesTheTime) {
  testing::TempDir dir("inflow");
  auto run = testing::make_fem_run(testing::scene_from_text(inflow_scene()), dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  const auto t = probes.column("time"), area = probes.column("area"), mass = probes.column("mass"), inserted = probes.column("inserted"),
             crossings = probes.column("crossings");
  const double A0 = 0.025 * 0.05, Q = 0.02 * 0.05, T = 1.5, rho = 2300.0;
  double worst_pouring = 0.0, worst_after = 0.0, worst_mass = 0.0;
  int rows = 0;
  for (std::size_t k = 1; k < t.size(); ++k) {
    const double poured = A0 + Q * std::min(t[k], T);
    const double e = std::abs(area[k] - poured) / poured;
    (t[k] <= T ? worst_pouring : worst_after) = std::max(t[k] <= T ? worst_pouring : worst_after, e);
    worst_mass = std::max(worst_mass, std::abs(mass[k] / rho - poured) / poured);
    rows += inserted[k] > 0;
    EXPECT_EQ(inserted[k], inserted[k] > 0 ? 9.0 : 0.0);  // a row: 50 mm / 6.25 mm + 1
    EXPECT_EQ(crossings[k], 0.0);
  }
  // The first row enters one spacing behind the section and the last reaches it at T: 0.03 m / 6.25 mm rows.
  EXPECT_EQ(rows, int(std::lround(0.02 * T / 0.00625)));
  EXPECT_LT(worst_pouring, 5e-3);
  EXPECT_LT(worst_after, 1e-3);
  EXPECT_LT(worst_mass, 5e-3);
  std::printf("[inflow] %d rows; area downstream against A_0 + Q t: %.1e while pouring, %.1e after; mass %.1e\n", rows, worst_pouring,
              worst_after, worst_mass);
}

// Gmsh 2.2 ASCII: a layer [0, 0.2] x [0, 0.025] (32 x 4 squares of 6.25 mm) and a column [0.075, 0.125] x
// [0.06, 0.16] (8 x 16 squares) 35 mm above it, one physical surface.
std::string two_part_mesh() {
  std::vector<std::array<double, 2>> x;
  std::vector<std::array<int, 3>> t;
  auto block = [&](double x0, double y0, double h, int nx, int ny) {
    const int first = int(x.size());
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) x.push_back({x0 + h * i, y0 + h * j});
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int a = first + j * (nx + 1) + i + 1, b = a + 1, c = a + nx + 2, d = a + nx + 1;  // 1-based
        t.push_back({a, b, c});
        t.push_back({a, c, d});
      }
  };
  block(0.0, 0.0, 0.00625, 32, 4);
  block(0.075, 0.06, 0.00625, 8, 16);
  std::ostringstream os;
  os.precision(17);
  os << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 1 \"paste\"\n$EndPhysicalNames\n$Nodes\n" << x.size() << "\n";
  for (std::size_t i = 0; i < x.size(); ++i) os << i + 1 << " " << x[i][0] << " " << x[i][1] << " 0\n";
  os << "$EndNodes\n$Elements\n" << t.size() << "\n";
  for (std::size_t e = 0; e < t.size(); ++e) os << e + 1 << " 2 2 1 1 " << t[e][0] << " " << t[e][1] << " " << t[e][2] << "\n";
  os << "$EndElements\n";
  return os.str();
}

// A column of paste falling onto a layer of the same body (two parts of one mesh file, written into `dir`).
std::string merging_scene(const testing::TempDir& dir, const std::string& remesh_extra = "") {
  testing::write_text(dir.file("two_parts.msh"), two_part_mesh());
  return "[scene]\nname = \"merging\"\nmethod = \"es_pfem\"\n"
         "[time]\nintegrator = \"bossak\"\ndt = 1e-3\nsteps = 300\n"
         "[solver]\nresidual_relative = 1e-8\nmax_cutbacks = 6\n" + kPaste +
         "[[body]]\nname = \"paste\"\nmaterial = \"paste\"\nelement = \"es_up\"\nalpha_stab = 200.0\n"
         "mesh = { file = \"" + dir.file("two_parts.msh") + "\" }\n"
         "[body_force]\ny = -9.81\n"
         "[[wall]]\nname = \"ground\"\npoint = [0.0, 0.0]\nnormal = [0.0, 1.0]\nslip = \"stick\"\n"
         "[remesh]\nsurface = \"constrained\"\nalpha = 1.3\n" + remesh_extra +
         "[[probe]]\nname = \"top\"\nkind = \"extent\"\ncomponent = \"y\"\n"
         "[[probe]]\nname = \"mass\"\nkind = \"mass\"\n"
         "[[probe]]\nname = \"merged\"\nkind = \"remesh\"\nquantity = \"merged\"\n"
         "[[probe]]\nname = \"crossings\"\nkind = \"remesh\"\nquantity = \"crossings\"\n"
         "[[probe]]\nname = \"isolated\"\nkind = \"remesh\"\nquantity = \"isolated\"\n"
         "[output]\nevery = 0\n";
}

TEST(SurfaceMerging, AColumnFallingOntoALayerJoinsItWithoutCrossingSurfaces) {
  testing::TempDir dir("merging");
  const std::string text = merging_scene(dir);
  auto run = testing::make_fem_run(testing::scene_from_text(text), dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  const auto merged = probes.column("merged"), crossings = probes.column("crossings"), mass = probes.column("mass"),
             isolated = probes.column("isolated"), top = probes.column("top");
  double merges = 0.0, crossed = 0.0, jump = 0.0;
  for (std::size_t k = 1; k < merged.size(); ++k) {
    merges += merged[k], crossed += crossings[k];
    EXPECT_EQ(isolated[k], 0.0) << "step " << k;
    // Mass changes only where a gap became material.
    if (merged[k] == 0.0) jump = std::max(jump, std::abs(mass[k] - mass[k - 1]) / mass[0]);
  }
  EXPECT_GT(merges, 0.0) << "the column never joined the layer";
  EXPECT_EQ(crossed, 0.0) << "a boundary edge crossed another";
  EXPECT_LT(jump, 1e-12);
  // The gaps that closed (at most 0.9 h wide, under the column's 50 mm) and the voids trapped at the impact.
  EXPECT_LT(mass.back() / mass[0] - 1.0, 0.05);
  EXPECT_LT(top.back(), 0.16 - 0.035 - 0.02);  // it fell through the gap and sank into the layer
  std::printf("[merging] %g triangles added across gaps; mass %.4f -> %.4f kg/m (+%.2f %%)\n", merges, mass[0], mass.back(),
              100.0 * (mass.back() / mass[0] - 1.0));
}

// The same fall with remesh.max_new_material = 0.02: the merges add 3.6 % of the mass, so the run stops as failed once
// they pass 2 %, naming the key, with the probes written up to the last converged step.
TEST(SurfaceMerging, ARunThatGainsMoreMassThanAllowedFails) {
  testing::TempDir dir("merging_limit");
  auto run = testing::make_fem_run(testing::scene_from_text(merging_scene(dir, "max_new_material = 0.02\n")), dir.path());
  const RunSummary summary = run->run();
  ASSERT_FALSE(summary.converged);
  EXPECT_NE(summary.failure.find("remesh.max_new_material = 0.02"), std::string::npos) << summary.failure;
  const auto mass = testing::read_probes(dir.file("probes.csv")).column("mass");
  EXPECT_LT(mass.size(), 301u);
  EXPECT_LT(mass.back() / mass[0] - 1.0, 0.02 + 1e-12);  // the step whose remesh passed the limit is not written
}

// A block of paste (tau0 = 1000 Pa: rho g H = 1130 Pa at its base, shear stresses below the yield stress) resting on a
// stick ground, remeshed before every one of 10^4 steps: after the elastic sag (Bossak's damping settles it in a few
// hundred steps) nothing moves; the ground then carries the weight to 1e-8, and no particle sinks into it by 1 % of
// the spacing at any step.
TEST(RestingBodyOnWalls, StaysAtRestThroughTenThousandRemeshes) {
  const std::string text = "[scene]\nname = \"resting\"\nmethod = \"es_pfem\"\n"
                           "[time]\nintegrator = \"bossak\"\ndt = 5e-3\nsteps = 10000\n"
                           "[solver]\nresidual_relative = 1e-10\n"
                           "[[material]]\nname = \"paste\"\nmodel = \"hencky_perzyna\"\nE = 1.0e5\nnu = 0.3\ntau0 = 1000.0\nviscosity = 50.0\ndensity = 2300.0\n"
                           "[[body]]\nname = \"paste\"\nmaterial = \"paste\"\nelement = \"es_up\"\nalpha_stab = 200.0\n"
                           "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [0.1, 0.05], divisions = [8, 4], pattern = \"shifted\" }\n"
                           "[body_force]\ny = -9.81\n"
                           "[[wall]]\nname = \"ground\"\npoint = [0.0, 0.0]\nnormal = [0.0, 1.0]\nslip = \"stick\"\n"
                           "[remesh]\nsurface = \"constrained\"\nalpha = 1.3\n"
                           "[[probe]]\nname = \"top\"\nkind = \"extent\"\ncomponent = \"y\"\n"
                           "[[probe]]\nname = \"right\"\nkind = \"extent\"\ncomponent = \"x\"\n"
                           "[[probe]]\nname = \"speed\"\nkind = \"speed\"\n"
                           "[[probe]]\nname = \"mass\"\nkind = \"mass\"\n"
                           "[[probe]]\nname = \"area\"\nkind = \"volume\"\n"
                           "[[probe]]\nname = \"changed\"\nkind = \"remesh\"\nquantity = \"changed\"\n"
                           "[[probe]]\nname = \"Fy\"\nkind = \"wall_force\"\nwall = \"ground\"\ncomponent = \"y\"\n"
                           "[[probe]]\nname = \"gap\"\nkind = \"penetration\"\n"
                           "[[probe]]\nname = \"ymin\"\nkind = \"extent\"\ncomponent = \"y\"\nbound = \"min\"\n"
                           "[output]\nevery = 0\n";
  testing::TempDir dir("resting_walls");
  auto run = testing::make_fem_run(testing::scene_from_text(text), dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  ASSERT_EQ(summary.steps_done, 10000);
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  const auto top = probes.column("top"), right = probes.column("right"), speed = probes.column("speed"), mass = probes.column("mass"),
             area = probes.column("area"), changed = probes.column("changed"), Fy = probes.column("Fy"), gap = probes.column("gap"),
             ymin = probes.column("ymin");
  const std::size_t settled = 2000;
  double drift = 0.0, fastest = 0.0;
  int changes = 0;
  for (std::size_t k = settled; k < top.size(); ++k) {
    drift = std::max({drift, std::abs(top[k] - top[settled]), std::abs(right[k] - right[settled])});
    fastest = std::max(fastest, speed[k]);
    changes += changed[k] > 0;
  }
  EXPECT_LT(drift, 1e-9);      // 0.05 m block: a nanometre over 8000 steps and remeshes
  EXPECT_LT(fastest, 1e-9);
  EXPECT_EQ(changes, 0);
  EXPECT_EQ(mass.back(), mass[1]);
  EXPECT_NEAR(area.back(), area[settled], 1e-12 * area[settled]);
  // At rest the stick ground carries the weight (the mass probe is rho times the reference area); the default penalty
  // keeps every particle within 1 % of the spacing (12.5 mm) of it at every step (about p / k_N = 1.4 um at rest).
  EXPECT_NEAR(Fy.back(), 9.81 * mass.back(), 1e-8 * 9.81 * mass.back());
  EXPECT_LT(*std::max_element(gap.begin(), gap.end()), 0.01 * 0.0125);
  // Consistency of the two probes: the lowest particle is no deeper than the penetration reported.
  for (std::size_t k = 0; k < ymin.size(); ++k) EXPECT_LE(std::max(-ymin[k], 0.0), gap[k] + 1e-15) << "step " << k;
  std::printf("[resting on walls] sag %.3e m; after step %zu: largest move %.1e m, speed %.1e m/s, %d connectivity changes; "
              "wall force / weight - 1 = %.1e, largest penetration %.2e m\n",
              0.05 - top.back(), settled, drift, fastest, changes, Fy.back() / (9.81 * mass.back()) - 1.0,
              *std::max_element(gap.begin(), gap.end()));
}

TEST(StopWhen, EndsTheRunOnceTheProbeFallsBelowItsBound) {
  // The same block released slightly above the ground settles; the run asks for 2000 steps and stops when the
  // largest speed is below 1e-4 m/s. Frames every 1000 steps: the settled state is written as well.
  const std::string text = "[scene]\nname = \"settle\"\nmethod = \"es_pfem\"\n"
                           "[time]\nintegrator = \"bossak\"\ndt = 5e-3\nsteps = 2000\nstop_when = { probe = \"speed\", below = 1e-4, after = 0.1 }\n"
                           "[[material]]\nname = \"paste\"\nmodel = \"hencky_perzyna\"\nE = 1.0e5\nnu = 0.3\ntau0 = 1000.0\nviscosity = 50.0\ndensity = 2300.0\n"
                           "[[body]]\nname = \"paste\"\nmaterial = \"paste\"\nelement = \"es_up\"\nalpha_stab = 200.0\n"
                           "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [0.1, 0.05], divisions = [8, 4], pattern = \"shifted\" }\n"
                           "[body_force]\ny = -9.81\n"
                           "[[wall]]\nname = \"ground\"\npoint = [0.0, 0.0]\nnormal = [0.0, 1.0]\nslip = \"stick\"\n"
                           "[[probe]]\nname = \"speed\"\nkind = \"speed\"\n"
                           "[output]\nevery = 1000\n";
  testing::TempDir dir("stop_when");
  auto run = testing::make_fem_run(testing::scene_from_text(text), dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  EXPECT_TRUE(summary.completed);
  EXPECT_TRUE(summary.settled);
  EXPECT_LT(summary.steps_done, 2000);
  const auto speed = testing::read_probes(dir.file("probes.csv")).column("speed");
  ASSERT_EQ(speed.size(), std::size_t(summary.steps_done) + 1);
  EXPECT_LT(speed.back(), 1e-4);
  for (std::size_t k = 21; k + 1 < speed.size(); ++k) EXPECT_GE(speed[k], 1e-4) << "it should have stopped at step " << k;
  EXPECT_NEAR(summary.last_converged_time, summary.steps_done * 5e-3, 1e-12);
  char frame[32];
  std::snprintf(frame, sizeof frame, "settle_%06d.vtu", summary.steps_done);
  EXPECT_TRUE(std::filesystem::exists(dir.file(frame))) << frame << " (the settled state) was not written";

  // A run that settles on a step of its checkpoints writes that checkpoint too.
  testing::TempDir again("stop_when_checkpoint");
  auto checkpointed = testing::make_fem_run(
      testing::scene_from_text(text, {"output.checkpoint_every=" + std::to_string(summary.steps_done)}), again.path());
  const RunSummary second = checkpointed->run();
  ASSERT_TRUE(second.settled) << second.failure;
  EXPECT_EQ(second.steps_done, summary.steps_done);
  char checkpoint[48];
  std::snprintf(checkpoint, sizeof checkpoint, "checkpoint_%06d.loom", summary.steps_done);
  EXPECT_TRUE(std::filesystem::exists(again.file(checkpoint))) << checkpoint << " (the settled step's) was not written";
}

// The same with the top's rate of change: it stops once the top has moved by less than 1e-6 m/s * 0.5 s in the last
// 0.5 s, and not before 0.5 s of history.
TEST(StopWhen, EndsTheRunOnceTheProbeHasStoppedChanging) {
  const std::string text = "[scene]\nname = \"settle-rate\"\nmethod = \"es_pfem\"\n"
                           "[time]\nintegrator = \"bossak\"\ndt = 5e-3\nsteps = 2000\nstop_when = { probe = \"top\", rate_below = 1e-6, over = 0.5 }\n"
                           "[[material]]\nname = \"paste\"\nmodel = \"hencky_perzyna\"\nE = 1.0e5\nnu = 0.3\ntau0 = 1000.0\nviscosity = 50.0\ndensity = 2300.0\n"
                           "[[body]]\nname = \"paste\"\nmaterial = \"paste\"\nelement = \"es_up\"\nalpha_stab = 200.0\n"
                           "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [0.1, 0.05], divisions = [8, 4], pattern = \"shifted\" }\n"
                           "[body_force]\ny = -9.81\n"
                           "[[wall]]\nname = \"ground\"\npoint = [0.0, 0.0]\nnormal = [0.0, 1.0]\nslip = \"stick\"\n"
                           "[[probe]]\nname = \"top\"\nkind = \"extent\"\ncomponent = \"y\"\n"
                           "[output]\nevery = 0\n";
  testing::TempDir dir("stop_rate");
  auto run = testing::make_fem_run(testing::scene_from_text(text), dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  EXPECT_TRUE(summary.settled);
  EXPECT_LT(summary.steps_done, 2000);
  const auto top = testing::read_probes(dir.file("probes.csv")).column("top");
  const std::size_t n = top.size() - 1, window = 100;  // 0.5 s of 5 ms steps
  ASSERT_GE(n, window);
  EXPECT_LT(std::abs(top[n] - top[n - window]), 1e-6 * 0.5);
  for (std::size_t k = window; k < n; ++k) EXPECT_GE(std::abs(top[k] - top[k - window]), 1e-6 * 0.5) << "it should have stopped at step " << k;
}

}  // namespace
}  // namespace loom
