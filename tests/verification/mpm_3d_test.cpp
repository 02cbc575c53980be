// Method mpm in 3D (tet4 background grids, seed 003 §6.3-6.4):
//  - free fall: a block under a constant body force, displacement (p1) and mixed u-p (p1p1_up with ASGS)
//    grids, follows Newmark's exact solution u = g t^2 / 2 at every particle (the derivation is
//    mpm_free_fall_test.cpp's: a rigid translation has f_int = 0, so every active node gets a = g);
//  - the particle-to-grid projection conserves mass, linear and angular momentum (sum_I N_I(x_p) = 1 and
//    sum_I N_I(x_p) x_I = x_p for linear cells: sum_I x_I x m_I v_I = sum_p x_p x m_p v_p);
//  - material points at the centroids of a body-fitted grid reproduce the fem's linear tetrahedron (one
//    Gauss point at the centroid) on a static nonlinear problem with body forces and face tractions: the
//    same equations, so the same solution;
//  - the manufactured solution of seed 003 §6.1 extruded along z (scenes/mms_mpm_3d.toml) converges at the
//    seed's 2D rates (Fig 2: about 2 for u and p) with PPP and ASGS: the L2 errors of the grid's u and p on
//    n x n x 2 Kuhn lattices, integrated with the degree-6 tetrahedron rule in every cell;
//  - results do not depend on the thread count (a short run of the bending column on a coarse grid);
//  - a run stopped and restarted from its checkpoint writes the probes of the uninterrupted run, bit for bit;
//  - the paper's columns at h = 0.25 (4 points per cell) over a few hundred steps stay near loom's FEM reference
//    (docs/fem_3d.md, tet10 h = 0.25) within the discretisation error docs/mpm/mpm_3d.md measures, and never gain
//    energy beyond 1e-5 of it (the grid-Newmark transfers dissipate; docs/mpm/velocity_update.md);
//  - 3D scene errors: a rule the tetrahedron does not have, the particle Newmark scheme.
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <cstdio>

#include "engine/core/errors.hpp"
#include "engine/mesh/tetrahedron_rules.hpp"
#include "engine/scene/scene_loader.hpp"
#include "systems/map/project_to_grid.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

constexpr double kDt = 0.05;
constexpr int kSteps = 20;
const Vec3 kG(1.0, -2.0, -9.81);

std::string falling_block(const std::string& element) {
  const bool mixed = element == "p1p1_up";
  return std::string("[scene]\nname = \"mpm-3d-free-fall\"\nmethod = \"mpm\"\ndimension = 3\n") +
         "[time]\nintegrator = \"newmark\"\ndt = 0.05\nsteps = 20\ninitial_acceleration = \"equilibrium\"\n"
         "[solver]\nresidual_relative = 1e-12\n"
         "[[material]]\nname = \"m\"\nmodel = \"" + (mixed ? "neo_hooke_split" : "neo_hooke") + "\"\nE = 100.0\nnu = " + (mixed ? "0.5" : "0.3") +
         "\ndensity = 2.0\n"
         "[[body]]\nname = \"block\"\nmaterial = \"m\"\nelement = \"" + element + "\"\n" + (mixed ? "stabilisation = \"asgs\"\n" : "") +
         "particles_per_cell = 4\n"
         "mesh = { generator = \"box\", origin = [0.1, 0.2, 7.3], size = [0.6, 0.5, 0.4], divisions = [3, 2, 2] }\n"
         "[grid]\ngenerator = \"box\"\norigin = [-1.0, -3.0, -6.0]\nsize = [3.0, 5.0, 15.0]\ndivisions = [6, 10, 30]\n"
         "[body_force]\nx = 1.0\ny = -2.0\nz = -9.81\n"
         "[[probe]]\nname = \"uz\"\nkind = \"point\"\nat = [0.3, 0.4, 7.5]\ncomponent = \"z\"\n"
         "[output]\nevery = 0\n";
}

