// The face-based smoothing domains of linear tetrahedra (engine/mesh/smoothing_faces, the 3D geometry of
// systems/assemble/smoothing_geometry): counts (faces = (4T + B) / 2), stencil order (slots 0-2 a face seen from
// outside its first tetrahedron, the opposite vertices after it), volumes that tile the body, smoothed gradients
// that are linearly complete per domain (sum_I b~_I = 0, sum_I x_I (x) b~_I = I: an affine field's gradient is
// exact), valid colours, and the errors a broken mesh gets.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <set>
#include <vector>

#include "engine/core/errors.hpp"
#include "engine/mesh/cell_domains.hpp"
#include "engine/mesh/smoothing_faces.hpp"
#include "engine/mesh/tet_adjacency.hpp"
#include "engine/mesh/tet_generators.hpp"
#include "engine/store/nodes.hpp"
#include "systems/assemble/smoothing_geometry.hpp"

namespace loom {
namespace {

struct Mesh {
  Nodes<3> nodes;
  Cells cells{CellType::tet4, Formulation::es_up};
  Index n_nodes() const { return nodes.size(); }
};

Mesh make_mesh(const TetMeshData& data) {
  Mesh m;
  m.nodes.X.values() = data.X;
  m.nodes.resize(Index(data.X.size()));
  m.cells.nodes.values() = data.tets;
  m.cells.body.assign(data.n_tets(), 0);
  return m;
}

// The distorted Kuhn box and the BCC lattice, both with a displacement u_n so that B_n is not the reference.
std::vector<Mesh> meshes() {
  BoxSpec spec;
  spec.size = Vec3(1.0, 0.8, 1.2);
  spec.nx = 4, spec.ny = 3, spec.nz = 3;
  TetMeshData kuhn = generate_box(spec);
  EXPECT_GT(distort_interior_nodes(kuhn, 0.3, 5), 0.2);
  std::vector<Mesh> out;
  out.push_back(make_mesh(kuhn));
  out.push_back(make_mesh(generate_bcc_box(spec)));
  for (Mesh& m : out)
    for (Index i = 0; i < m.nodes.size(); ++i) {
      const Vec3 X = m.nodes.X[i];
      m.nodes.u_n[i] = Vec3(0.05 * X.y() * X.z(), -0.03 * X.x(), 0.02 * X.x() * X.y());
    }
  return out;
}

double tet_volume_n(const Mesh& m, Index t) {
  const Index* c = m.cells.cell_nodes(t);
  return tet_volume(m.nodes.position_n(c[0]), m.nodes.position_n(c[1]), m.nodes.position_n(c[2]), m.nodes.position_n(c[3]));
}

// sum_I b~_I = 0, sum_I x_I (x) b~_I = I and the affine field u = A x + c has gradient A, for every domain.
void expect_linearly_complete(const Mesh& m, const Edges<3>& e) {
  const int S = e.stride();
  const Mat3 A = (Mat3() << 0.3, -0.2, 0.7, 0.1, 0.5, -0.4, 0.9, 0.2, -0.6).finished();
  const Vec3 c(0.2, -1.0, 0.5);
  for (Index k = 0; k < e.size(); ++k) {
    const auto b = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3>>(e.gradient(k), S, 3);
    Vec3 sum = Vec3::Zero();
    Mat3 xb = Mat3::Zero(), ub = Mat3::Zero();
    for (int I = 0; I < S; ++I) {
      const Vec3 x = m.nodes.position_n(e.stencil.node(k, I));
      sum += b.row(I).transpose();
      xb += x * b.row(I);
      ub += (A * x + c) * b.row(I);
    }
    const double scale = b.cwiseAbs().maxCoeff();
    ASSERT_LE(sum.norm(), 1e-14 * scale) << "domain " << k;
    ASSERT_LE((xb - Mat3::Identity()).norm(), 1e-14 * scale) << "domain " << k;
    ASSERT_LE((ub - A).norm(), 1e-14 * scale * A.norm()) << "domain " << k;
  }
}

// No two domains of one colour share a node.
void expect_valid_colours(const Edges<3>& e, Index n_nodes) {
  std::vector<Index> stamp(std::size_t(n_nodes), kNoIndex);
  for (Index colour = 0; colour < e.stencil.n_colours(); ++colour)
    for (Index i = e.stencil.colour_offsets[std::size_t(colour)]; i < e.stencil.colour_offsets[std::size_t(colour) + 1]; ++i) {
      const Index k = e.stencil.by_colour[std::size_t(i)];
      for (int I = 0; I < e.stride(); ++I) {
        const Index n = e.stencil.node(k, I);
        ASSERT_NE(stamp[std::size_t(n)], colour) << "node " << n << " twice in colour " << colour;
        stamp[std::size_t(n)] = colour;
      }
    }
}

}  // namespace

TEST(SmoothingFaces, CountsAndStencilOrder) {
  for (const Mesh& m : meshes()) {
    const FaceDomains d = build_face_domains(m.cells, m.n_nodes());
    const Index T = m.cells.size(), B = Index(boundary_faces(m.cells.nodes.values()).size());
    EXPECT_EQ(d.interior.stride(), 5);
    EXPECT_EQ(d.boundary.stride(), 4);
    EXPECT_EQ(d.boundary.size(), B);
    EXPECT_EQ(2 * (d.interior.size() + d.boundary.size()), 4 * T + B);
    for (const Edges<3>* e : {&d.interior, &d.boundary})
      for (Index k = 0; k < e->size(); ++k) {
        const Index* s = e->stencil.cell_nodes(k);
        // Slots 0-2 seen from outside the first tetrahedron: its opposite vertex (slot 3) lies behind the face,
        // and the second one's (slot 4) in front of it.
        const auto side = [&](Index n) {
          return tet_volume(m.nodes.X[s[0]], m.nodes.X[s[1]], m.nodes.X[s[2]], m.nodes.X[n]);
        };
        EXPECT_LT(side(s[3]), 0.0) << "domain " << k;
        if (e->stride() == 5) {
          EXPECT_GT(side(s[4]), 0.0) << "domain " << k;
        }
        EXPECT_EQ(e->triangles[2 * k + 1] != kNoIndex, e->stride() == 5);
        double w = 0.0;
        for (int I = 0; I < e->stride(); ++I) w += e->pressure_weight[k * e->stride() + I];
        EXPECT_DOUBLE_EQ(w, 1.0);
        EXPECT_EQ(e->pressure_weight[k * e->stride() + 3], 0.0);
      }
  }
}

TEST(SmoothingFaces, VolumesTileTheBodyAndGradientsAreLinearlyComplete) {
  for (Mesh& m : meshes()) {
    FaceDomains d = build_face_domains(m.cells, m.n_nodes());
    Edges<3> t = build_cell_domains<3>(m.cells, m.n_nodes());
    EXPECT_EQ(compute_smoothing_geometry(m.nodes, m.cells, d.interior), 0);
    EXPECT_EQ(compute_smoothing_geometry(m.nodes, m.cells, d.boundary), 0);
    EXPECT_EQ(compute_smoothing_geometry(m.nodes, m.cells, t), 0);
    double body = 0.0;
    for (Index c = 0; c < m.cells.size(); ++c) body += tet_volume_n(m, c);
    double faces = 0.0, tets = 0.0;
    for (const Edges<3>* e : {&d.interior, &d.boundary})
      for (Index k = 0; k < e->size(); ++k) faces += e->volume_n[k];
    for (Index k = 0; k < t.size(); ++k) {
      tets += t.volume_n[k];
      EXPECT_NEAR(t.volume_n[k], tet_volume_n(m, k), 1e-15 * body);
    }
    EXPECT_NEAR(faces, body, 1e-14 * body);
    EXPECT_NEAR(tets, body, 1e-14 * body);
    expect_linearly_complete(m, d.interior);
    expect_linearly_complete(m, d.boundary);
    expect_linearly_complete(m, t);
    expect_valid_colours(d.interior, m.n_nodes());
    expect_valid_colours(d.boundary, m.n_nodes());
    expect_valid_colours(t, m.n_nodes());
    // A face's pressure point is its centroid in B_n.
    const Index* s = d.interior.stencil.cell_nodes(0);
    EXPECT_LT((d.interior.midpoint[0] - (m.nodes.position_n(s[0]) + m.nodes.position_n(s[1]) + m.nodes.position_n(s[2])) / 3.0).norm(), 1e-15);
  }
}

// An interior face's smoothed gradient is the volume-weighted mean of its two tetrahedra's (a quarter of each).
TEST(SmoothingFaces, HandCheckedTwoTetrahedra) {
  Mesh m;
  m.nodes.X.values() = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 1)};
  m.nodes.resize(5);
  m.cells.nodes.values() = {0, 1, 2, 3, 1, 2, 3, 4};  // share face (1, 2, 3)
  m.cells.body.assign(2, 3);
  ASSERT_GT(tet_volume(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 1)), 0.0);
  FaceDomains d = build_face_domains(m.cells, 5);
  ASSERT_EQ(d.interior.size(), 1);
  ASSERT_EQ(d.boundary.size(), 6);
  EXPECT_EQ(d.interior.stencil.body[0], 3);
  const std::vector<Index> stencil(d.interior.stencil.cell_nodes(0), d.interior.stencil.cell_nodes(0) + 5);
  EXPECT_EQ(stencil, (std::vector<Index>{1, 2, 3, 0, 4}));  // face opposite corner 0 of tet 0 (kTetFaces[0]), then 0, 4
  compute_smoothing_geometry(m.nodes, m.cells, d.interior);
  const double V0 = 1.0 / 6.0, V1 = 1.0 / 3.0;
  EXPECT_NEAR(d.interior.volume_n[0], (V0 + V1) / 4.0, 1e-16);
  // grad N of node 0 in tet 0 is (-1, -1, -1); node 0 is not in tet 1.
  const auto b = Eigen::Map<const Eigen::Matrix<double, 5, 3>>(d.interior.gradient(0));
  EXPECT_LT((b.row(3) - Vec3(-1, -1, -1).transpose() * (V0 / 4.0) / ((V0 + V1) / 4.0)).norm(), 1e-15);
}

TEST(SmoothingFaces, BrokenMeshesAreRefused) {
  Mesh m;
  m.nodes.X.values() = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 1), Vec3(-1, -1, -1), Vec3(0.3, 0.3, 2)};
  m.nodes.resize(7);
  // Three tetrahedra on face (1, 2, 3).
  m.cells.nodes.values() = {0, 1, 2, 3, 1, 2, 3, 4, 1, 2, 3, 6};
  m.cells.body.assign(3, 0);
  EXPECT_THROW(build_face_domains(m.cells, 7), InputError);
  m.cells.nodes.values() = {0, 1, 2, 2};
  m.cells.body.assign(1, 0);
  EXPECT_THROW(build_face_domains(m.cells, 7), InputError);
}

}  // namespace loom
