// The history of the face-smoothed domains across a 3D remesh (engine/methods/pfem/domain_transfer.hpp with D = 3) on
// the smallest change a 3D remesh makes: a 2-3 flip, two tetrahedra on the face abc replaced by three around the edge
// de. The six outer faces survive, the face abc goes and the faces ade, bde, cde are new.
//  - Every old face carries its own b^e, so that a wrong key, index or nearest-face search shows: survivors keep
//    theirs exactly; a new face takes the isochoric part of the nearest old face's (closest centroid) and the volume
//    from the nodal J of its three nodes; the new tetrahedra get V_n / J_e (a static run).
//  - A body deformed homogeneously (x = F X, b^e = F F^T everywhere) in a dynamic run (lumped masses): the three new
//    tetrahedra tile what the two old ones held, so they get their reference volumes V(X) and the new faces b^e =
//    F F^T again, J = det F exact: the remesh changes nothing a homogeneous state does not already say.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "engine/mesh/tet_mesh.hpp"
#include "engine/methods/model/build_domains.hpp"
#include "engine/methods/pfem/domain_transfer.hpp"

namespace loom {
namespace {

using Face = std::array<Index, 3>;

// a, b, c and the apexes d (above) and e (below); the segment de pierces abc, so both meshes are valid.
Nodes<3> five_points() {
  Nodes<3> nodes;
  nodes.J_node.use();
  nodes.resize(5);
  nodes.X[0] = Vec3(0, 0, 0), nodes.X[1] = Vec3(1, 0.1, 0), nodes.X[2] = Vec3(0.3, 1, 0.05);
  nodes.X[3] = Vec3(0.4, 0.35, 0.9), nodes.X[4] = Vec3(0.35, 0.3, -0.8);
  return nodes;
}

// Corner quadruples, each turned positive at x_n.
Cells tets(const Nodes<3>& nodes, std::vector<std::array<Index, 4>> quads) {
  Cells c(CellType::tet4, Formulation::es_up);
  for (auto& q : quads) {
    if (tet_volume(nodes.position_n(q[0]), nodes.position_n(q[1]), nodes.position_n(q[2]), nodes.position_n(q[3])) < 0.0) std::swap(q[2], q[3]);
    c.nodes.values().insert(c.nodes.values().end(), q.begin(), q.end());
  }
  c.body.assign(Index(quads.size()), 0);
  return c;
}

const std::vector<std::array<Index, 4>> kBefore{{0, 1, 2, 3}, {0, 1, 2, 4}};
const std::vector<std::array<Index, 4>> kAfter{{0, 1, 3, 4}, {1, 2, 3, 4}, {2, 0, 3, 4}};

double volume_n(const Nodes<3>& n, const Cells& c, Index t) {
  const Index* v = c.cell_nodes(t);
  return tet_volume(n.position_n(v[0]), n.position_n(v[1]), n.position_n(v[2]), n.position_n(v[3]));
}

double volume_0(const Nodes<3>& n, const Cells& c, Index t) {
  const Index* v = c.cell_nodes(t);
  return tet_volume(n.X[v[0]], n.X[v[1]], n.X[v[2]], n.X[v[3]]);
}

Face face_of(const Edges<3>& e, Index k) {
  Face f{e.stencil.node(k, 0), e.stencil.node(k, 1), e.stencil.node(k, 2)};
  std::sort(f.begin(), f.end());
  return f;
}

Mat3 labelled(Index k) {
  Mat3 b = Mat3::Identity();
  b(0, 0) = 1.0 + 0.1 * double(k + 1), b(1, 1) = 1.0 / (1.0 + 0.05 * double(k)), b(0, 1) = b(1, 0) = 0.02 * double(k);
  b(2, 2) = 1.0 + 0.01 * double(k), b(0, 2) = b(2, 0) = -0.01 * double(k);
  return b;
}

Mat3 isochoric(const Mat3& b) { return b / std::cbrt(b.determinant()); }

TEST(DomainTransfer3d, TwoThreeFlipKeepsSurvivorsAndProjectsTheNewFaces) {
  Nodes<3> nodes = five_points();
  for (Index i = 0; i < 5; ++i) nodes.u_n[i] = Vec3(0.02 * nodes.X[i].y(), -0.03 * nodes.X[i].z(), 0.01 * nodes.X[i].x());
  const double J[5] = {1.0, 1.2, 1.1, 1.4, 0.9};
  for (Index i = 0; i < 5; ++i) nodes.J_node[i] = J[i];

  std::vector<Cells> cells{tets(nodes, kBefore)};
  set_reference_areas(nodes, cells);
  std::vector<Edges<3>> edges;
  build_domains(nodes, cells, {0}, edges);
  std::map<Face, Mat3> old_be;
  std::map<Face, Vec3> old_centroid;
  Index label = 0;
  for (Edges<3>& e : edges)
    for (Index k = 0; k < e.size(); ++k) {
      e.be_n[k] = labelled(label++);
      old_be[face_of(e, k)] = e.be_n[k];
      old_centroid[face_of(e, k)] = e.midpoint[k];
    }
  ASSERT_EQ(old_be.size(), 7u);

  const DomainSnapshot<3> snapshot = snapshot_domains(edges, cells);
  std::vector<Cells> flipped{tets(nodes, kAfter)};
  const DomainTransferStats stats = transfer_domains(snapshot, nodes, flipped, {0}, edges);
  EXPECT_EQ(stats.kept, 6);
  EXPECT_EQ(stats.projected, 3);
  int seen = 0;
  for (const Edges<3>& e : edges)
    for (Index k = 0; k < e.size(); ++k, ++seen) {
      const Face f = face_of(e, k);
      EXPECT_EQ(e.be[k], e.be_n[k]);
      if (old_be.count(f)) {
        EXPECT_EQ(e.be_n[k], old_be.at(f)) << "face " << f[0] << f[1] << f[2];
        continue;
      }
      EXPECT_EQ(f[1], 3);  // a new face: one of a, b, c with d and e
      EXPECT_EQ(f[2], 4);
      const auto nearest = std::min_element(old_centroid.begin(), old_centroid.end(), [&](const auto& p, const auto& q) {
        return (p.second - e.midpoint[k]).squaredNorm() < (q.second - e.midpoint[k]).squaredNorm();
      });
      EXPECT_NEAR(std::sqrt(e.be_n[k].determinant()), (J[f[0]] + J[3] + J[4]) / 3.0, 1e-14);
      EXPECT_LT((isochoric(e.be_n[k]) - isochoric(old_be.at(nearest->first))).norm(), 1e-14);
    }
  EXPECT_EQ(seen, 9);
  ASSERT_EQ(flipped[0].size(), 3);
  for (Index t = 0; t < 3; ++t) {
    const Index* v = flipped[0].cell_nodes(t);
    const double J_e = (J[v[0]] + J[v[1]] + J[v[2]] + J[v[3]]) / 4.0;
    EXPECT_NEAR(flipped[0].measure[t], volume_n(nodes, flipped[0], t) / J_e, 1e-15);
  }
}

TEST(DomainTransfer3d, HomogeneousDeformationPassesAFlipExactly) {
  Nodes<3> nodes = five_points();
  Mat3 F;
  F << 1.2, 0.1, -0.05, 0.03, 0.95, 0.2, 0.0, -0.1, 1.1;
  for (Index i = 0; i < 5; ++i) nodes.u_n[i] = (F - Mat3::Identity()) * nodes.X[i], nodes.J_node[i] = F.determinant();
  const double rho = 2300.0;
  nodes.lumped_mass.use();
  nodes.resize(5);

  std::vector<Cells> cells{tets(nodes, kBefore)};
  cells[0].measure.use();
  cells[0].measure.resize(2);
  for (Index t = 0; t < 2; ++t) {
    cells[0].measure[t] = volume_0(nodes, cells[0], t);
    for (int a = 0; a < 4; ++a) nodes.lumped_mass[cells[0].node(t, a)] += rho * cells[0].measure[t] / 4.0;
  }
  std::vector<Edges<3>> edges;
  build_domains(nodes, cells, {0}, edges);
  const Mat3 b = F * F.transpose();
  for (Edges<3>& e : edges)
    for (Index k = 0; k < e.size(); ++k) e.be_n[k] = e.be[k] = b;

  const DomainSnapshot<3> snapshot = snapshot_domains(edges, cells);
  std::vector<Cells> flipped{tets(nodes, kAfter)};
  const std::vector<double> density{rho};
  const DomainTransferStats stats = transfer_domains(snapshot, nodes, flipped, {0}, edges, &density);
  EXPECT_EQ(stats.projected, 3);
  double mass = 0.0;
  for (Index t = 0; t < 3; ++t) {
    EXPECT_NEAR(flipped[0].measure[t], volume_0(nodes, flipped[0], t), 1e-15) << "tetrahedron " << t;
    EXPECT_NEAR(volume_n(nodes, flipped[0], t) / flipped[0].measure[t], F.determinant(), 1e-14);
    mass += rho * flipped[0].measure[t];
  }
  double particles = 0.0;
  for (Index i = 0; i < 5; ++i) particles += nodes.lumped_mass[i];
  EXPECT_NEAR(mass, particles, 1e-14 * mass);
  for (const Edges<3>& e : edges)
    for (Index k = 0; k < e.size(); ++k) EXPECT_LT((e.be_n[k] - b).norm(), 1e-14 * b.norm()) << "face " << k;
}

}  // namespace
}  // namespace loom