// `by_default`: without the initial_acceleration key (the default start is the equilibrium one).
void check_free_fall(const std::string& element, bool by_default = false) {
  SCOPED_TRACE(element + (by_default ? ", default start" : ""));
  std::string text = falling_block(element);
  if (by_default) text.erase(text.find("initial_acceleration = \"equilibrium\"\n"), std::string("initial_acceleration = \"equilibrium\"\n").size());
  auto run = testing::make_mpm_run<3>(testing::scene_from_text(text));
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const Points<3>& particles = run->model().particles;
  const double T = kDt * kSteps;
  const Vec3 u_exact = 0.5 * kG * T * T, v_exact = kG * T;
  double worst_u = 0.0, worst_v = 0.0, worst_F = 0.0;
  for (Index p = 0; p < particles.X.size(); ++p) {
    worst_u = std::max(worst_u, (particles.u[p] - u_exact).norm() / u_exact.norm());
    worst_v = std::max(worst_v, (particles.v[p] - v_exact).norm() / v_exact.norm());
    worst_F = std::max(worst_F, (particles.F[p] - Mat3::Identity()).norm());
  }
  EXPECT_LE(worst_u, 1e-10);
  EXPECT_LE(worst_v, 1e-10);
  EXPECT_LE(worst_F, 1e-12);
  EXPECT_NEAR(run->probe_values()[0], u_exact.z(), 1e-10 * u_exact.norm());
  EXPECT_GT(u_exact.norm() / 0.5, 10.0);  // fell across more than ten grid cells
  std::printf("[mpm 3d free fall] %-8s %d particles: u %.1e, v %.1e, |F - I| %.1e; Newton %lld\n", element.c_str(), int(particles.X.size()),
              worst_u, worst_v, worst_F, summary.newton_iterations);
}

TEST(Mpm3d, FreeFallIsExactOnADisplacementGrid) { check_free_fall("p1"); }
TEST(Mpm3d, FreeFallIsExactOnAMixedGrid) { check_free_fall("p1p1_up"); }
// A scene that says nothing of the start falls at g (it lagged by g dt t / 2: 5 % after 20 steps).
TEST(Mpm3d, ABodyFallsAtGByDefault) { check_free_fall("p1", true); }

TEST(Mpm3d, ProjectionConservesMassAndMomentum) {
  std::string text = falling_block("p1p1_up");
  text.replace(text.find("particles_per_cell = 4"), 22, "particles_per_cell = 14");
  text += "";
  SceneSpec scene = testing::scene_from_text(text, {"body[0].initial_velocity.x=\"1.0 + 2.0 * y - z\"",
                                                    "body[0].initial_velocity.y=\"-2.0 * x + 0.5 * z\"",
                                                    "body[0].initial_velocity.z=\"x * y\""});
  MpmModelT<3> m(scene);
  StepContext ctx;
  ctx.scene = &m.scene;
  project_to_grid(ctx, m.grid, m.particles, m.particle_loc, m.grid_nodes);
  double mass_p = 0.0, mass_g = 0.0;
  Vec3 P_p = Vec3::Zero(), P_g = Vec3::Zero(), L_p = Vec3::Zero(), L_g = Vec3::Zero();
  for (Index p = 0; p < m.particles.X.size(); ++p) {
    mass_p += m.particles.mass[p];
    P_p += m.particles.mass[p] * m.particles.v[p];
    L_p += m.particles.X[p].cross(m.particles.mass[p] * m.particles.v[p]);
  }
  for (Index i = 0; i < m.grid_nodes.size(); ++i) {
    mass_g += m.grid_nodes.lumped_mass[i];
    P_g += m.grid_nodes.lumped_mass[i] * m.grid_nodes.v_n[i];
    L_g += m.grid_nodes.X[i].cross(m.grid_nodes.lumped_mass[i] * m.grid_nodes.v_n[i]);
  }
  EXPECT_GT(P_p.norm(), 0.1 * mass_p);
  EXPECT_NEAR(mass_g, mass_p, 1e-13 * mass_p);  // sums of 1008 terms in two orders
  EXPECT_LE((P_g - P_p).norm(), 1e-13 * P_p.norm());
  EXPECT_LE((L_g - L_p).norm(), 1e-12 * L_p.norm());
  std::printf("[mpm 3d projection] %d particles: mass %.1e, momentum %.1e, angular momentum %.1e (relative)\n", int(m.particles.X.size()),
              std::abs(mass_g - mass_p) / mass_p, (P_g - P_p).norm() / P_p.norm(), (L_g - L_p).norm() / L_p.norm());
}

