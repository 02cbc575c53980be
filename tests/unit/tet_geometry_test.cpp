// compute_geometry in 3D (systems/assemble/compute_geometry.cpp) on tet4 and tet10 cell blocks of a distorted Kuhn
// box: the point weights add up to the box's volume, the cached gradients reproduce an affine field at every point,
// the points per cell follow the formulation (p1: 1, tri6 on tet10 and p1p1_uphi on tet4: the four-point rule), and
// an inverted cell is counted; the lumped masses (compute_lumped_mass in 3D) add up to rho V and are positive
// (tet10: HRZ; the row sum would give the corners negative masses).
#include <gtest/gtest.h>

#include "engine/mesh/tet_generators.hpp"
#include "systems/assemble/compute_geometry.hpp"
#include "systems/update/lumped_mass.hpp"

namespace loom {
namespace {

struct Block {
  Nodes<3> nodes;
  std::vector<Cells> cells;
};

Block box(CellType type, Formulation formulation) {
  BoxSpec spec;
  spec.size = Vec3(2.0, 1.0, 0.5);
  spec.nx = 3, spec.ny = 2, spec.nz = 2;
  TetMeshData mesh = generate_box(spec);
  EXPECT_GT(distort_interior_nodes(mesh, 0.25, 3), 0.0);
  std::vector<Vec3> X = mesh.X;
  std::vector<Index> connectivity = mesh.tets;
  if (type == CellType::tet10) {
    Tet10MeshData q = tet10_from_tet4(mesh);
    X = q.X, connectivity = q.cells;
  }
  Block b;
  b.nodes.resize(Index(X.size()));
  for (Index i = 0; i < Index(X.size()); ++i) b.nodes.X[i] = X[std::size_t(i)];
  Cells cells;
  cells.type = type;
  cells.formulation = formulation;
  cells.stride = nodes_per_cell(type);
  cells.nodes.values() = connectivity;
  cells.body.values().assign(connectivity.size() / std::size_t(cells.stride), 0);
  b.cells.push_back(std::move(cells));
  return b;
}

void expect_geometry(CellType type, Formulation formulation, int per_cell) {
  Block b = box(type, formulation);
  std::vector<QuadPoints<3>> quad;
  allocate_quad_points(b.cells, quad);
  ASSERT_EQ(quad[0].per_cell, per_cell);
  ASSERT_EQ(compute_geometry(b.nodes, b.cells, quad), 0);
  const Cells& cells = b.cells[0];
  const int nen = cells.stride;
  const Vec3 g(0.4, -1.2, 2.5);  // u = g . X + 1
  double volume = 0.0;
  for (Index c = 0; c < cells.size(); ++c)
    for (int q = 0; q < per_cell; ++q) {
      const Index p = c * per_cell + q;
      volume += quad[0].weight_n[p];
      Eigen::Map<const Eigen::MatrixXd> dN(quad[0].grad(p), nen, 3);
      Vec3 grad = Vec3::Zero();
      for (int a = 0; a < nen; ++a) grad += dN.row(a).transpose() * (g.dot(b.nodes.X[cells.cell_nodes(c)[a]]) + 1.0);
      EXPECT_LE((grad - g).norm(), 1e-12) << "cell " << c << " point " << q;
    }
  EXPECT_NEAR(volume, 1.0, 1e-13);

  std::vector<BodyMaterial> materials(1);
  materials[0].density = 2.5;
  b.nodes.lumped_mass.use();
  compute_lumped_mass(b.cells, quad, materials, b.nodes);
  double mass = 0.0, smallest = INFINITY;
  for (Index i = 0; i < b.nodes.size(); ++i) mass += b.nodes.lumped_mass[i], smallest = std::min(smallest, b.nodes.lumped_mass[i]);
  EXPECT_NEAR(mass, 2.5, 1e-13);
  EXPECT_GT(smallest, 0.0);
}

}  // namespace

TEST(TetGeometry, Tet4OnePointOrFourForTheMixedCell) {
  expect_geometry(CellType::tet4, Formulation::p1, 1);
  expect_geometry(CellType::tet4, Formulation::p1p1_uphi, 4);
}

TEST(TetGeometry, Tet10FourPoints) { expect_geometry(CellType::tet10, Formulation::tri6, 4); }

TEST(TetGeometry, AnInvertedCellIsCounted) {
  Block b = box(CellType::tet4, Formulation::p1);
  std::swap(b.cells[0].nodes.values()[2], b.cells[0].nodes.values()[3]);  // cell 0 turned inside out
  std::vector<QuadPoints<3>> quad;
  allocate_quad_points(b.cells, quad);
  EXPECT_EQ(compute_geometry(b.nodes, b.cells, quad), 1);
}

}  // namespace loom
