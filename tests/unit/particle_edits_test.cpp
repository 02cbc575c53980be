// Particle insertion and removal in the PFEM remesh stage (engine/methods/pfem/particle_edits, particle_set), on an
// 8 x 4 block of es_pfem's smoothed u-p triangles and of pfem's p1 triangles:
//  - insertion at the midpoints of long edges interpolates every nodal field linearly, so a linear field (here a
//    homogeneous deformation u = A X, velocity v = B X, pressure and J linear in X) is carried exactly, and the
//    body's area does not change (the new particles lie on edges of the old mesh);
//  - removal of an interior particle that came too close to a neighbour leaves the area exactly as it was and the
//    remaining particles' fields untouched; a surface particle goes only into its neighbour along the surface;
//  - particles with a prescribed displacement are never removed;
//  - near a wall with a spacing of its own the spacing is graded, and the edits refine there only; a longer ramp
//    makes the first row next to the wall follow its spacing;
//  - the renumbered model is consistent: cells on particles only, every cell counter-clockwise, dofs rebuilt.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/mesh/triangle_geometry.hpp"
#include "engine/methods/model/fem_model.hpp"
#include "engine/methods/pfem/pfem_remesh.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

std::string block_scene(const std::string& method, const std::string& element, const std::string& extra) {
  return "[scene]\nname = \"edits\"\nmethod = \"" + method + "\"\n"
         "[time]\nintegrator = \"bossak\"\ndt = 1e-3\nsteps = 1\n"
         "[[material]]\nname = \"m\"\nmodel = \"" + std::string(element == "es_up" ? "hencky_perzyna" : "neo_hooke") +
         "\"\nE = 1e5\nnu = 0.3\ndensity = 1000.0\n"
         "[[body]]\nname = \"b\"\nmaterial = \"m\"\nelement = \"" + element + "\"\n" + (element == "es_up" ? "alpha_stab = 200.0\n" : "") +
         "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [0.2, 0.1], divisions = [8, 4], pattern = \"alternating\" }\n"
         "[output]\nevery = 0\n" + extra;
}

const Eigen::Matrix2d kA = (Eigen::Matrix2d() << 0.3, 0.05, -0.02, 0.1).finished();  // u = A X (stretches x by 1.3)
const Eigen::Matrix2d kB = (Eigen::Matrix2d() << 0.7, -0.4, 0.2, 0.5).finished();    // v = B X

PfemSettings settings_of(const FemModel& m, double insert_above, double remove_below) {
  PfemSettings s;
  s.remesh = {m.scene.pfem.alpha, m.scene.pfem.lchar, m.scene.pfem.local, SurfaceMode::constrained};
  s.edits = {insert_above, remove_below};
  return s;
}

double area(const FemModel& m) {
  double a = 0.0;
  for (const Cells& cb : m.cells)
    for (Index c = 0; c < cb.size(); ++c) a += signed_area(m.nodes.position_n(cb.node(c, 0)), m.nodes.position_n(cb.node(c, 1)), m.nodes.position_n(cb.node(c, 2)));
  return a;
}

// Remeshes with `s`'s edits until a pass inserts and removes nothing, at most max_passes times; the passes made.
int remesh_until_settled(const PfemSettings& s, PfemTopology& topo, FemModel& m, int max_passes) {
  Timers timers;
  int passes = 0;
  for (Index changed = 1; changed > 0 && passes < max_passes; ++passes) {
    const RemeshReport r = remesh_model(s, 0.0, topo, m, timers);
    changed = r.inserted + r.removed;
  }
  return passes;
}

void expect_consistent(const FemModel& m, const PfemTopology& topo) {
  for (const Cells& cb : m.cells)
    for (Index c = 0; c < cb.size(); ++c) {
      for (int a = 0; a < 3; ++a) EXPECT_LT(cb.node(c, a), topo.n_points);
      EXPECT_GT(signed_area(m.nodes.position_n(cb.node(c, 0)), m.nodes.position_n(cb.node(c, 1)), m.nodes.position_n(cb.node(c, 2))), 0.0);
    }
  EXPECT_EQ(m.node_body.size(), std::size_t(m.nodes.size()));
  EXPECT_EQ(m.system.dofs.n_dofs(), m.nodes.size() * m.system.dofs.per_node);
}

class ParticleInsertion : public ::testing::TestWithParam<std::pair<const char*, const char*>> {};