// A block on a clamped base, pulled down by gravity hard enough to be nonlinear (the top sags by ~10 % of the
// height) and loaded on its top face by a traction linear in x and y, one static step. With the grid equal to
// the body mesh and one particle at each cell's centroid, the MPM's equations are the fem's linear tetrahedron
// with its one-point rule, and its traction points (three a face, degree 2) integrate the face loads exactly
// as the fem's face rule does: the nodal displacements agree.
std::string sagging_block(const std::string& method) {
  const bool mpm = method == "mpm";
  std::string s = "[scene]\nname = \"sag\"\nmethod = \"" + method + "\"\ndimension = 3\n"
                  "[time]\nintegrator = \"static\"\ndt = 1.0\nsteps = 1\n"
                  "[solver]\nresidual_relative = 1e-13\n"
                  "[[material]]\nname = \"m\"\nmodel = \"neo_hooke\"\nE = 1000.0\nnu = 0.3\ndensity = 1.0\n"
                  "[[body]]\nname = \"block\"\nmaterial = \"m\"\nelement = \"p1\"\n" +
                  std::string(mpm ? "particles_per_cell = 1\n" : "") +
                  "mesh = { generator = \"box\", origin = [0.0, 0.0, 0.0], size = [1.0, 1.0, 2.0], divisions = [2, 2, 4] }\n"
                  "[body_force]\nz = -60.0\nx = 20.0\n"
                  "[[boundary]]\nname = \"base\"\nregion = { box = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0]] }\ndisplacement = { x = 0.0, y = 0.0, z = 0.0 }\n"
                  "[[boundary]]\nname = \"top\"\nregion = { box = [[0.0, 0.0, 2.0], [1.0, 1.0, 2.0]] }\n"
                  "traction = { x = \"10 * (1 + y)\", y = \"-5\", z = \"-30 * x\" }\n"
                  "[output]\nevery = 0\n";
  if (mpm) s += "[grid]\ngenerator = \"box\"\norigin = [0.0, 0.0, 0.0]\nsize = [1.0, 1.0, 2.0]\ndivisions = [2, 2, 4]\n";
  return s;
}

TEST(Mpm3d, CentroidParticlesOnABodyFittedGridReproduceTheLinearTetrahedron) {
  auto fem = testing::make_fem_run<3>(testing::scene_from_text(sagging_block("fem")));
  const RunSummary fs = fem->run();
  ASSERT_TRUE(fs.converged) << fs.failure;
  auto mpm = testing::make_mpm_run<3>(testing::scene_from_text(sagging_block("mpm")));
  const RunSummary ms = mpm->run();
  ASSERT_TRUE(ms.converged) << ms.failure;
  // The particle at a cell's centroid moved by the mean of the cell's corner displacements.
  const auto& grid = mpm->model().grid;
  const auto& loc = mpm->model().particle_loc;
  const Points<3>& particles = mpm->model().particles;
  const Nodes<3>& nodes = fem->nodes();
  ASSERT_EQ(particles.X.size(), grid.size());
  double scale = 0.0, worst = 0.0;
  for (Index p = 0; p < particles.X.size(); ++p) {
    const Index c = loc.cell[p];  // located at the start of the step: the undeformed grid
    Vec3 u = Vec3::Zero();
    for (int a = 0; a < 4; ++a) u += 0.25 * nodes.u[grid.node(c, a)];  // the grid's and the fem mesh's nodes coincide
    scale = std::max(scale, u.norm());
    worst = std::max(worst, (particles.u[p] - u).norm());
  }
  EXPECT_GT(scale, 0.1);  // nonlinear: the top moves by > 5 % of the height
  EXPECT_LE(worst, 1e-9 * scale);
  std::printf("[mpm 3d vs fem tet4] max |u| %.3f, worst difference %.1e; Newton fem %lld, mpm %lld\n", scale, worst, fs.newton_iterations,
              ms.newton_iterations);
}

