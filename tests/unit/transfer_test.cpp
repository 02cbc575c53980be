// systems/map: the particle-grid transfers of seed 003 Algorithm 1 conserve mass and momentum to round-off
// (STYLE §11 invariants): projection keeps sum m, sum m v, sum m a; interpolation after a Newmark update
// of the grid gives the particles the grid's momentum; a node held in place starts the step at rest and ends
// it at rest (a = v = 0 from the Newmark update with u = 0), so it passes the particles no velocity increment; constants and linear fields pass unchanged; the
// projection does not depend on the thread count. On tri3 and on quad4 grids.
#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/task_arena.h>

#include <random>

#include "engine/mesh/background_grid.hpp"
#include "engine/mesh/generators.hpp"
#include "systems/locate/locate_points.hpp"
#include "systems/map/interpolate_to_particles.hpp"
#include "systems/map/project_to_grid.hpp"
#include "systems/map/rest_held_grid_nodes.hpp"
#include "systems/update/grid_newmark.hpp"

namespace loom {
namespace {

struct Fixture {
  Nodes<2> nodes;
  Cells cells;
  GridLayout layout;
  Points<2> particles;
  PointLocations loc;
  StepContext ctx;

  explicit Fixture(Index n_particles, unsigned seed = 1, bool quad = false) {
    RectangleSpec spec;
    spec.size = Vec2(2.0, 1.5), spec.nx = 40, spec.ny = 30, spec.pattern = GridPattern::alternating;
    for (auto* c : {&nodes.lumped_mass}) c->use();
    for (auto* c : {&nodes.v_n, &nodes.a_n, &nodes.v, &nodes.a, &nodes.proj_u}) c->use();
    nodes.p.use(), nodes.proj_p.use();
    if (quad) build_quad_grid(spec, Formulation::p1p1_up, nodes, cells, layout);
    else build_background_grid(generate_rectangle(spec), &spec, Formulation::p1p1_up, nodes, cells, layout);
    particles.for_each_column([](const char*, auto& c) { c.use(); });
    particles.resize(n_particles);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> x(0.01, 1.99), y(0.01, 1.49), s(-1.0, 1.0), m(0.5, 2.0);
    for (Index p = 0; p < n_particles; ++p) {
      particles.X[p] = Vec2(x(rng), y(rng));
      particles.mass[p] = m(rng);
      particles.v[p] = Vec2(s(rng), s(rng));
      particles.a[p] = Vec2(s(rng), s(rng));
      particles.pressure[p] = s(rng);
      particles.proj_u[p] = Vec2(s(rng), s(rng));
      particles.proj_p[p] = s(rng);
    }
    ctx.dt = 0.01;
    locate_points(ctx, layout, cells, nodes, particles, loc);
  }
};

template <class Get>
auto particle_sum(const Fixture& f, Get get) {
  using T = decltype(get(Index(0)));
  T s = get(Index(0));
  s *= 0.0;
  for (Index p = 0; p < f.particles.X.size(); ++p) s += f.particles.mass[p] * get(p);
  return s;
}
template <class Get>
auto grid_sum(const Fixture& f, Get get) {
  using T = decltype(get(Index(0)));
  T s = get(Index(0));
  s *= 0.0;
  for (Index i = 0; i < f.nodes.size(); ++i) s += f.nodes.lumped_mass[i] * get(i);
  return s;
}

class Transfer : public ::testing::TestWithParam<bool> {};  // quad4 grid?

TEST_P(Transfer, ProjectionConservesMassAndMomentum) {
  Fixture f(5000, 1, GetParam());
  project_to_grid(f.ctx, f.cells, f.particles, f.loc, f.nodes);
  const double mass = particle_sum(f, [](Index) { return 1.0; });
  EXPECT_NEAR(grid_sum(f, [](Index) { return 1.0; }), mass, 1e-13 * mass);
  const Vec2 mv = particle_sum(f, [&](Index p) { return Vec2(f.particles.v[p]); });
  const Vec2 ma = particle_sum(f, [&](Index p) { return Vec2(f.particles.a[p]); });
  EXPECT_LE((grid_sum(f, [&](Index i) { return Vec2(f.nodes.v_n[i]); }) - mv).norm(), 1e-13 * mass);
  EXPECT_LE((grid_sum(f, [&](Index i) { return Vec2(f.nodes.a_n[i]); }) - ma).norm(), 1e-13 * mass);
  EXPECT_NEAR(grid_sum(f, [&](Index i) { return f.nodes.p[i]; }), particle_sum(f, [&](Index p) { return f.particles.pressure[p]; }), 1e-13 * mass);
}

TEST_P(Transfer, InterpolationGivesTheParticlesTheGridsMomentumAfterANewmarkStep) {
  Fixture f(5000, 2, GetParam());
  project_to_grid(f.ctx, f.cells, f.particles, f.loc, f.nodes);
  // A grid Newmark step (beta = 1/4, gamma = 1/2) with an arbitrary new acceleration.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> s(-1.0, 1.0);
  const double dt = f.ctx.dt;
  for (Index i = 0; i < f.nodes.size(); ++i) {
    f.nodes.a[i] = Vec2(s(rng), s(rng));
    f.nodes.v[i] = f.nodes.v_n[i] + 0.5 * dt * (f.nodes.a_n[i] + f.nodes.a[i]);
    f.nodes.u[i] = dt * f.nodes.v_n[i] + 0.25 * dt * dt * (f.nodes.a_n[i] + f.nodes.a[i]);
  }
  const Vec2 grid_mv = grid_sum(f, [&](Index i) { return Vec2(f.nodes.v[i]); });
  const Vec2 grid_ma = grid_sum(f, [&](Index i) { return Vec2(f.nodes.a[i]); });
  const Vec2 grid_mu = grid_sum(f, [&](Index i) { return Vec2(f.nodes.u[i]); });
  const double mass = particle_sum(f, [](Index) { return 1.0; });
  interpolate_to_particles(f.ctx, f.cells, f.nodes, f.loc, f.particles);
  EXPECT_LE((particle_sum(f, [&](Index p) { return Vec2(f.particles.v[p]); }) - grid_mv).norm(), 1e-13 * mass);
  EXPECT_LE((particle_sum(f, [&](Index p) { return Vec2(f.particles.a[p]); }) - grid_ma).norm(), 1e-13 * mass);
  EXPECT_LE((particle_sum(f, [&](Index p) { return Vec2(f.particles.u[p]); }) - grid_mu).norm(), 1e-13 * mass);
}

TEST_P(Transfer, HeldNodesStartAndEndTheStepAtRestWhileMovingOnesKeepTheProjection) {
  Fixture f(5000, 4, GetParam());
  project_to_grid(f.ctx, f.cells, f.particles, f.loc, f.nodes);
  BoundaryConditions<2> bc;
  bc.per_node = 3, bc.increments = true;  // p1p1_up: u_x, u_y, p per node
  bc.target = Eigen::VectorXd::Zero(3 * f.nodes.size());
  std::vector<char> held(std::size_t(f.nodes.size()), 0), moved(std::size_t(f.nodes.size()), 0);
  for (Index i = 0; i < f.nodes.size(); ++i) {
    const bool bottom = f.nodes.X[i].y() < 1e-12, top = f.nodes.X[i].y() > 1.5 - 1e-12;
    if (!bottom && !top) continue;
    for (int d = 0; d < 2; ++d) bc.prescribed.push_back({3 * i + d, i, 0});
    if (top) bc.target[3 * i + 0] = 1e-4, moved[std::size_t(i)] = 1;  // x moves this step, y held
    else held[std::size_t(i)] = 1;
  }
  const Nodes<2> projected = f.nodes;
  rest_held_grid_nodes(f.ctx, bc, f.nodes);
  Index n_held = 0;
  for (Index i = 0; i < f.nodes.size(); ++i) {
    if (!(f.nodes.lumped_mass[i] > 0.0)) continue;
    f.nodes.u[i] = Vec2(bc.target[3 * i], bc.target[3 * i + 1]);
    const Vec2 a = newmark_acceleration(f.nodes, i, f.ctx.dt), v = newmark_velocity(f.nodes, i, a, f.ctx.dt);
    if (held[std::size_t(i)]) {
      ++n_held;
      EXPECT_EQ(a, Vec2::Zero()) << "node " << i;
      EXPECT_EQ(v, Vec2::Zero()) << "node " << i;
    } else if (moved[std::size_t(i)]) {
      EXPECT_EQ(f.nodes.v_n[i].x(), projected.v_n[i].x()) << "node " << i;  // a prescribed motion keeps the projection
      EXPECT_EQ(f.nodes.v_n[i].y(), 0.0) << "node " << i;
    } else {
      EXPECT_EQ(f.nodes.v_n[i], projected.v_n[i]) << "node " << i;
      EXPECT_EQ(f.nodes.a_n[i], projected.a_n[i]) << "node " << i;
    }
  }
  EXPECT_GT(n_held, 10);
  // Without the rest, the projected velocity of a held node comes back reversed: v = -v_n.
  Nodes<2> g = projected;
  const Index i = [&] { for (Index k = 0;; ++k) if (held[std::size_t(k)] && g.lumped_mass[k] > 0.0) return k; }();
  g.u[i].setZero();
  EXPECT_LE((newmark_velocity(g, i, newmark_acceleration(g, i, f.ctx.dt), f.ctx.dt) + g.v_n[i]).norm(), 1e-12 * g.v_n[i].norm());
}

TEST_P(Transfer, ReproducesConstantsAndLinearFields) {
  Fixture f(3000, 4, GetParam());
  for (Index p = 0; p < f.particles.X.size(); ++p) f.particles.v[p] = Vec2(0.3, -0.7), f.particles.pressure[p] = 2.5;
  project_to_grid(f.ctx, f.cells, f.particles, f.loc, f.nodes);
  for (Index i = 0; i < f.nodes.size(); ++i) {
    if (f.nodes.lumped_mass[i] == 0.0) continue;
    EXPECT_LE((f.nodes.v_n[i] - Vec2(0.3, -0.7)).norm(), 1e-14);
    EXPECT_NEAR(f.nodes.p[i], 2.5, 1e-14);
  }
  // A linear displacement field on the grid moves every particle by its value and gives F = I + grad.
  Eigen::Matrix2d G;
  G << 0.01, -0.02, 0.03, 0.005;
  for (Index i = 0; i < f.nodes.size(); ++i) f.nodes.u[i] = G * f.nodes.X[i] + Vec2(0.1, 0.2);
  interpolate_to_particles(f.ctx, f.cells, f.nodes, f.loc, f.particles);
  for (Index p = 0; p < f.particles.X.size(); ++p) {
    EXPECT_LE((f.particles.u[p] - (G * f.particles.X[p] + Vec2(0.1, 0.2))).norm(), 1e-14);
    EXPECT_LE((f.particles.F[p].topLeftCorner<2, 2>() - (Eigen::Matrix2d::Identity() + G)).norm(), 1e-13);
  }
}

TEST_P(Transfer, ProjectionDoesNotDependOnTheThreadCount) {
  const bool quad = GetParam();
  auto project = [quad](int threads) {
    oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    oneapi::tbb::task_arena arena(threads);
    std::vector<double> out;
    arena.execute([&] {
      Fixture f(40000, 5, quad);
      project_to_grid(f.ctx, f.cells, f.particles, f.loc, f.nodes);
      for (Index i = 0; i < f.nodes.size(); ++i) out.insert(out.end(), {f.nodes.lumped_mass[i], f.nodes.v_n[i].x(), f.nodes.a_n[i].y(), f.nodes.p[i]});
    });
    return out;
  };
  const auto one = project(1), two = project(2);
  ASSERT_EQ(one.size(), two.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < one.size(); ++k) worst = std::max(worst, std::abs(one[k] - two[k]) / std::max(1.0, std::abs(one[k])));
  EXPECT_LE(worst, 1e-12);
  std::printf("[transfers] 1 vs 2 threads: worst relative difference %.1e\n", worst);
}

INSTANTIATE_TEST_SUITE_P(Grid, Transfer, ::testing::Bool(), [](const ::testing::TestParamInfo<bool>& p) { return p.param ? "quad4" : "tri3"; });

}  // namespace
}  // namespace loom
