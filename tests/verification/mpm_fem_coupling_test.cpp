// Method mpm_fem (seed 004 §4): particle-Newmark MPM on a quad9 grid coupled monolithically to an FEM plate whose
// quad9 cells share the grid's nodes (engine/mesh/coupled_grid, systems/update/coupled_fem).
//  - the coupled mesh: the plate's nodes on the grid's side are the grid's (one interface row), the rest new;
//  - the reset field (eq 8) carries a rigid motion of the FEM nodes (small rotation and translation, the linear
//    fields with no symmetric gradient) over the whole grid exactly: they are its zero-energy fields, and quad9
//    cells hold them (a linear field with a symmetric gradient would not be one: the free sides' natural condition
//    (grad u + grad u^T) n = 0 bends it);
//  - a disk and the plate falling together under gravity, nothing held: the plate's nodes, the grid that moves
//    with it and every particle follow Newmark's closed form, u_n = g t_n^2 / 2 from the equilibrium start (the
//    default), and with a_0 = 0 (spec seed004 §3, check 1)
//      u_n = g (t_n^2 / 2 - dt t_n / 2 + beta dt^2),  v_n = g (t_n - dt / 2)   (n >= 1),
//    to round-off, with F = I: the FEM cells' consistent mass, their body force and the shared nodes carry a
//    translation exactly;
//  - a disk rolling on a plate a thousand times stiffer than itself rolls as on the rigid ground of method mpm
//    (the same grid, particles and contact terms): the coupling adds only the plate's compliance;
//  - a block of particles resting on the plate: the plate's clamp carries its weight;
//  - the patch test across the interface: a homogeneous deformation is reproduced exactly;
// and two things the coupled scenes brought with them: time.adaptive_dt (each step the formula at the probe's last
// value, the run ending at time.end; a restarted coupled run equal to the straight one) and method mpm with several
// bodies (two disks, each under its own force).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/methods/model/mpm_model.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

constexpr double kG = -9.81, kDt = 0.02, kBeta = 0.3;
constexpr int kSteps = 25;

// A disk in a 3 x 3 quad9 grid refined twice, a plate of 3 x 1 coarse cells under it.
// With unit_inertia_plate the plate's inertia has density 1 (inertia = "unit_density") and its body force is
// g / rho: rho b / 1 = g, so that it still falls with the disk.
std::string falling_scene(bool gravity_on_plate, bool unit_inertia_plate = false) {
  return std::string("[scene]\nname = \"coupled-fall\"\nmethod = \"mpm_fem\"\n"
                     "[time]\nintegrator = \"newmark\"\ndt = 0.02\nsteps = 25\nbeta = 0.3\ngamma = 0.5\n"
                     "[solver]\nresidual_relative = 1e-12\n"
                     "[mpm]\nsoft_stiffness = { c1 = 0.1, c2 = 0.01 }\n"
                     "[[material]]\nname = \"m\"\nmodel = \"neo_hooke\"\nE = 4.2e6\nnu = 0.4\ndensity = 1000.0\n"
                     "[[material]]\nname = \"p\"\nmodel = \"neo_hooke\"\nE = 8.4e6\nnu = 0.4\ndensity = 1000.0\n"
                     "[[body]]\nname = \"disk\"\nmaterial = \"m\"\n"
                     "particles = { generator = \"disk\", centre = [0.5, -0.2], radius = 0.5, core_radius = 0.4, n_theta = 40, factor = 1.3 }\n"
                     "body_force = { y = -9.81 }\n"
                     "[[body]]\nname = \"plate\"\nmaterial = \"m\"\nelement = \"quad9\"\n") +
         (unit_inertia_plate ? "inertia = \"unit_density\"\nbody_force = { y = -0.00981 }\n"
                             : gravity_on_plate ? "body_force = { y = -9.81 }\n" : "") +
         "mesh = { generator = \"rectangle\", origin = [-1.0, -2.5], size = [3.0, 0.5], divisions = [3, 1] }\n"
         "[grid]\ncells = \"quad9\"\ngenerator = \"rectangle\"\norigin = [-1.0, -2.0]\nsize = [3.0, 3.0]\ndivisions = [3, 3]\n"
         "grading = [1.0, 0.8]\nrefinements = 2\n"
         "[[probe]]\nname = \"uy\"\nkind = \"point\"\nat = [0.5, -0.2]\ncomponent = \"y\"\n"
         "[output]\nevery = 0\n";
}