// A free block (no body force) on a grid that does not fit it, pushed on its x = 0.7 face by a constant traction
// and on its top by one growing in time. Its particles' momentum is the impulse of the loads, and the centre of
// mass moves as a rigid body's under the constant part: the lumped grid mass and the partition of unity carry
// the resultant of the traction points to the particles whatever the body's deformation (sum_I f_int,I = 0).
// Newmark's trapezoidal velocity update integrates a load linear in t exactly; its position update does only
// for the constant one (x).
TEST(Mpm3d, TractionPointsGiveTheBodyTheImpulseOfTheLoads) {
  const std::string text =
      "[scene]\nname = \"pushed\"\nmethod = \"mpm\"\ndimension = 3\n"
      "[time]\nintegrator = \"newmark\"\ndt = 0.02\nsteps = 25\ninitial_acceleration = \"equilibrium\"\n"
      "[solver]\nresidual_relative = 1e-12\n"
      "[[material]]\nname = \"m\"\nmodel = \"neo_hooke\"\nE = 200.0\nnu = 0.3\ndensity = 2.0\n"
      "[[body]]\nname = \"block\"\nmaterial = \"m\"\nelement = \"p1\"\nparticles_per_cell = 4\n"
      "mesh = { generator = \"box\", origin = [0.1, 0.2, 0.3], size = [0.6, 0.5, 0.4], divisions = [3, 2, 2] }\n"
      "[grid]\ngenerator = \"box\"\norigin = [-2.05, -1.1, -1.3]\nsize = [4.0, 3.0, 3.0]\ndivisions = [12, 9, 9]\n"
      "[[boundary]]\nname = \"side\"\nregion = { box = [[0.7, 0.2, 0.3], [0.7, 0.7, 0.7]] }\ntraction = { x = -6.0 }\n"
      "[[boundary]]\nname = \"top\"\nregion = { box = [[0.1, 0.2, 0.7], [0.7, 0.7, 0.7]] }\ntraction = { z = \"4 * t\" }\n"
      "[output]\nevery = 0\n";
  auto run = testing::make_mpm_run<3>(testing::scene_from_text(text));
  const Points<3>& particles = run->model().particles;
  const Index n_traction = run->model().traction_points.X.size();
  EXPECT_EQ(n_traction, 3 * (2 * 2 * 2 + 3 * 2 * 2));  // 3 points on each of the faces' triangles
  double mass = 0.0;
  Vec3 X0 = Vec3::Zero();
  for (Index p = 0; p < particles.X.size(); ++p) mass += particles.mass[p], X0 += particles.mass[p] * particles.X[p];
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const double T = 0.02 * 25, A_side = 0.5 * 0.4, A_top = 0.6 * 0.5;
  const Vec3 impulse(-6.0 * A_side * T, 0.0, 2.0 * A_top * T * T);
  Vec3 P = Vec3::Zero(), x_cm = Vec3::Zero();
  for (Index p = 0; p < particles.X.size(); ++p) P += particles.mass[p] * particles.v[p], x_cm += particles.mass[p] * particles.position(p);
  x_cm = (x_cm - X0) / mass;
  const double ux_exact = -6.0 * A_side / mass * T * T / 2;
  EXPECT_LE((P - impulse).norm(), 1e-12 * impulse.norm());
  EXPECT_NEAR(x_cm.x(), ux_exact, 1e-12 * std::abs(ux_exact));
  EXPECT_GT(std::abs(ux_exact), 0.3);  // crossed a grid cell: the traction points moved with the body
  std::printf("[mpm 3d tractions] %d traction points: impulse %.1e, centre of mass x %.1e (relative); Newton %lld\n", int(n_traction),
              (P - impulse).norm() / impulse.norm(), std::abs(x_cm.x() - ux_exact) / std::abs(ux_exact), summary.newton_iterations);
}

// The extruded manufactured solution: u = (f(s), -f(s), 0), f = 0.01 s^2 e^s, s = x + y; p = E/3 sin 2 pi x cos 2 pi y.
Vec3 mms_u(const Vec3& X) {
  const double s = X.x() + X.y(), f = 0.01 * s * s * std::exp(s);
  return Vec3(f, -f, 0.0);
}
double mms_p(const Vec3& X) { return 10.0 / 3.0 * std::sin(2 * M_PI * X.x()) * std::cos(2 * M_PI * X.y()); }

struct MmsError {
  double u = 0, p = 0;
  long long newton = 0;
};