TEST_P(ParticleInsertion, CarriesLinearFieldsExactlyAndKeepsTheArea) {
  const auto [method, element] = GetParam();
  FemModel m(testing::scene_from_text(block_scene(method, element, "")));
  PfemTopology topo = initial_topology(m);
  const double h0 = topo.spacing[0];
  // A homogeneous deformation: every nodal field linear in X.
  for (Index i = 0; i < m.nodes.size(); ++i) {
    const Vec2 X = m.nodes.X[i];
    m.nodes.u_n[i] = m.nodes.u[i] = kA * X;
    m.nodes.v_n[i] = kB * X;
    if (m.nodes.p_n.used()) m.nodes.p_n[i] = m.nodes.p[i] = 3.0 + 2.0 * X.x() - X.y();
    if (m.nodes.J_node.used()) m.nodes.J_node[i] = 1.0 + 0.1 * X.x();
  }
  const double area_before = area(m);
  Index long_edges = 0;  // edges of the deformed mesh longer than 1.2 h0
  {
    std::set<std::pair<Index, Index>> seen;
    for (std::size_t t = 0; t < topo.triangles[0].size(); t += 3)
      for (int e = 0; e < 3; ++e) {
        const Index a = topo.triangles[0][t + std::size_t(e)], b = topo.triangles[0][t + std::size_t((e + 1) % 3)];
        if (seen.insert({std::min(a, b), std::max(a, b)}).second && (m.nodes.position_n(a) - m.nodes.position_n(b)).norm() > 1.2 * h0) ++long_edges;
      }
  }
  ASSERT_GT(long_edges, 0);
  const Index n_before = topo.n_points;
  Timers timers;
  const RemeshReport r = remesh_model(settings_of(m, 1.2, 0.0), 0.0, topo, m, timers);
  EXPECT_TRUE(r.changed);
  EXPECT_EQ(r.inserted, long_edges);
  EXPECT_EQ(r.removed, 0);
  EXPECT_EQ(topo.n_points, n_before + long_edges);
  EXPECT_EQ(r.isolated, 0);
  EXPECT_NEAR(area(m), area_before, 1e-14);
  double worst = 0.0;
  for (Index i = 0; i < topo.n_points; ++i) {
    const Vec2 X = m.nodes.X[i];
    worst = std::max(worst, (m.nodes.u_n[i] - kA * X).norm() + (m.nodes.v_n[i] - kB * X).norm());
    if (m.nodes.p_n.used()) worst = std::max(worst, std::abs(m.nodes.p_n[i] - (3.0 + 2.0 * X.x() - X.y())));
    if (m.nodes.J_node.used()) worst = std::max(worst, std::abs(m.nodes.J_node[i] - (1.0 + 0.1 * X.x())));
  }
  EXPECT_LT(worst, 1e-15);
  expect_consistent(m, topo);
  // Idempotent: nothing is long any more.
  EXPECT_EQ(remesh_model(settings_of(m, 1.2, 0.0), 0.0, topo, m, timers).inserted, 0);
}

INSTANTIATE_TEST_SUITE_P(Methods, ParticleInsertion,
                         ::testing::Values(std::make_pair("es_pfem", "es_up"), std::make_pair("pfem", "p1")));