// The linear field u = (t / T) A X of the patch tests, prescribed on the nodes of each box.
const Eigen::Matrix2d kA = (Eigen::Matrix2d() << 0.01, 0.02, -0.015, 0.005).finished();
std::string held_on_linear_field(const std::vector<std::string>& boxes, const std::string& T) {
  const std::string ux = "t * (0.01 * x + 0.02 * y) / " + T, uy = "t * (-0.015 * x + 0.005 * y) / " + T;
  std::string text;
  for (std::size_t k = 0; k < boxes.size(); ++k)
    text += "[[boundary]]\nname = \"side" + std::to_string(k) + "\"\nregion = { box = " + boxes[k] + " }\ndisplacement = { x = \"" + ux +
            "\", y = \"" + uy + "\" }\n";
  return text;
}

// Displacement and velocity factors of g after n steps: from a_0 = 0 (the paper), or from the equilibrium a_0 = g
// (the default), with which Newmark integrates the fall exactly.
double u_factor(int n, bool zero_start) {
  const double t = n * kDt;
  if (!zero_start || n == 0) return 0.5 * t * t;
  return 0.5 * t * t - 0.5 * kDt * t + kBeta * kDt * kDt;
}
double v_factor(int n, bool zero_start) { return zero_start ? kDt * (n - 0.5) : kDt * n; }

TEST(MpmFemCoupling, ThePlateSharesOneRowOfGridNodes) {
  const MpmModel m(testing::scene_from_text(falling_scene(true)));
  // Grid: 12 x 12 quad9 cells, 25 x 25 nodes; plate: 12 x 4 cells, 25 x 9 nodes, its top row the grid's bottom row.
  EXPECT_EQ(m.coupled_mesh.grid_cells, 144);
  EXPECT_EQ(m.grid.size(), 144 + 48);
  EXPECT_EQ(m.grid_nodes.size(), 25 * 25 + 25 * 8);
  Index interface = 0, fem = 0;
  for (std::size_t i = 0; i < m.coupled_mesh.fem_node.size(); ++i) interface += m.coupled_mesh.interface_node[i], fem += m.coupled_mesh.fem_node[i];
  EXPECT_EQ(interface, 25);
  EXPECT_EQ(fem, 25 * 9);
  for (std::size_t i = 0; i < m.coupled_mesh.interface_node.size(); ++i)
    if (m.coupled_mesh.interface_node[i]) {
      EXPECT_NEAR(m.grid_nodes.X[Index(i)].y(), -2.0, 1e-15);
    }
  // Every FEM cell is active from the start, with the grid cells that hold particles.
  for (Index c = m.coupled_mesh.grid_cells; c < m.grid.size(); ++c) EXPECT_TRUE(m.activity.cell_active[std::size_t(c)]);
}

TEST(MpmFemCoupling, TheResetFieldCarriesARigidMotionOfThePlateOverTheGrid) {
  MpmModel m(testing::scene_from_text(falling_scene(true)));
  Eigen::Matrix2d A;
  A << 0.0, -0.02, 0.02, 0.0;
  const Vec2 b(0.03, -0.04);
  std::vector<Vec2> X0(std::size_t(m.grid_nodes.size()));
  for (Index i = 0; i < m.grid_nodes.size(); ++i) {
    X0[std::size_t(i)] = m.grid_nodes.X[i];
    if (!m.coupled_mesh.fem_node[std::size_t(i)]) continue;
    m.grid_nodes.u_n[i] = A * X0[std::size_t(i)] + b;
    m.grid_nodes.X[i] += m.grid_nodes.u_n[i];
  }
  StepContext ctx;
  ctx.scene = &m.scene;
  reset_grid(ctx, m.reset, m.coupled_mesh.fem_node, m.grid_nodes);
  double worst = 0.0;
  for (Index i = 0; i < m.grid_nodes.size(); ++i) {
    const Vec2 u = A * X0[std::size_t(i)] + b;
    worst = std::max({worst, (m.grid_nodes.u_n[i] - u).norm(), (m.grid_nodes.X[i] - X0[std::size_t(i)] - u).norm()});
  }
  EXPECT_LE(worst, 1e-13);
  std::printf("[mpm_fem reset field] rigid motion over %d nodes: %.1e\n", int(m.grid_nodes.size()), worst);
}