MmsError run_mms(const std::string& stabilisation, int n) {
  const std::string depth = std::to_string(2.0 / n), nn = std::to_string(n);
  const std::string div = std::string("[") + nn + "," + nn + ",2]", size = std::string("[1.0,1.0,") + depth + "]";
  const SceneSpec scene = load_scene(std::string(LOOM_SOURCE_DIR) + "/scenes/mms_mpm_3d.toml",
                                     {"body[0].stabilisation=\"" + stabilisation + "\"", "body[0].mesh.divisions=" + div, "grid.divisions=" + div,
                                      "body[0].mesh.size=" + size, "grid.size=" + size,
                                      "boundary[5].region.box=[[0.0,0.0," + depth + "],[1.0,1.0,1.0]]", "output.every=0"});
  auto run = testing::make_mpm_run<3>(scene);
  const RunSummary summary = run->run();
  EXPECT_TRUE(summary.converged) << stabilisation << " n = " << n << ": " << summary.failure;
  const auto& m = run->model();
  const auto& rule = tetrahedron_rule(24);
  auto for_each_point = [&](auto&& f) {
    for (Index c = 0; c < m.grid.size(); ++c)
      for (const auto& q : rule) {
        Vec3 X = Vec3::Zero(), u = Vec3::Zero();
        double p = 0.0;
        for (int a = 0; a < 4; ++a) {
          const Index i = m.grid.node(c, a);
          X += q.l[a] * m.grid_nodes.X[i], u += q.l[a] * m.grid_nodes.u[i], p += q.l[a] * m.grid_nodes.p[i];
        }
        f(X, u, p, q.w * m.grid.measure[c]);
      }
  };
  double volume = 0.0, mean_h = 0.0, mean_ex = 0.0;  // the pressure is compared up to its mean
  for_each_point([&](const Vec3& X, const Vec3&, double p, double w) { volume += w, mean_h += w * p, mean_ex += w * mms_p(X); });
  mean_h /= volume, mean_ex /= volume;
  MmsError e;
  e.newton = summary.newton_iterations;
  for_each_point([&](const Vec3& X, const Vec3& u, double p, double w) {
    e.u += w * (u - mms_u(X)).squaredNorm();
    e.p += w * std::pow((p - mean_h) - (mms_p(X) - mean_ex), 2);
  });
  // Per unit area of the square (the depth 2 / n shrinks with the grid): the 2D norms of the plane solution.
  e.u = std::sqrt(e.u / volume), e.p = std::sqrt(e.p / volume);
  return e;
}

TEST(Mpm3d, ExtrudedManufacturedSolutionConvergesAtTheSeedsRates) {
  for (const std::string stab : {"ppp", "asgs"}) {
    // ASGS with c1 = 1 is pre-asymptotic longer (its residual misses div sigma_dev, an O(tau1) consistency error;
    // mpm_mms_test.cpp): one grid more.
    std::vector<int> ns = stab == "asgs" ? std::vector<int>{4, 8, 16, 32} : std::vector<int>{4, 8, 16};
    std::vector<MmsError> es;
    for (int n : ns) es.push_back(run_mms(stab, n));
    for (std::size_t k = 0; k < es.size(); ++k) {
      const double ru = k ? std::log(es[k - 1].u / es[k].u) / std::log(2.0) : NAN;
      const double rp = k ? std::log(es[k - 1].p / es[k].p) / std::log(2.0) : NAN;
      std::printf("[mms 3d %-4s] h = %-7.4f |e_u| = %.3e (rate %5.2f)  |e_p| = %.3e (rate %5.2f)  Newton %lld\n", stab.c_str(), 1.0 / ns[k],
                  es[k].u, ru, es[k].p, rp, es[k].newton);
    }
    const MmsError &a = es[es.size() - 2], &b = es.back();
    EXPECT_GE(std::log(a.u / b.u) / std::log(2.0), 1.8) << stab;
    EXPECT_GE(std::log(a.p / b.p) / std::log(2.0), 1.3) << stab;
  }
}

struct Snapshot {
  std::vector<double> probes;
  std::vector<Vec3> u;
  std::vector<double> p;
};

Snapshot run_with_threads(const SceneSpec& scene, int threads) {
  oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  oneapi::tbb::task_arena arena(threads);
  Snapshot s;
  arena.execute([&] {
    auto run = testing::make_mpm_run<3>(scene);
    const RunSummary summary = run->run();
    EXPECT_TRUE(summary.converged) << summary.failure;
    s.probes = run->probe_values();
    const auto& pts = run->model().particles;
    for (Index p = 0; p < pts.X.size(); ++p) s.u.push_back(pts.u[p]), s.p.push_back(pts.pressure[p]);
  });
  return s;
}

TEST(Mpm3d, BendingColumnDoesNotDependOnTheThreadCount) {
  const SceneSpec scene = testing::scene_from_text(
      testing::read_text(std::string(LOOM_SOURCE_DIR) + "/scenes/column_bending_mpm.toml"),
      {"time.steps=6", "output.every=0", "body[0].particles_per_cell=4", "body[0].mesh.divisions=[2,2,12]", "grid.divisions=[16,4,14]"});
  const Snapshot one = run_with_threads(scene, 1), two = run_with_threads(scene, 2);
  ASSERT_EQ(one.u.size(), two.u.size());
  for (std::size_t k = 0; k < one.u.size(); ++k) {
    ASSERT_EQ(one.u[k], two.u[k]) << "particle " << k;
    ASSERT_EQ(one.p[k], two.p[k]) << "particle " << k;
  }
  EXPECT_EQ(one.probes, two.probes);
}