// Near a wall with a spacing of its own, h0 is graded: h_w on the wall, growing linearly to h0 one h0 away. The
// undeformed block has no edge too long for h0; with the ground graded to 0.4 h0, repeated remeshes split edges
// near it, only there (every new particle within h0 of it), until every edge is within insert_above times the
// spacing at its midpoint, and none is below remove_below times it; the body's area stays what it was.
TEST(ParticleInsertion, GradedNearAWallRefinesOnlyNearItUntilEveryEdgeFitsTheLocalSpacing) {
  FemModel m(testing::scene_from_text(block_scene("es_pfem", "es_up", "")));
  PfemTopology topo = initial_topology(m);
  const double h0 = topo.spacing[0];
  PfemSettings s = settings_of(m, 1.7, 0.3);
  s.edits.graded = {{Vec2(0.0, 0.0), Vec2(0.0, 1.0), 0.4 * h0, kNoIndex}};
  EXPECT_DOUBLE_EQ(local_spacing(s.edits, 0, h0, Vec2(0.1, 0.0)), 0.4 * h0);
  EXPECT_DOUBLE_EQ(local_spacing(s.edits, 0, h0, Vec2(0.1, -0.01)), 0.4 * h0);  // behind the wall: its own spacing
  EXPECT_DOUBLE_EQ(local_spacing(s.edits, 0, h0, Vec2(0.1, 0.5 * h0)), 0.7 * h0);
  EXPECT_EQ(local_spacing(s.edits, 0, h0, Vec2(0.1, h0)), h0);  // beyond the ramp: exactly h0
  EXPECT_EQ(local_spacing(s.edits, 0, h0, Vec2(0.1, 2.0 * h0)), h0);
  Timers timers;
  ASSERT_EQ(remesh_model(settings_of(m, 1.7, 0.3), 0.0, topo, m, timers).inserted, 0);  // ungraded: nothing to do
  // A wall graded for another body changes nothing for this one.
  PfemSettings other = settings_of(m, 1.7, 0.3);
  other.edits.graded = {{Vec2(0.0, 0.0), Vec2(0.0, 1.0), 0.4 * h0, 1}};
  EXPECT_EQ(local_spacing(other.edits, 0, h0, Vec2(0.1, 0.0)), h0);
  const RemeshReport r_other = remesh_model(other, 0.0, topo, m, timers);
  ASSERT_EQ(r_other.inserted + r_other.removed, 0);
  const double area_before = area(m);
  const Index n_before = topo.n_points;
  ASSERT_LT(remesh_until_settled(s, topo, m, 10), 10);
  ASSERT_GT(topo.n_points, n_before);
  for (Index i = n_before; i < topo.n_points; ++i) EXPECT_LT(m.nodes.position_n(i).y(), h0);
  std::set<std::pair<Index, Index>> seen;
  for (std::size_t t = 0; t < topo.triangles[0].size(); t += 3)
    for (int e = 0; e < 3; ++e) {
      const Index a = topo.triangles[0][t + std::size_t(e)], b = topo.triangles[0][t + std::size_t((e + 1) % 3)];
      if (!seen.insert({std::min(a, b), std::max(a, b)}).second) continue;
      const Vec2 xa = m.nodes.position_n(a), xb = m.nodes.position_n(b);
      const double h = local_spacing(s.edits, 0, h0, 0.5 * (xa + xb));
      EXPECT_LE((xa - xb).norm(), 1.7 * h);
      EXPECT_GE((xa - xb).norm(), 0.3 * h);
    }
  EXPECT_NEAR(area(m), area_before, 1e-14);
  expect_consistent(m, topo);
}

// The height of the first row: the highest particle joined by an edge to one on the wall y = 0, after remeshing
// with `s`'s insertions until nothing changes.
double first_row_height(const std::string& scene, const PfemSettings& s) {
  FemModel m(testing::scene_from_text(scene));
  PfemTopology topo = initial_topology(m);
  EXPECT_LT(remesh_until_settled(s, topo, m, 12), 12);
  double highest = 0.0;
  for (std::size_t t = 0; t < topo.triangles[0].size(); t += 3)
    for (int e = 0; e < 3; ++e) {
      const Vec2 xa = m.nodes.position_n(topo.triangles[0][t + std::size_t(e)]);
      const Vec2 xb = m.nodes.position_n(topo.triangles[0][t + std::size_t((e + 1) % 3)]);
      if (std::abs(xa.y()) < 1e-12) highest = std::max(highest, xb.y());
      if (std::abs(xb.y()) < 1e-12) highest = std::max(highest, xa.y());
    }
  return highest;
}

// spacing_ramp: the spacing grows from s on the wall to h0 over the ramp instead of over h0. An edge from the wall
// to height y is split unless y <= 1.7 (s + g y / 2), g = (h0 - s) / ramp, so the first row stays below
// 1.7 s / (1 - 0.85 g): over one h0 with s = h0 / 4 that is 1.17 h0, not below the block's own rows, over 3 h0 it is
// 0.54 h0. The graded block's first row must come out within that bound, below the default ramp's.
TEST(ParticleInsertion, ALongerRampMakesTheFirstRowNextToTheWallFollowItsSpacing) {
  const std::string scene = block_scene("es_pfem", "es_up", "");
  FemModel m(testing::scene_from_text(scene));
  const double h0 = initial_topology(m).spacing[0], s_w = 0.25 * h0, ramp = 3.0 * h0;
  PfemSettings one = settings_of(m, 1.7, 0.3), three = settings_of(m, 1.7, 0.3);
  one.edits.graded = {{Vec2(0.0, 0.0), Vec2(0.0, 1.0), s_w, kNoIndex}};
  three.edits.graded = {{Vec2(0.0, 0.0), Vec2(0.0, 1.0), s_w, kNoIndex, ramp}};
  EXPECT_DOUBLE_EQ(local_spacing(three.edits, 0, h0, Vec2(0.1, 0.0)), s_w);
  EXPECT_DOUBLE_EQ(local_spacing(three.edits, 0, h0, Vec2(0.1, 1.5 * h0)), s_w + 0.5 * (h0 - s_w));
  EXPECT_EQ(local_spacing(three.edits, 0, h0, Vec2(0.1, ramp)), h0);
  EXPECT_DOUBLE_EQ(local_spacing(one.edits, 0, h0, Vec2(0.1, 0.5 * h0)), s_w + 0.5 * (h0 - s_w));
  const double bound = 1.7 * s_w / (1.0 - 0.85 * (h0 - s_w) / ramp);
  const double y_one = first_row_height(scene, one), y_three = first_row_height(scene, three);
  EXPECT_LE(y_three, bound * (1.0 + 1e-12));
  EXPECT_LT(y_three, 0.75 * y_one);
}