// Both starts: the default (equilibrium: the body force at the particles and at the plate's free nodes, a fall at g
// exactly, also when the plate's inertia has unit density) and a_0 = 0.
TEST(MpmFemCoupling, DiskAndPlateFallTogetherAsNewmarksClosedForm) {
  for (const int start : {0, 1, 2}) {
  const bool zero_start = start == 1, unit_inertia = start == 2;
  SCOPED_TRACE(zero_start ? "a_0 = 0" : unit_inertia ? "a_0 = g (default), plate of unit-density inertia" : "a_0 = g (default)");
  const SceneSpec scene = testing::scene_from_text(falling_scene(true, unit_inertia),
                                                   zero_start ? std::vector<std::string>{"time.initial_acceleration=\"zero\""}
                                                              : std::vector<std::string>{});
  testing::TempDir dir(zero_start ? "mpm_fem_fall_zero" : unit_inertia ? "mpm_fem_fall_unit" : "mpm_fem_fall");
  auto run = testing::make_mpm_run(scene, dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const MpmModel& m = run->model();
  const double u = kG * u_factor(kSteps, zero_start), v = kG * v_factor(kSteps, zero_start);
  double worst_u = 0.0, worst_v = 0.0, worst_F = 0.0, worst_node = 0.0, worst_grid = 0.0;
  for (Index p = 0; p < m.particles.X.size(); ++p) {
    worst_u = std::max(worst_u, (m.particles.u[p] - Vec2(0.0, u)).norm() / std::abs(u));
    worst_v = std::max(worst_v, (m.particles.v[p] - Vec2(0.0, v)).norm() / std::abs(v));
    worst_F = std::max(worst_F, (m.particles.F[p] - Mat3::Identity()).norm());
  }
  for (Index i = 0; i < m.grid_nodes.size(); ++i) {
    if (m.coupled_mesh.fem_node[std::size_t(i)])
      worst_node = std::max({worst_node, (m.grid_nodes.u_n[i] - Vec2(0.0, u)).norm() / std::abs(u), (m.grid_nodes.v[i] - Vec2(0.0, v)).norm() / std::abs(v)});
    else  // the grid moved with the plate at the start of the last step: the reset field is the plate's u^(n-1)
      worst_grid = std::max(worst_grid, (m.grid_nodes.u_n[i] - Vec2(0.0, kG * u_factor(kSteps - 1, zero_start))).norm() / std::abs(u));
  }
  const auto uy = testing::read_probes(dir.file("probes.csv")).column("uy");
  double worst_probe = 0.0;
  for (int n = 0; n <= kSteps; ++n) worst_probe = std::max(worst_probe, std::abs(uy[std::size_t(n)] - kG * u_factor(n, zero_start)) / std::abs(u));
  // A plate of unit-density inertia weighs 1/rho of a real one: its residual converges only to Newton's tolerance
  // relative to the disk's forces (observed 1e-9).
  const double tol = unit_inertia ? 1e-8 : 1e-10;
  EXPECT_LE(worst_u, tol);
  EXPECT_LE(worst_v, tol);
  EXPECT_LE(worst_F, tol);
  EXPECT_LE(worst_node, tol);
  EXPECT_LE(worst_grid, tol);
  EXPECT_LE(worst_probe, tol);
  EXPECT_GT(std::abs(u), 4 * 0.25);  // fell by more than four of the grid's cells
  std::printf("[mpm_fem free fall, %s] %d particles u %.1e v %.1e F %.1e; plate nodes %.1e; grid %.1e; Newton %lld\n",
              zero_start ? "a_0 = 0" : unit_inertia ? "a_0 = g, unit inertia" : "a_0 = g", int(m.particles.X.size()), worst_u, worst_v, worst_F, worst_node, worst_grid,
              summary.newton_iterations);
  }
}


// The centre particle's (x, y) history of a rolling-disk scene of seed 004, 40 steps of 0.01 s, with a lighter disk
// (n_theta = 150, factor 1.2) than the paper's.
struct History {
  std::vector<double> x, y;
};
double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
  EXPECT_EQ(a.size(), b.size());
  double d = 0.0;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) d = std::max(d, std::abs(a[k] - b[k]));
  return d;
}