struct ColumnRun {
  std::vector<double> t, ux, uy, total, newton;
};

ColumnRun run_column(const std::string& column, int steps) {
  const SceneSpec scene = load_scene(std::string(LOOM_SOURCE_DIR) + "/scenes/column_" + column + "_mpm.toml",
                                     {"time.steps=" + std::to_string(steps), "body[0].particles_per_cell=4", "output.every=0"});
  testing::TempDir dir("mpm_3d_" + column);
  auto run = testing::make_mpm_run<3>(scene, dir.path());
  const RunSummary summary = run->run();
  EXPECT_TRUE(summary.converged) << summary.failure;
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  return {probes.column("time"), probes.column("ux_A"), probes.column("uy_A"), probes.column("total"), probes.column("newton")};
}

// Energy never above its start (to 1e-5 of it); Newton steady. Under the grid's velocity increment (FLIP) the
// particles' kinetic energy is not bounded by the grid's: the bending column's (its held base nodes start each step
// at rest while the particles next to them move) rose by 1e-6 of E0 in its first step and falls from the second on.
void check_column_invariants(const ColumnRun& r, double min_kept) {
  const double E0 = r.total.front();
  for (std::size_t k = 0; k < r.total.size(); ++k) {
    EXPECT_LE(r.total[k], E0 * (1.0 + 1e-5)) << "t = " << r.t[k];
    EXPECT_LE(r.newton[k], 10.0) << "t = " << r.t[k];
  }
  EXPECT_GT(r.total.back(), min_kept * E0);
}

TEST(Mpm3d, BendingColumnsFirstSwingIsNearTheFemReference) {
  const ColumnRun r = run_column("bending", 450);  // past the first peak (FEM: 2.8381 m at t = 0.439 s)
  ASSERT_EQ(r.t.size(), 451u);
  const double peak = *std::max_element(r.ux.begin(), r.ux.end());
  EXPECT_NEAR(peak, 2.8381, 0.03 * 2.8381);  // measured 2.819 (2.823 before the FLIP update; docs/mpm/mpm_3d.md)
  check_column_invariants(r, 0.7);           // 19 % lost by t = 0.45 s
  std::printf("[mpm 3d bending, h = 0.25, 4 per cell] first peak %.4f m (FEM 2.8381), energy kept %.3f\n", peak, r.total.back() / r.total.front());
}

TEST(Mpm3d, TwistingColumnsFirstTurnIsNearTheFemReference) {
  const ColumnRun r = run_column("twisting", 200);
  ASSERT_EQ(r.t.size(), 201u);
  EXPECT_NEAR(r.uy[20], -1.1498, 0.2 * 1.1498);  // t = 0.02 s; measured -0.939 (18 % off; -0.973 before the FLIP update)
  check_column_invariants(r, 0.4);               // 44 % lost by t = 0.2 s
  std::printf("[mpm 3d twisting, h = 0.25, 4 per cell] u_y(A) at 0.02 s %.4f m (FEM -1.1498), energy kept %.3f\n", r.uy[20],
              r.total.back() / r.total.front());
}

TEST(Mpm3d, RestartContinuesTheRunBitForBit) {
  const std::string scene = std::string(LOOM_SOURCE_DIR) + "/scenes/column_twisting_mpm.toml";
  const std::vector<std::string> sets = {"--set", "time.steps=6", "--set", "body[0].particles_per_cell=4", "--set", "output.every=3",
                                         "--set", "body[0].mesh.divisions=[2,2,12]", "--set", "grid.divisions=[8,8,14]"};
  testing::TempDir whole("mpm_3d_whole"), parts("mpm_3d_parts");
  auto run = [&](std::vector<std::string> args) {
    args.insert(args.end(), sets.begin(), sets.end());
    const testing::Command c = testing::run_loom(args);
    EXPECT_EQ(c.exit_code, 0) << c.err;
  };
  run({"run", scene, "--out", whole.path(), "--quiet"});
  run({"run", scene, "--out", parts.path(), "--quiet", "--stop-after", "3"});
  run({"run", scene, "--quiet", "--restart", parts.path()});
  const std::string a = testing::read_text(whole.file("probes.csv")), b = testing::read_text(parts.file("probes.csv"));
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, b);
}

}  // namespace
}  // namespace loom
