// The PFEM remesh stage (engine/methods/pfem/pfem_remesh): on the stores FemModel builds from
// scenes/constrained_block_pfem.toml (8 x 4 shifted grid on [0, 2] x [0, 1], whose cells are the Delaunay
// triangles of their points), with the history F_n written by hand:
//  - an unchanged point cloud changes nothing: same cells in the same order, F_n bit for bit, no
//    transfer (p1, p1p1_uphi: not even a rebuild; tri6: mid-nodes re-created where they were, every
//    point kept), same dofs and sparsity (the pattern version, which triggers a new symbolic
//    factorization, stays);
//  - a particle moved far enough to flip edges changes the connectivity: the cells that kept their
//    corners keep their points' F_n exactly (point by point, following the corner the point sits at),
//    the others are mapped (CPM here), and dofs and sparsity are rebuilt.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <vector>

#include "engine/methods/model/fem_model.hpp"
#include "engine/methods/pfem/pfem_remesh.hpp"
#include "engine/scene/scene_loader.hpp"

namespace loom {
namespace {

using Triple = std::array<Index, 3>;

FemModel block_model(const std::string& element) {
  return FemModel(load_scene(std::string(LOOM_SOURCE_DIR) + "/scenes/constrained_block_pfem.toml",
                             {"body[0].element=" + element, "output.every=0"}));
}

PfemSettings settings_of(const FemModel& m) {
  PfemSettings s;
  s.remesh = {m.scene.pfem.alpha, m.scene.pfem.lchar, m.scene.pfem.local};
  return s;
}

// A distinct history per point: F_n = I + 0.01 * (global point number) e_1 (x) e_2 (det 1, all different).
void label_history(FemModel& m) {
  double label = 0.0;
  for (auto& q : m.quad)
    for (Index p = 0; p < q.size(); ++p) {
      Mat3 F = Mat3::Identity();
      F(0, 1) = 0.01 * ++label;
      q.F_n[p] = q.F[p] = F;
    }
}

// Per cell: its corner triple (sorted) and the F_n of the point at each corner (3-point rules: point q
// sits nearest corner q).
std::map<Triple, std::map<Index, Mat3>> history_by_corner(const FemModel& m) {
  std::map<Triple, std::map<Index, Mat3>> h;
  for (std::size_t k = 0; k < m.cells.size(); ++k) {
    const Cells& cb = m.cells[k];
    const QuadPoints<2>& q = m.quad[k];
    for (Index c = 0; c < cb.size(); ++c) {
      Triple t{cb.node(c, 0), cb.node(c, 1), cb.node(c, 2)};
      std::map<Index, Mat3> at;
      for (int p = 0; p < q.per_cell; ++p) at[q.per_cell == 3 ? t[std::size_t(p)] : kNoIndex] = q.F_n[c * q.per_cell + p];
      std::sort(t.begin(), t.end());
      h[t] = at;
    }
  }
  return h;
}

class RemeshModelIdentity : public ::testing::TestWithParam<const char*> {};

TEST_P(RemeshModelIdentity, AnUnchangedPointCloudChangesNothing) {
  const std::string element = GetParam();
  FemModel m = block_model(element);
  label_history(m);
  PfemTopology topo = initial_topology(m);
  const std::vector<Cells> cells_before = m.cells;
  std::vector<std::vector<Mat3>> F_before;
  for (const auto& q : m.quad) F_before.emplace_back(q.F_n.begin(), q.F_n.end());
  std::vector<Vec2> x_before;
  for (Index i = 0; i < m.nodes.size(); ++i) x_before.push_back(m.nodes.position_n(i));
  const auto version = m.system.pattern.version;
  const auto kinds = m.system.dofs.kind;
  const Index n_free = m.system.dofs.n_free;
  Timers timers;

  for (int pass = 0; pass < 3; ++pass) {  // idempotent: a second and third remesh change nothing either
    const RemeshReport r = remesh_model(settings_of(m), 0.0, topo, m, timers);
    EXPECT_FALSE(r.changed);
    EXPECT_EQ(r.rejected, 0);
    EXPECT_EQ(r.isolated, 0);
    EXPECT_EQ(r.triangles, cells_before[0].size());
    EXPECT_NEAR(r.area_after, 2.0, 1e-12);
    EXPECT_EQ(r.area_after, r.area_before);
    EXPECT_EQ(r.map.copied + r.map.interpolated + r.map.fallback, 0);  // no transfer
    if (element == "tri6")
      EXPECT_EQ(r.map.kept, 3 * cells_before[0].size());  // re-created cells: every point copied from its own
    else
      EXPECT_EQ(r.map.kept, 0);                            // nothing rebuilt at all

    ASSERT_EQ(m.cells.size(), cells_before.size());
    ASSERT_EQ(m.cells[0].size(), cells_before[0].size());
    for (Index c = 0; c < m.cells[0].size(); ++c)
      for (int a = 0; a < 3; ++a) EXPECT_EQ(m.cells[0].node(c, a), cells_before[0].node(c, a)) << "cell " << c;
    for (std::size_t k = 0; k < m.quad.size(); ++k)
      for (Index p = 0; p < m.quad[k].size(); ++p) EXPECT_EQ(m.quad[k].F_n[p], F_before[k][std::size_t(p)]);
    // Nodes (tri6: the re-created mid-nodes) where they were.
    ASSERT_EQ(m.nodes.size(), Index(x_before.size()));
    for (Index c = 0; c < m.cells[0].size(); ++c)
      for (int a = 0; a < m.cells[0].stride; ++a)
        EXPECT_EQ(m.nodes.position_n(m.cells[0].node(c, a)), x_before[std::size_t(cells_before[0].node(c, a))]);
    EXPECT_EQ(m.system.pattern.version, version);
    EXPECT_EQ(m.system.dofs.kind, kinds);
    EXPECT_EQ(m.system.dofs.n_free, n_free);
  }
}

INSTANTIATE_TEST_SUITE_P(Elements, RemeshModelIdentity, ::testing::Values("p1", "p1p1_uphi", "tri6"));

class RemeshModelChange : public ::testing::TestWithParam<const char*> {};

// The particle at (1, 0.5) is moved up by 0.2 (row spacing 0.25): it enters the circumcircle of the triangle above it,
// so edges flip. alpha is raised so that no triangle is rejected (the alpha test is not under test).
TEST_P(RemeshModelChange, CellsThatKeepTheirCornersKeepTheirHistory) {
  const std::string element = GetParam();
  FemModel m = block_model(element);
  label_history(m);
  PfemTopology topo = initial_topology(m);
  Index moved = kNoIndex;
  for (Index i = 0; i < topo.n_points; ++i)
    if ((m.nodes.X[i] - Vec2(1.0, 0.5)).norm() < 1e-12) moved = i;
  ASSERT_NE(moved, kNoIndex);
  m.nodes.u_n[moved] = Vec2(0.0, 0.2);
  const auto before = history_by_corner(m);
  const auto version = m.system.pattern.version;
  PfemSettings s = settings_of(m);
  s.remesh.alpha = 100.0;
  Timers timers;
  const RemeshReport r = remesh_model(s, 0.0, topo, m, timers);

  EXPECT_TRUE(r.changed);
  EXPECT_NE(m.system.pattern.version, version);
  EXPECT_NEAR(r.area_after, 2.0, 1e-12);
  const auto after = history_by_corner(m);
  Index kept_cells = 0, new_cells = 0;
  for (const auto& [corners, at] : after) {
    const auto old = before.find(corners);
    if (old == before.end()) {
      ++new_cells;
      continue;
    }
    ++kept_cells;
    EXPECT_EQ(at.size(), old->second.size());
    for (const auto& [corner, F] : at) EXPECT_EQ(F, old->second.at(corner)) << "a point of an unchanged cell moved its history";
  }
  EXPECT_GT(new_cells, 0);
  EXPECT_EQ(r.map.kept, kept_cells * m.quad[0].per_cell);
  EXPECT_EQ(r.map.copied, new_cells * m.quad[0].per_cell);  // CPM: every point of a new cell is a copy
  EXPECT_EQ(r.map.interpolated, 0);
  std::printf("[pfem remesh] %-9s: %d cells kept their corners, %d are new\n", element.c_str(), int(kept_cells), int(new_cells));

  // A new cell's points carry values of old points (CPM copies, it does not invent).
  std::vector<Mat3> old_values;
  for (const auto& [c, at] : before)
    for (const auto& [k, F] : at) old_values.push_back(F);
  for (const auto& q : m.quad)
    for (Index p = 0; p < q.size(); ++p)
      EXPECT_NE(std::find(old_values.begin(), old_values.end(), q.F_n[p]), old_values.end());

  // The next remesh of the same positions is the identity.
  const RemeshReport again = remesh_model(s, 0.0, topo, m, timers);
  EXPECT_FALSE(again.changed);
  EXPECT_EQ(again.map.copied + again.map.interpolated + again.map.fallback, 0);
}

INSTANTIATE_TEST_SUITE_P(Elements, RemeshModelChange, ::testing::Values("p1", "p1p1_uphi", "tri6"));

}  // namespace
}  // namespace loom