// B1 rolls on a rigid ground (method mpm, grid nodes held at y = -1.6); B3 on an FEM plate sharing those nodes.
// With the side and top walls of B1 (free) and the plate's top row held, the coupled run is B1 to round-off: the
// FEM cells, the reset field and the moving-grid locate change nothing where the plate does not move. Free, a
// plate 1000 times stiffer than the disk moves the disk by the plate's deflection only (tens of micrometres).
TEST(MpmFemCoupling, AStiffPlateRollsTheDiskAsTheRigidGroundDoes) {
  const std::vector<std::string> b3 = {"material[plate].E=4.2e9"};
  auto run_text = [](const std::string& text, std::vector<std::string> overrides) {
    for (const char* o : {"time.steps=40", "output.every=0", "body[disk].particles.n_theta=150", "body[disk].particles.factor=1.2"})
      overrides.push_back(o);
    testing::TempDir out("mpm_fem_roll");
    auto run = testing::make_mpm_run(testing::scene_from_text(text, overrides), out.path());
    const RunSummary summary = run->run();
    EXPECT_TRUE(summary.converged) << summary.failure;
    const auto probes = testing::read_probes(out.file("probes.csv"));
    return History{probes.column("centre_x"), probes.column("centre_y")};
  };
  const History ground = run_text(testing::read_text(std::string(LOOM_SOURCE_DIR) + "/scenes/rolling_disk_mpm.toml"), {});
  // Method mpm_fem's scene with B1's free walls: its [[boundary]] left, right and top lose their displacement.
  std::string text = testing::read_text(std::string(LOOM_SOURCE_DIR) + "/scenes/rolling_disk_on_plate.toml");
  for (const std::string held : {"region = { box = [[-2.0, -3.2], [-2.0, 3.4]] }\ndisplacement = { x = 0 }\n",
                                  "region = { box = [[22.0, -3.2], [22.0, 3.4]] }\ndisplacement = { x = 0 }\n",
                                  "region = { box = [[-2.0, 3.4], [22.0, 3.4]] }\ndisplacement = { y = 0 }\n"}) {
    const auto at = text.find(held);
    ASSERT_NE(at, std::string::npos) << held;
    text.replace(at, held.size(), held.substr(0, held.find('\n') + 1));
  }
  const std::string clamp = "\n[[boundary]]\nname = \"interface\"\nregion = { box = [[-2.0, -1.6], [22.0, -1.6]] }\ndisplacement = { x = 0, y = 0 }\n";
  const History held = run_text(text + clamp, b3), plate = run_text(text, b3);
  const double scale = std::abs(ground.x.back());
  const double same_x = largest_difference(ground.x, held.x), same_y = largest_difference(ground.y, held.y);
  const double plate_x = largest_difference(ground.x, plate.x), plate_y = largest_difference(ground.y, plate.y);
  EXPECT_LE(std::max(same_x, same_y), 1e-12 * scale);
  EXPECT_LE(std::max(plate_x, plate_y), 2e-4);
  EXPECT_GT(std::max(plate_x, plate_y), 1e-7);  // the plate does deflect
  std::printf("[mpm_fem vs rigid ground] x(0.4 s) = %.4f m; plate's top held: %.1e, %.1e m; free plate (E x 1000): %.1e, %.1e m\n",
              ground.x.back(), same_x, same_y, plate_x, plate_y);
}