// An interior particle moved to within 0.15 h0 of its neighbour: it (or the neighbour) goes, the other particles
// keep their values, the union of the triangles (the body) is unchanged.
TEST(ParticleRemoval, RemovesOneOfTwoCloseInteriorParticlesAndKeepsTheBody) {
  FemModel m(testing::scene_from_text(block_scene("es_pfem", "es_up", "")));
  PfemTopology topo = initial_topology(m);
  const double h0 = topo.spacing[0];
  Index mover = kNoIndex, target = kNoIndex;
  for (Index i = 0; i < topo.n_points; ++i) {
    if (std::abs(m.nodes.X[i].x() - 0.1) < 1e-12 && std::abs(m.nodes.X[i].y() - 0.05) < 1e-12) mover = i;
    if (std::abs(m.nodes.X[i].x() - 0.125) < 1e-12 && std::abs(m.nodes.X[i].y() - 0.05) < 1e-12) target = i;
  }
  ASSERT_NE(mover, kNoIndex);
  ASSERT_NE(target, kNoIndex);
  m.nodes.u_n[mover] = m.nodes.u[mover] = 0.85 * (m.nodes.X[target] - m.nodes.X[mover]);
  for (Index i = 0; i < m.nodes.size(); ++i) m.nodes.v_n[i] = kB * m.nodes.X[i];
  const double area_before = area(m);
  Timers timers;
  const Index n_before = topo.n_points;
  const RemeshReport r = remesh_model(settings_of(m, 0.0, 0.3), 0.0, topo, m, timers);
  EXPECT_EQ(r.removed, 1);
  EXPECT_EQ(topo.n_points, n_before - 1);
  EXPECT_NEAR(area(m), area_before, 1e-15);
  for (Index i = 0; i < topo.n_points; ++i) EXPECT_EQ(m.nodes.v_n[i], kB * m.nodes.X[i]);  // the others untouched
  expect_consistent(m, topo);
  EXPECT_LT(0.15 * h0, 0.3 * h0);
}

// A particle on the bottom surface moved next to its neighbour along the surface goes into it; the same
// particle held by a Dirichlet boundary stays.
TEST(ParticleRemoval, TakesASurfaceParticleIntoItsSurfaceNeighbourButNeverAHeldOne) {
  for (const bool held : {false, true}) {
    const std::string bc = held ? "[[boundary]]\nname = \"base\"\nregion = { box = [[0.0, 0.0], [0.2, 0.0]] }\ndisplacement = { y = 0.0 }\n" : "";
    FemModel m(testing::scene_from_text(block_scene("es_pfem", "es_up", bc)));
    PfemTopology topo = initial_topology(m);
    Index mover = kNoIndex, target = kNoIndex;
    for (Index i = 0; i < topo.n_points; ++i) {
      if (std::abs(m.nodes.X[i].x() - 0.1) < 1e-12 && m.nodes.X[i].y() == 0.0) mover = i;
      if (std::abs(m.nodes.X[i].x() - 0.125) < 1e-12 && m.nodes.X[i].y() == 0.0) target = i;
    }
    ASSERT_NE(mover, kNoIndex);
    m.nodes.u_n[mover] = m.nodes.u[mover] = 0.9 * (m.nodes.X[target] - m.nodes.X[mover]);
    const double area_before = area(m);
    Timers timers;
    const RemeshReport r = remesh_model(settings_of(m, 0.0, 0.3), 0.0, topo, m, timers);
    EXPECT_EQ(r.removed, held ? 0 : 1) << (held ? "held" : "free");
    EXPECT_NEAR(area(m), area_before, 1e-15);  // the surface stays a straight line
    expect_consistent(m, topo);
  }
}

}  // namespace
}  // namespace loom
