// The history of seed 001's domains across a remesh (engine/methods/pfem/domain_transfer.hpp) on the smallest
// case that changes: a unit square whose diagonal flips from 0-2 to 1-3. Every old edge carries its own b^e,
// so that a wrong key, index or nearest-edge search shows: the four boundary edges survive and must keep
// theirs exactly; the new diagonal must take the isochoric part of the old diagonal's (the nearest old
// midpoint, the same point) and the volume from the nodal J of its two ends; the new triangles get A_n / J_e.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/methods/model/build_domains.hpp"
#include "engine/methods/pfem/domain_transfer.hpp"

namespace loom {
namespace {

Cells square(const std::vector<Index>& triangles) {
  Cells c(CellType::tri3, Formulation::es_up);
  c.nodes.values() = triangles;
  c.body.assign(Index(triangles.size() / 3), 0);
  return c;
}

Mat3 labelled(Index k) {
  Mat3 b = Mat3::Identity();
  b(0, 0) = 1.0 + 0.1 * double(k + 1), b(1, 1) = 1.0 / (1.0 + 0.05 * double(k)), b(0, 1) = b(1, 0) = 0.02 * double(k);
  b(2, 2) = 1.0 + 0.01 * double(k);
  return b;
}

TEST(DomainTransfer, SurvivorsKeepTheirHistoryAndANewEdgeTakesTheNearestWithTheNodalVolume) {
  Nodes<2> nodes;
  nodes.J_node.use();
  nodes.resize(4);
  nodes.X[0] = Vec2(0, 0), nodes.X[1] = Vec2(1, 0), nodes.X[2] = Vec2(1, 1), nodes.X[3] = Vec2(0, 1);
  nodes.J_node[0] = 1.0, nodes.J_node[1] = 1.2, nodes.J_node[2] = 1.1, nodes.J_node[3] = 1.4;

  std::vector<Cells> cells{square({0, 1, 2, 0, 2, 3})};
  set_reference_areas(nodes, cells);
  std::vector<Edges<2>> edges;
  build_domains(nodes, cells, {0}, edges);
  std::map<std::pair<Index, Index>, Mat3> old_be;
  Index label = 0;
  for (Edges<2>& e : edges)
    for (Index k = 0; k < e.size(); ++k) {
      e.be_n[k] = labelled(label++);
      const Index a = e.stencil.node(k, 0), b = e.stencil.node(k, 1);
      old_be[{std::min(a, b), std::max(a, b)}] = e.be_n[k];
    }
  ASSERT_EQ(old_be.size(), 5u);

  const DomainSnapshot<2> snapshot = snapshot_domains(edges, cells);
  std::vector<Cells> flipped{square({0, 1, 3, 1, 2, 3})};
  const DomainTransferStats stats = transfer_domains(snapshot, nodes, flipped, {0}, edges);
  EXPECT_EQ(stats.kept, 4);
  EXPECT_EQ(stats.projected, 1);
  int seen = 0;
  for (const Edges<2>& e : edges)
    for (Index k = 0; k < e.size(); ++k) {
      ++seen;
      const Index a = std::min(e.stencil.node(k, 0), e.stencil.node(k, 1)), b = std::max(e.stencil.node(k, 0), e.stencil.node(k, 1));
      EXPECT_EQ(e.be[k], e.be_n[k]);
      if (a == 1 && b == 3) {
        const Mat3& from = old_be.at({0, 2});
        const double J = 0.5 * (1.2 + 1.4);
        EXPECT_NEAR(std::sqrt(e.be_n[k].determinant()), J, 1e-14);
        EXPECT_LT((e.be_n[k] / std::cbrt(e.be_n[k].determinant()) - from / std::cbrt(from.determinant())).norm(), 1e-14);
      } else {
        EXPECT_EQ(e.be_n[k], old_be.at({a, b})) << "edge " << a << "-" << b;
      }
    }
  EXPECT_EQ(seen, 5);
  EXPECT_NEAR(flipped[0].measure[0], 0.5 / ((1.0 + 1.2 + 1.4) / 3.0), 1e-15);
  EXPECT_NEAR(flipped[0].measure[1], 0.5 / ((1.2 + 1.1 + 1.4) / 3.0), 1e-15);
}

}  // namespace
}  // namespace loom