// time.adaptive_dt: each step's size is the formula at the previous step's probe value, and the run ends at
// time.end exactly (the last step shortened), whatever time.steps allows beyond it.
TEST(AdaptiveTimeStep, EachStepTakesTheFormulaAtTheProbesLastValueAndTheRunEndsAtTheEnd) {
  std::string text = falling_scene(true);
  const std::string fixed = "dt = 0.02\nsteps = 25\n";
  text.replace(text.find(fixed), fixed.size(),
               "dt = 0.02\nsteps = 100\nend = 0.3\nadaptive_dt = { probe = \"bottom\", expression = \"bottom > -0.75 ? 0.02 : 0.0125\" }\n");
  text += "[[probe]]\nname = \"bottom\"\nkind = \"extent\"\ncomponent = \"y\"\nbound = \"min\"\n";
  testing::TempDir dir("adaptive_dt");
  auto run = testing::make_mpm_run(testing::scene_from_text(text), dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  EXPECT_TRUE(summary.completed);
  EXPECT_DOUBLE_EQ(summary.last_converged_time, 0.3);
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  const auto t = probes.column("time"), bottom = probes.column("bottom");
  int coarse = 0, fine = 0;
  for (std::size_t k = 1; k < t.size(); ++k) {
    const double want = std::min(bottom[k - 1] > -0.75 ? 0.02 : 0.0125, 0.3 - t[k - 1]);
    EXPECT_NEAR(t[k] - t[k - 1], want, 1e-14) << "step " << k;
    (want == 0.02 ? coarse : fine) += 1;
  }
  EXPECT_NEAR(t.back(), 0.3, 1e-15);
  EXPECT_GT(coarse, 2);
  EXPECT_GT(fine, 2);
  std::printf("[adaptive dt] %zu steps to t = %.3f: %d of 0.02, %d of 0.0125 or the last one's remainder\n", t.size() - 1, t.back(), coarse, fine);
}


// The block's weight reaches the plate's clamp through the shared nodes: a block of particles (sampled from a
// rectangle mesh) resting on the plate, one step of 1000 s (the inertia m / (beta dt^2) is then 1e-9 of the
// stiffness: a static solve), the plate weightless and clamped at its bottom. The clamp's reaction is the block's
// weight, rho A g, to the Newton tolerance: the interface passes the whole force (the soft stiffness's forces sum to
// zero over a cell's nodes and add nothing).
TEST(MpmFemCoupling, TheClampCarriesTheWeightOfABlockOnThePlate) {
  std::string text = falling_scene(false);
  const auto cut = [&](const std::string& from, const std::string& to) { text.replace(text.find(from), from.size(), to); };
  // From rest (a_0 = 0): Newmark carries (1 - 2 beta) / (2 beta) a_0 into the end of a step, however long; from the
  // equilibrium start (a_0 = g) the clamp would see the block's weight and 2/3 of it again.
  cut("dt = 0.02\nsteps = 25\n", "dt = 1000.0\nsteps = 1\ninitial_acceleration = \"zero\"\n");
  cut("particles = { generator = \"disk\", centre = [0.5, -0.2], radius = 0.5, core_radius = 0.4, n_theta = 40, factor = 1.3 }\n",
      "mesh = { generator = \"rectangle\", origin = [0.0, -2.0], size = [0.5, 0.25], divisions = [8, 4], pattern = \"alternating\" }\n"
      "particles_per_cell = 6\n");
  cut("at = [0.5, -0.2]", "at = [0.25, -1.9]");
  text += "[[boundary]]\nname = \"clamp\"\nregion = { box = [[-1.0, -2.5], [2.0, -2.5]] }\ndisplacement = { x = 0, y = 0 }\n"
          "[[probe]]\nname = \"Ry\"\nkind = \"reaction\"\nboundary = \"clamp\"\ncomponent = \"y\"\n"
          "[[probe]]\nname = \"Rx\"\nkind = \"reaction\"\nboundary = \"clamp\"\ncomponent = \"x\"\n";
  testing::TempDir dir("mpm_fem_block");
  auto run = testing::make_mpm_run(testing::scene_from_text(text), dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  const double weight = 1000.0 * 0.5 * 0.25 * 9.81;
  const double Ry = probes.column("Ry").back(), Rx = probes.column("Rx").back();
  EXPECT_NEAR(std::abs(Ry), weight, 1e-7 * weight);
  EXPECT_NEAR(Rx, 0.0, 1e-7 * weight);
  double mass = 0.0;
  for (Index p = 0; p < run->model().particles.X.size(); ++p) mass += run->model().particles.mass[p];
  EXPECT_NEAR(mass * 9.81, weight, 1e-12 * weight);
  std::printf("[mpm_fem block on plate] clamp reaction (%.6e, %.10e) N/m against the weight %.10e N/m\n", Rx, Ry, weight);
}


// Method mpm with several bodies (scheme particle_newmark, the MPM side of the B4 comparison): two disks in cells of
// their own, each under its own body force, fall as Newmark's closed form says, each particle by its body's force.
// Extent probes with a gap stop at the first step between the sorted coordinates wider than it.
TEST(MpmSeveralBodies, TwoDisksOnOneGridFallEachByItsOwnBodyForce) {
  const std::string text =
      "[scene]\nname = \"two-disks\"\nmethod = \"mpm\"\n"
      "[time]\nintegrator = \"newmark\"\ndt = 0.02\nsteps = 25\nbeta = 0.3\ngamma = 0.5\n"
      "[solver]\nresidual_relative = 1e-12\n"
      "[mpm]\nscheme = \"particle_newmark\"\nsoft_stiffness = { c1 = 0.1, c2 = 0.01 }\n"
      "[[material]]\nname = \"m\"\nmodel = \"neo_hooke\"\nE = 4.2e6\nnu = 0.4\ndensity = 1000.0\n"
      "[[material]]\nname = \"n\"\nmodel = \"neo_hooke\"\nE = 1.0e6\nnu = 0.3\ndensity = 500.0\n"
      "[[body]]\nname = \"a\"\nmaterial = \"m\"\n"
      "particles = { generator = \"disk\", centre = [-1.0, 0.5], radius = 0.4, core_radius = 0.3, n_theta = 40, factor = 1.3 }\n"
      "body_force = { y = -9.81 }\n"
      "[[body]]\nname = \"b\"\nmaterial = \"n\"\n"
      "particles = { generator = \"disk\", centre = [1.0, 0.5], radius = 0.4, core_radius = 0.3, n_theta = 40, factor = 1.3 }\n"
      "body_force = { y = -4.0 }\n"
      "[grid]\ncells = \"quad9\"\ngenerator = \"rectangle\"\norigin = [-2.0, -2.0]\nsize = [4.0, 3.0]\ndivisions = [4, 3]\nrefinements = 2\n"
      "[[probe]]\nname = \"low_b\"\nkind = \"extent\"\ncomponent = \"y\"\nbound = \"min\"\nbody = \"b\"\n"
      // Extents with a gap: one wider than the disk stops nowhere; a narrow one at the first wider step between the
      // sorted x of the particles of body a, from the other end.
      "[[probe]]\nname = \"right_of_a\"\nkind = \"extent\"\ncomponent = \"x\"\nbody = \"a\"\ngap = 1.0\n"
      "[[probe]]\nname = \"right_of_a_narrow\"\nkind = \"extent\"\ncomponent = \"x\"\nbody = \"a\"\ngap = 0.012\n"
      "[[probe]]\nname = \"left_of_a_narrow\"\nkind = \"extent\"\ncomponent = \"x\"\nbody = \"a\"\nbound = \"min\"\ngap = 0.012\n"
      "[output]\nevery = 0\n";
  testing::TempDir dir("two_disks");
  auto run = testing::make_mpm_run(testing::scene_from_text(text), dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const Points<2>& particles = run->model().particles;
  double worst = 0.0, low_b = 1e300;
  std::vector<double> xa;  // body a's x, sorted below
  for (Index p = 0; p < particles.X.size(); ++p) {
    if (particles.body[p] == 0) xa.push_back(particles.position(p).x());
    const double g = particles.body[p] == 0 ? -9.81 : -4.0;
    // The default start, a_0 = each particle's body force: g t^2 / 2 exactly.
    worst = std::max(worst, (particles.u[p] - Vec2(0.0, g * u_factor(kSteps, false))).norm() / std::abs(g * u_factor(kSteps, false)));
    if (particles.body[p] == 1) low_b = std::min(low_b, particles.position(p).y());
  }
  EXPECT_LE(worst, 1e-10);
  // The extent probe reads its body only (body a, under more gravity, ends 0.7 m lower).
  const testing::ProbeTable probes = testing::read_probes(dir.file("probes.csv"));
  EXPECT_NEAR(probes.column("low_b").back(), low_b, 1e-12);
  std::sort(xa.begin(), xa.end());
  std::size_t up = 0, down = xa.size() - 1;
  while (up + 1 < xa.size() && xa[up + 1] - xa[up] <= 0.012) ++up;
  while (down > 0 && xa[down] - xa[down - 1] <= 0.012) --down;
  EXPECT_NEAR(probes.column("right_of_a").back(), xa.back(), 1e-12);
  EXPECT_NEAR(probes.column("right_of_a_narrow").back(), xa[up], 1e-12);
  EXPECT_NEAR(probes.column("left_of_a_narrow").back(), xa[down], 1e-12);
  EXPECT_LT(xa[up], xa.back() - 0.1);  // the narrow gap stops inside the disk
  EXPECT_GT(xa[down], xa.front() + 0.1);
  std::printf("[mpm, two bodies] %d particles: u against each body's closed form %.1e\n", int(particles.X.size()), worst);
}


// The patch test across the interface: a grid filled with particles whose quadrature is exact for a constant
// stress (each quad9 cell cut into two triangles with 6 Dunavant points each, degree 4 >= the degree 3 of grad N),
// a plate of the same material below it (across two materials a homogeneous F would not balance the tractions),
// every outer node given u = A X (one static-like step of 1e4 s, Neo-Hooke). A homogeneous deformation F = I + A
// is then the exact discrete solution on both sides: every node, grid's and plate's, moves by A X and every
// particle has F = I + A, to the Newton tolerance (with the plate 3 times stiffer the interface nodes are off by
// 2e-3: the test can fail). One step only: the grid's held nodes are spatial points, reset every step, so over
// several steps the same expression would not prescribe a homogeneous motion of the material there; the FEM
// side's later steps are the next test's.
TEST(MpmFemCoupling, AHomogeneousDeformationPassesTheInterfaceExactly) {
  std::string text =
      "[scene]\nname = \"patch\"\nmethod = \"mpm_fem\"\n"
      "[time]\nintegrator = \"newmark\"\ndt = 1e4\nsteps = 1\nbeta = 0.3\ngamma = 0.5\n"
      "[solver]\nresidual_relative = 1e-13\nresidual_absolute = 1e-14\n"
      "[mpm]\nsoft_stiffness = { c1 = 0.0, c2 = 0.0 }\n"
      "[[material]]\nname = \"m\"\nmodel = \"neo_hooke\"\nE = 1.0e6\nnu = 0.3\ndensity = 1000.0\n"
      "[[body]]\nname = \"block\"\nmaterial = \"m\"\nparticles_per_cell = 6\n"
      "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [2.0, 1.0], divisions = [4, 2], pattern = \"alternating\" }\n"
      "[[body]]\nname = \"plate\"\nmaterial = \"m\"\nelement = \"quad9\"\n"
      "mesh = { generator = \"rectangle\", origin = [0.0, -0.5], size = [2.0, 0.5], divisions = [2, 1] }\n"
      "[grid]\ncells = \"quad9\"\ngenerator = \"rectangle\"\norigin = [0.0, 0.0]\nsize = [2.0, 1.0]\ndivisions = [2, 1]\nrefinements = 1\n"
      "[output]\nevery = 0\n";
  text += held_on_linear_field({"[[0.0, -0.5], [0.0, 1.0]]", "[[2.0, -0.5], [2.0, 1.0]]", "[[0.0, 1.0], [2.0, 1.0]]", "[[0.0, -0.5], [2.0, -0.5]]"}, "1e4");
  testing::TempDir dir("mpm_fem_patch");
  auto run = testing::make_mpm_run(testing::scene_from_text(text), dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const MpmModel& m = run->model();
  const Eigen::Matrix2d& A = kA;
  double worst_node = 0.0, worst_F = 0.0;
  for (Index i = 0; i < m.grid_nodes.size(); ++i) {
    const Vec2 X0 = m.grid_nodes.X[i] - m.grid_nodes.u_n[i];  // undeformed
    worst_node = std::max(worst_node, (m.grid_nodes.u_n[i] + m.grid_nodes.u[i] - A * X0).norm());
  }
  Mat3 F = Mat3::Identity();
  F.topLeftCorner<2, 2>() += A;
  for (Index p = 0; p < m.particles.X.size(); ++p) worst_F = std::max(worst_F, (m.particles.F[p] - F).norm());
  EXPECT_EQ(m.particles.X.size(), 8 * 2 * 6);
  EXPECT_LE(worst_node, 1e-12);
  EXPECT_LE(worst_F, 1e-12);
  std::printf("[mpm_fem patch] %d nodes move by A X to %.1e, %d particles have F = I + A to %.1e\n", int(m.grid_nodes.size()), worst_node,
              int(m.particles.X.size()), worst_F);
}


// The FEM side over several steps: the plate's boundary nodes (its top row is the grid's bottom row) given
// u = (t / 3e4) A X^, three static-like steps, a small disk far from it. Its interior nodes must follow the
// homogeneous deformation at every step; from the second step on its cells start deformed (F_n = dX/dX^ != I) and
// the prescribed values must be read at the undeformed X^ (the nodes have moved).
TEST(MpmFemCoupling, ThePlateFollowsAHomogeneousDeformationOverSeveralSteps) {
  std::string text =
      "[scene]\nname = \"plate-patch\"\nmethod = \"mpm_fem\"\n"
      "[time]\nintegrator = \"newmark\"\ndt = 1e4\nsteps = 3\nbeta = 0.3\ngamma = 0.5\n"
      "[solver]\nresidual_relative = 1e-13\nresidual_absolute = 1e-14\n"
      "[mpm]\nsoft_stiffness = { c1 = 0.1, c2 = 0.01 }\n"
      "[[material]]\nname = \"m\"\nmodel = \"neo_hooke\"\nE = 1.0e6\nnu = 0.3\ndensity = 1000.0\n"
      "[[body]]\nname = \"disk\"\nmaterial = \"m\"\n"
      "particles = { generator = \"disk\", centre = [1.0, 1.5], radius = 0.2, core_radius = 0.15, n_theta = 40, factor = 1.3 }\n"
      "[[body]]\nname = \"plate\"\nmaterial = \"m\"\nelement = \"quad9\"\n"
      "mesh = { generator = \"rectangle\", origin = [0.0, -0.5], size = [2.0, 0.5], divisions = [2, 1] }\n"
      "[grid]\ncells = \"quad9\"\ngenerator = \"rectangle\"\norigin = [0.0, 0.0]\nsize = [2.0, 2.0]\ndivisions = [2, 2]\nrefinements = 2\n"
      "[output]\nevery = 0\n";
  text += held_on_linear_field({"[[0.0, -0.5], [0.0, 0.0]]", "[[2.0, -0.5], [2.0, 0.0]]", "[[0.0, 0.0], [2.0, 0.0]]", "[[0.0, -0.5], [2.0, -0.5]]"}, "3e4");
  testing::TempDir dir("mpm_fem_plate_patch");
  auto run = testing::make_mpm_run(testing::scene_from_text(text), dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const MpmModel& m = run->model();
  const Eigen::Matrix2d& A = kA;
  double worst = 0.0;
  Index interior = 0;
  for (Index i = 0; i < m.grid_nodes.size(); ++i) {
    if (!m.coupled_mesh.fem_node[std::size_t(i)]) continue;
    const Vec2 X0 = m.grid_nodes.X[i] - m.grid_nodes.u_n[i];
    worst = std::max(worst, (m.grid_nodes.u_n[i] - A * X0).norm());
    interior += X0.x() > 1e-9 && X0.x() < 2.0 - 1e-9 && X0.y() > -0.5 + 1e-9 && X0.y() < -1e-9;
  }
  EXPECT_EQ(interior, 15 * 7);  // 8 x 4 cells of quad9: 17 x 9 nodes, 15 x 7 inside
  EXPECT_LE(worst, 1e-12);
  std::printf("[mpm_fem plate over three steps] the plate's nodes at A X^ to %.1e (%d inside)\n", worst, int(interior));
}

// A coupled run with an adaptive step, stopped and restarted, is the run that went straight through, bit for bit
// (the checkpoint holds the nodes' reference positions, u_n, v and a; the restored probes give the next step's size).
TEST(MpmFemCoupling, ARestartedAdaptiveRunIsTheStraightRun) {
  std::string text = falling_scene(true);
  const std::string fixed = "dt = 0.02\nsteps = 25\n";
  text.replace(text.find(fixed), fixed.size(),
               "dt = 0.02\nsteps = 100\nend = 0.3\nadaptive_dt = { probe = \"bottom\", expression = \"bottom > -0.75 ? 0.02 : 0.0125\" }\n");
  text += "[[probe]]\nname = \"bottom\"\nkind = \"extent\"\ncomponent = \"y\"\nbound = \"min\"\n"
          "[[probe]]\nname = \"energy\"\nkind = \"energy\"\nenergy = \"mechanical\"\n";
  testing::TempDir dir("mpm_fem_restart");
  const std::string scene = dir.file("scene.toml");
  testing::write_text(scene, text);
  const auto straight = testing::run_loom({"run", scene, "--quiet", "--threads", "1", "--out", dir.file("straight")});
  ASSERT_EQ(straight.exit_code, 0) << straight.err;
  const auto first = testing::run_loom({"run", scene, "--quiet", "--threads", "1", "--out", dir.file("split"), "--stop-after", "9"});
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const auto second = testing::run_loom({"run", scene, "--quiet", "--threads", "1", "--restart", dir.file("split")});
  ASSERT_EQ(second.exit_code, 0) << second.err;
  const std::string a = testing::read_text(dir.file("straight/probes.csv")), b = testing::read_text(dir.file("split/probes.csv"));
  EXPECT_EQ(a, b);
  EXPECT_GT(std::count(a.begin(), a.end(), '\n'), 15);
  // Too few steps for time.end: the run fails (exit 1) and says so, keeping what it wrote.
  std::string few = text;
  few.replace(few.find("steps = 100"), 11, "steps = 5\n");
  testing::write_text(scene, few);
  const auto short_run = testing::run_loom({"run", scene, "--quiet", "--threads", "1", "--out", dir.file("few")});
  EXPECT_EQ(short_run.exit_code, 1) << short_run.err;
  EXPECT_NE(short_run.err.find("time.steps = 5 ran out"), std::string::npos) << short_run.err;
  const std::string rows = testing::read_text(dir.file("few/probes.csv"));
  EXPECT_EQ(std::count(rows.begin(), rows.end(), '\n'), 7);  // the header, the start and the five steps
}

}  // namespace
}  // namespace loom
