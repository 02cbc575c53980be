// Tetrahedra from gmsh files (engine/mesh/tet_mesh_from_gmsh.hpp): the unit cube in 4- and 10-node tetrahedra
// (tests/meshes/README.md says how they were made) fills its volume with positively oriented cells whose boundary
// is closed and points outwards; the 10-node cells' mid-nodes sit at the midpoints of the edges VTK's order names
// (which checks the turn from gmsh's edge order); the physical groups become regions; the files loom cannot use
// are input errors naming the file.
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <set>

#include "engine/core/errors.hpp"
#include "engine/mesh/tet_mesh_from_gmsh.hpp"

namespace loom {
namespace {

const std::string kMeshes = std::string(LOOM_SOURCE_DIR) + "/tests/meshes/";

TetMeshFile cube(const std::string& file, const std::string& volume = "") {
  return tet_mesh_of(read_gmsh_file(kMeshes + file, "scene.toml:3:8", "body[0].mesh.file"), volume, "scene.toml:3:8", "body[0].mesh.file");
}

void expect_unit_cube(const TetMeshData& m) {
  ASSERT_GT(m.n_tets(), 100);
  double total = 0.0, smallest = INFINITY;
  for (Index t = 0; t < m.n_tets(); ++t) {
    const Index* v = m.tets.data() + 4 * std::size_t(t);
    const double V = tet_volume(m.X[std::size_t(v[0])], m.X[std::size_t(v[1])], m.X[std::size_t(v[2])], m.X[std::size_t(v[3])]);
    total += V, smallest = std::min(smallest, V);
  }
  EXPECT_GT(smallest, 0.0);
  EXPECT_NEAR(total, 1.0, 1e-12);
  Vec3 area = Vec3::Zero();
  for (const auto& f : boundary_faces(m.tets)) {
    const Vec3 &a = m.X[std::size_t(f.nodes[0])], &b = m.X[std::size_t(f.nodes[1])], &c = m.X[std::size_t(f.nodes[2])];
    area += 0.5 * (b - a).cross(c - a);
    for (const Vec3* p : {&a, &b, &c}) EXPECT_NEAR(std::min({p->minCoeff(), 1.0 - p->maxCoeff()}), 0.0, 1e-12);  // on the cube's faces
  }
  EXPECT_LE(area.norm(), 1e-12);
  const MeshRegion* bottom = nullptr;
  for (const auto& r : m.regions)
    if (r.name == "bottom") bottom = &r;
  ASSERT_NE(bottom, nullptr);
  EXPECT_EQ(bottom->dim, 2);
  EXPECT_GE(bottom->corners.size(), 9u);
  for (Index n : bottom->corners) EXPECT_NEAR(m.X[std::size_t(n)].z(), 0.0, 1e-12);
}

}  // namespace

TEST(TetMeshFromGmsh, ReadsFourNodeTetrahedraAndTheirGroups) {
  const TetMeshFile f = cube("cube_tet4.msh", "cube");
  EXPECT_FALSE(f.is_quadratic());
  expect_unit_cube(f.corners);
  EXPECT_EQ(f.corners.source_tag.size(), std::size_t(f.corners.n_tets()));
}

TEST(TetMeshFromGmsh, TenNodeTetrahedraHaveTheirMidNodesInVtkOrder) {
  const TetMeshFile f = cube("cube_tet10.msh");
  ASSERT_TRUE(f.is_quadratic());
  expect_unit_cube(f.corners);
  const Tet10MeshData& q = f.quadratic;
  EXPECT_EQ(q.n_cells(), f.corners.n_tets());
  EXPECT_EQ(q.n_corners, Index(f.corners.X.size()));
  static constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  std::set<Index> mids;
  for (Index c = 0; c < q.n_cells(); ++c) {
    const Index* v = q.cells.data() + 10 * std::size_t(c);
    for (int a = 0; a < 4; ++a) EXPECT_EQ(v[a], f.corners.tets[4 * std::size_t(c) + std::size_t(a)]);
    for (int e = 0; e < 6; ++e) {
      // The cube's faces are flat, so gmsh put every mid-node on its straight edge.
      const Vec3 midpoint = 0.5 * (q.X[std::size_t(v[kEdges[e][0]])] + q.X[std::size_t(v[kEdges[e][1]])]);
      EXPECT_LE((q.X[std::size_t(v[4 + e])] - midpoint).norm(), 1e-12) << "cell " << c << " edge " << e;
      mids.insert(v[4 + e]);
    }
  }
  EXPECT_EQ(mids.size() + std::size_t(q.n_corners), q.X.size());  // every node is used
  EXPECT_GE(*mids.begin(), q.n_corners);
}

TEST(TetMeshFromGmsh, FilesLoomCannotUseAreInputErrorsNamingTheFile) {
  auto expect_error = [](const std::string& file, const std::string& volume, const std::string& message) {
    try {
      cube(file, volume);
      ADD_FAILURE() << file << ": no error";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("scene.toml:3:8: error: body[0].mesh.file: "), std::string::npos) << what;
      EXPECT_NE(what.find(message), std::string::npos) << what;
    }
  };
  expect_error("square_tri3.msh", "", "it holds no tetrahedra (mesh the volumes: gmsh -3)");
  expect_error("cube_tet4.msh", "disk", "no physical volume named \"disk\" (its physical groups: \"bottom\" (surface), \"cube\" (volume))");
}

}  // namespace loom
