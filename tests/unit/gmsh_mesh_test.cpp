// Mesh files written by gmsh (engine/mesh/gmsh_file.hpp, mesh_from_gmsh.hpp): 3-node triangles in ASCII
// 4.1 and 2.2, 6-node triangles in binary 4.1, physical groups as regions, and the errors of files loom
// cannot use (tests/meshes/README.md says how each file was made).
#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/errors.hpp"
#include "engine/mesh/boundary_edges.hpp"
#include "engine/mesh/gmsh_file.hpp"
#include "engine/mesh/mesh_from_gmsh.hpp"

namespace loom {
namespace {

const std::string kMeshes = std::string(LOOM_SOURCE_DIR) + "/tests/meshes/";

MeshData square(const std::string& file, const std::string& surface = "") {
  return triangle_mesh_of(read_gmsh_file(kMeshes + file, "scene.toml:3:8", "body[0].mesh.file"), surface, "scene.toml:3:8", "body[0].mesh.file");
}

double area(const MeshData& m, Index t) {
  const Vec2 &a = m.X[std::size_t(m.triangles[3 * std::size_t(t)])], &b = m.X[std::size_t(m.triangles[3 * std::size_t(t) + 1])],
             &c = m.X[std::size_t(m.triangles[3 * std::size_t(t) + 2])];
  return 0.5 * ((b - a).x() * (c - a).y() - (c - a).x() * (b - a).y());
}

// The 4 x 4 square: 25 corners, 32 counter-clockwise triangles covering area 1, and its groups.
void expect_square(const MeshData& m) {
  EXPECT_EQ(m.X.size(), 25u);
  ASSERT_EQ(m.n_triangles(), 32);
  double total = 0.0;
  for (Index t = 0; t < m.n_triangles(); ++t) {
    EXPECT_GT(area(m, t), 0.0) << "triangle " << t;
    total += area(m, t);
  }
  EXPECT_NEAR(total, 1.0, 1e-14);
  ASSERT_NE(m.region("bottom"), nullptr);
  EXPECT_EQ(m.region("bottom")->dim, 1);
  EXPECT_EQ(m.region("bottom")->corners.size(), 5u);
  for (Index v : m.region("bottom")->corners) EXPECT_EQ(m.X[std::size_t(v)].y(), 0.0);
  ASSERT_NE(m.region("corner"), nullptr);
  EXPECT_EQ(m.region("corner")->dim, 0);
  ASSERT_EQ(m.region("corner")->corners.size(), 1u);
  EXPECT_EQ(m.X[std::size_t(m.region("corner")->corners[0])], Vec2(1, 1));
  EXPECT_EQ(m.region("square")->corners.size(), 25u);
  EXPECT_EQ(m.source_tag.size(), 32u);
}

TEST(GmshMesh, ReadsThreeNodeTrianglesAndPhysicalGroupsFromAscii41) {
  const MeshData m = square("square_tri3.msh");
  expect_square(m);
  EXPECT_TRUE(m.mid_nodes.empty());
  expect_square(square("square_tri3.msh", "square"));
}

TEST(GmshMesh, ReadsTheOlderFormat22) { expect_square(square("square_tri3_v22.msh")); }

// A mesh whose triangles all run clockwise (a surface meshed with its normal along -z) is turned, not refused.
TEST(GmshMesh, AClockwiseMeshIsTurnedCounterClockwise) { expect_square(square("square_clockwise.msh")); }

// A group of two curves meeting at a corner: its edges are those of its line elements (8), all on y = 0 or
// x = 1; the corner cell's diagonal, which joins two of its nodes, is not one of them.
TEST(GmshMesh, ACurveGroupKeepsTheEdgesOfItsLineElements) {
  const MeshData m = square("square_tri3.msh");
  const MeshRegion* r = m.region("bottom_right");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->corners.size(), 9u);
  ASSERT_EQ(r->edges.size(), 8u);
  for (const auto& e : r->edges) {
    const Vec2 a = m.X[std::size_t(e[0])], b = m.X[std::size_t(e[1])];
    EXPECT_TRUE((a.y() == 0.0 && b.y() == 0.0) || (a.x() == 1.0 && b.x() == 1.0)) << a.transpose() << " - " << b.transpose();
    EXPECT_LT(e[0], e[1]);
  }
}

// Binary 4.1, 6-node triangles: every edge has one mid-node, at its middle (the square's edges are
// straight), shared by the two triangles of the edge, in the order of edges (c0,c1), (c1,c2), (c2,c0).
TEST(GmshMesh, ReadsSixNodeTrianglesFromBinary41WithTheirOwnMidNodes) {
  const MeshData m = square("square_tri6_binary.msh");
  expect_square(m);
  const std::size_t edges = 25 + 32 - 1;  // Euler
  EXPECT_EQ(m.mid_X.size(), edges);
  ASSERT_EQ(m.mid_nodes.size(), 3u * 32);
  for (std::size_t t = 0; t < 32; ++t)
    for (int s = 0; s < 3; ++s) {
      const Vec2 mid = 0.5 * (m.X[std::size_t(m.triangles[3 * t + std::size_t(s)])] + m.X[std::size_t(m.triangles[3 * t + std::size_t((s + 1) % 3)])]);
      EXPECT_NEAR((m.mid_X[std::size_t(m.mid_nodes[3 * t + std::size_t(s)])] - mid).norm(), 0.0, 1e-12) << "triangle " << t << " side " << s;  // gmsh places them to ~1e-13
    }
}

// The plate of scenes/plate_with_hole.toml: the mid-nodes of the hole's edges lie on the circle, not on the
// chords (the file's own mid-nodes are kept).
TEST(GmshMesh, CurvedMidNodesOfAHoleStayOnTheCircle) {
  const MeshData m = triangle_mesh_of(read_gmsh_file(std::string(LOOM_SOURCE_DIR) + "/scenes/meshes/plate_with_hole.msh", "s", "k"), "plate", "s", "k");
  const MeshRegion* hole = m.region("hole");
  ASSERT_NE(hole, nullptr);
  std::vector<char> on_hole(m.X.size(), 0);
  for (Index v : hole->corners) on_hole[std::size_t(v)] = 1;
  int curved = 0;
  for (std::size_t t = 0; t < std::size_t(m.n_triangles()); ++t)
    for (int s = 0; s < 3; ++s) {
      const Index a = m.triangles[3 * t + std::size_t(s)], b = m.triangles[3 * t + std::size_t((s + 1) % 3)];
      if (!on_hole[std::size_t(a)] || !on_hole[std::size_t(b)]) continue;
      const Vec2 mid = m.mid_X[std::size_t(m.mid_nodes[3 * t + std::size_t(s)])];
      EXPECT_NEAR(mid.norm(), 1.0, 1e-12);
      EXPECT_GT(mid.norm() - (0.5 * (m.X[std::size_t(a)] + m.X[std::size_t(b)])).norm(), 1e-6);  // off the chord
      ++curved;
    }
  EXPECT_GE(curved, 10);
}

void expect_error(const std::string& file, const std::string& surface, const std::string& words) {
  try {
    square(file, surface);
    ADD_FAILURE() << file << ": no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("scene.toml:3:8: error: body[0].mesh.file: " + kMeshes + file + ": ", 0), 0u) << what;
    EXPECT_NE(what.find(words), std::string::npos) << what;
  }
}

TEST(GmshMesh, FilesLoomCannotUseAreInputErrorsNamingTheFileAndTheCell) {
  expect_error("no_such_file.msh", "", "no such file");
  expect_error("square_quad4.msh", "", "it holds Quadrilateral 4 elements (gmsh element type 3): loom reads 3- and 6-node triangles");
  expect_error("square_inverted.msh", "", "triangle 18 (element tag) is inverted");
  expect_error("square_zero_area.msh", "", "triangle 19 (element tag) has zero area");
  expect_error("square_tri3.msh", "disk", "no physical surface named \"disk\" (its physical groups: \"corner\" (point), \"bottom\" (curve)");
  expect_error("README.md", "", "gmsh cannot read it");
  expect_error("square_tri6_folded.msh", "", "6-node triangle 18 (element tag) is inverted: its curved edges fold it over");
}

}  // namespace
}  // namespace loom
