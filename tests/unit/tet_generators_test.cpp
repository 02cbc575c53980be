// Tetrahedral meshes (engine/mesh/tet_generators): the Kuhn box and the extrusion of a 2D mesh are conforming
// (every interior face shared by exactly two tetrahedra, boundary faces only on the outline), positively
// oriented, and fill their volume; the boundary faces are closed and point outwards (divergence theorem);
// the interior distortion keeps the outline and the volume; tet10 adds one node per edge (Euler's formula).
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <set>

#include "engine/mesh/generators.hpp"
#include "engine/mesh/tet_generators.hpp"

namespace loom {
namespace {

double volume(const TetMeshData& m, Index t) {
  const Index* v = m.tets.data() + 4 * std::size_t(t);
  return tet_volume(m.X[std::size_t(v[0])], m.X[std::size_t(v[1])], m.X[std::size_t(v[2])], m.X[std::size_t(v[3])]);
}

struct Sums {
  double min_volume = INFINITY, total = 0.0;
};
Sums volumes(const TetMeshData& m) {
  Sums s;
  for (Index t = 0; t < m.n_tets(); ++t) {
    s.min_volume = std::min(s.min_volume, volume(m, t));
    s.total += volume(m, t);
  }
  return s;
}

// For a closed, outward surface: sum of area vectors = 0 and (1/3) sum x_c . n A = the enclosed volume.
void expect_closed_outward_surface(const TetMeshData& m, double enclosed) {
  Vec3 area = Vec3::Zero();
  double flux = 0.0;
  for (const auto& f : boundary_faces(m.tets)) {
    const Vec3 &a = m.X[std::size_t(f.nodes[0])], &b = m.X[std::size_t(f.nodes[1])], &c = m.X[std::size_t(f.nodes[2])];
    const Vec3 n = 0.5 * (b - a).cross(c - a);
    area += n;
    flux += (a + b + c).dot(n) / 9.0;
  }
  EXPECT_LE(area.norm(), 1e-12 * std::abs(enclosed));
  EXPECT_NEAR(flux, enclosed, 1e-12 * std::abs(enclosed));
}

}  // namespace

TEST(GenerateBox, KuhnLatticeIsConformingAndFillsTheBox) {
  BoxSpec spec;
  spec.origin = Vec3(-1.0, 0.5, 2.0);
  spec.size = Vec3(2.0, 1.5, 0.75);
  spec.nx = 4, spec.ny = 3, spec.nz = 2;
  const TetMeshData m = generate_box(spec);
  EXPECT_EQ(m.X.size(), 5u * 4u * 3u);
  EXPECT_EQ(m.n_tets(), 6 * 4 * 3 * 2);
  const Sums s = volumes(m);
  EXPECT_NEAR(s.min_volume, 2.0 * 1.5 * 0.75 / (6 * 24), 1e-14);  // all six Kuhn tetrahedra are equal
  EXPECT_NEAR(s.total, 2.0 * 1.5 * 0.75, 1e-13);
  // Two triangles per boundary square: conforming (a non-matching cut would leave interior faces used once).
  EXPECT_EQ(boundary_faces(m.tets).size(), std::size_t(2 * 2 * (4 * 3 + 3 * 2 + 2 * 4)));
  expect_closed_outward_surface(m, s.total);
}

TEST(Extrude, PrismsCutConsistentlyIntoTetrahedra) {
  for (bool quads : {false, true}) {
    const MeshData cook = generate_cooks_membrane(5, 4, GridPattern::alternating, quads);
    const TetMeshData m = extrude(cook, 3.0, 2);
    const Index triangles = quads ? 2 * Index(cook.quads.size() / 4) : cook.n_triangles();
    EXPECT_EQ(m.n_tets(), 3 * 2 * triangles);
    EXPECT_EQ(m.X.size(), 3 * cook.X.size());
    const Sums s = volumes(m);
    EXPECT_GT(s.min_volume, 0.0);
    EXPECT_NEAR(s.total, 3.0 * 0.5 * (44.0 + 16.0) * 48.0, 1e-9);  // Cook's trapezoid area x depth
    // Boundary: both caps (one face per triangle each) and two faces per outline edge per layer.
    const std::size_t outline = 2 * (5 + 4);
    EXPECT_EQ(boundary_faces(m.tets).size(), std::size_t(2 * triangles) + 2 * 2 * outline);
    expect_closed_outward_surface(m, s.total);
  }
}

TEST(DistortTetMesh, MovesOnlyInteriorNodesAndKeepsTheVolume) {
  BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 4;
  TetMeshData m = generate_box(spec);
  const TetMeshData before = m;
  const double ratio = distort_interior_nodes(m, 0.3, 7);
  EXPECT_GT(ratio, 0.0);
  EXPECT_LT(ratio, 0.9);  // the nodes did move
  std::set<Index> outline;
  for (const auto& f : boundary_faces(m.tets)) outline.insert(f.nodes.begin(), f.nodes.end());
  std::size_t moved = 0;
  for (std::size_t i = 0; i < m.X.size(); ++i) {
    if (outline.count(Index(i))) EXPECT_EQ(m.X[i], before.X[i]);
    else moved += (m.X[i] != before.X[i]);
  }
  EXPECT_EQ(moved, 27u);  // every interior node
  EXPECT_NEAR(volumes(m).total, 1.0, 1e-14);
  TetMeshData again = before;
  distort_interior_nodes(again, 0.3, 7);
  EXPECT_EQ(again.X, m.X);  // deterministic
}

TEST(Tet10FromTet4, OneMidNodePerEdgeAtItsMidpoint) {
  BoxSpec spec;
  spec.nx = 3, spec.ny = 2, spec.nz = 2;
  const TetMeshData m = generate_box(spec);
  const Tet10MeshData q = tet10_from_tet4(m);
  // Euler: V - E + F - T = 1 for a ball, F = (4 T + boundary faces) / 2.
  const std::size_t V = m.X.size(), T = std::size_t(m.n_tets()), B = boundary_faces(m.tets).size();
  const std::size_t F = (4 * T + B) / 2, E = V + F - T - 1;
  EXPECT_EQ(q.X.size(), V + E);
  EXPECT_EQ(q.n_corners, Index(V));
  std::set<Index> used;
  for (Index c = 0; c < q.n_cells(); ++c) {
    const Index* v = q.cells.data() + 10 * std::size_t(c);
    for (int a = 0; a < 4; ++a) EXPECT_EQ(v[a], m.tets[4 * std::size_t(c) + std::size_t(a)]);
    static constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
    for (int e = 0; e < 6; ++e) {
      EXPECT_GE(v[4 + e], q.n_corners);
      EXPECT_LE((q.X[std::size_t(v[4 + e])] - 0.5 * (q.X[std::size_t(v[kEdges[e][0]])] + q.X[std::size_t(v[kEdges[e][1]])])).norm(), 1e-15);
      used.insert(v[4 + e]);
    }
  }
  EXPECT_EQ(used.size(), E);
}

}  // namespace loom
