// 3D patch test of the tetrahedral kernels (displacement_point<NEN, 3>, uphi_internal<3>) on a distorted
// Kuhn box and on gmsh's unstructured mesh of the unit cube (tests/meshes/cube_tet4.msh, cube_tet10.msh): with the boundary nodes displaced by a homogeneous u = (F - I) X that has out-of-plane shear, the
// interior nodes of tet4, tet10 and the mixed tet4 u-phi settle at the same affine map to round-off (and the
// mixed tet's phi at det F), for a linear and a Neo-Hooke material. The kernels are assembled here by hand
// (a Newton loop over a sparse LU) because the engine's systems are still 2D; the 3D systems will repeat this
// test through a scene.
#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <cmath>
#include <random>
#include <vector>

#include "engine/mesh/tet_generators.hpp"
#include "engine/mesh/tet_mesh_from_gmsh.hpp"
#include "systems/assemble/elements/p1p1_uphi_cell.hpp"
#include "systems/assemble/elements/tet10.hpp"
#include "systems/assemble/elements/tet4.hpp"
#include "systems/assemble/materials/material.hpp"

namespace loom {
namespace {

enum class Element { tet4, tet10, uphi };

struct Patch {
  std::vector<Vec3> X;
  std::vector<Index> cells;
  int nen = 4, per_node = 3;
  std::vector<char> on_boundary;
};

// The distorted box, or (from_file) the unit cube meshed by gmsh, its 10-node cells read from their own file.
Patch make_patch(Element e, bool from_file) {
  BoxSpec spec;
  spec.size = from_file ? Vec3(1.0, 1.0, 1.0) : Vec3(1.0, 0.8, 1.2);
  spec.nx = spec.ny = spec.nz = 3;
  TetMeshData mesh;
  Tet10MeshData q;
  if (from_file) {
    const std::string file = std::string(LOOM_SOURCE_DIR) + "/tests/meshes/" + (e == Element::tet10 ? "cube_tet10.msh" : "cube_tet4.msh");
    const TetMeshFile read = tet_mesh_of(read_gmsh_file(file, "test", "mesh"), "", "test", "mesh");
    mesh = read.corners, q = read.quadratic;
  } else {
    mesh = generate_box(spec);
    EXPECT_GT(distort_interior_nodes(mesh, 0.3, 11), 0.2);
    if (e == Element::tet10) q = tet10_from_tet4(mesh);
  }
  Patch p;
  if (e == Element::tet10) {
    p.X = q.X, p.cells = q.cells, p.nen = 10;
  } else {
    p.X = mesh.X, p.cells = mesh.tets;
  }
  p.per_node = e == Element::uphi ? 4 : 3;
  // Boundary nodes: on the box's faces (the outline is not distorted).
  p.on_boundary.resize(p.X.size());
  for (std::size_t i = 0; i < p.X.size(); ++i) {
    const Vec3 s = p.X[i].cwiseQuotient(spec.size);
    p.on_boundary[i] = s.minCoeff() < 1e-12 || s.maxCoeff() > 1 - 1e-12;
  }
  return p;
}

// Residual and tangent of the whole patch at the dofs x (node-major, per_node per node), B_n = B_0.
template <class M>
bool assemble(const M& material, Element e, const Patch& p, const Eigen::VectorXd& x, Eigen::VectorXd& r,
              Eigen::SparseMatrix<double>& K) {
  const int S = p.per_node;
  r.setZero(x.size());
  std::vector<Eigen::Triplet<double>> triplets;
  auto scatter = [&](const Index* v, int nen, const auto& re, const auto& Ke) {
    for (int a = 0; a < nen; ++a)
      for (int i = 0; i < S; ++i) {
        r[S * v[a] + i] += re[S * a + i];
        for (int b = 0; b < nen; ++b)
          for (int k = 0; k < S; ++k) triplets.emplace_back(S * v[a] + i, S * v[b] + k, Ke(S * a + i, S * b + k));
      }
  };
  for (std::size_t c = 0; c < p.cells.size() / std::size_t(p.nen); ++c) {
    const Index* v = p.cells.data() + std::size_t(p.nen) * c;
    if (e == Element::tet10) {
      Tet10Nodes X;
      NodalVectors<10, 3> du;
      for (int a = 0; a < 10; ++a) X.row(a) = p.X[std::size_t(v[a])].transpose(), du.row(a) = x.segment<3>(3 * v[a]).transpose();
      ElementVector<10, 3> re = ElementVector<10, 3>::Zero();
      ElementMatrix<10, 3> Ke = ElementMatrix<10, 3>::Zero();
      for (const auto& l : kTet4Rule4) {
        Tet10Gradients dN;
        const double det = tet10_gradients(X, l, dN);
        Mat3 F;
        if (!add_displacement_point<10, 3>(material, du, dN, det / 24.0, Mat3::Identity(), F, re, &Ke)) return false;
      }
      scatter(v, 10, re, Ke);
      continue;
    }
    Tet4Corners X;
    for (int a = 0; a < 4; ++a) X.row(a) = p.X[std::size_t(v[a])].transpose();
    Tet4Gradients dN;
    const double volume = tet4_gradients(X, dN);
    if (e == Element::tet4) {
      NodalVectors<4, 3> du;
      for (int a = 0; a < 4; ++a) du.row(a) = x.segment<3>(3 * v[a]).transpose();
      ElementVector<4, 3> re = ElementVector<4, 3>::Zero();
      ElementMatrix<4, 3> Ke = ElementMatrix<4, 3>::Zero();
      Mat3 F;
      if (!add_displacement_point<4, 3>(material, du, dN, volume, Mat3::Identity(), F, re, &Ke)) return false;
      scatter(v, 4, re, Ke);
    } else {
      UPhiCellT<3> cell;
      cell.dN = dN;
      for (int a = 0; a < 4; ++a) {
        cell.du.row(a) = x.segment<3>(4 * v[a]).transpose();
        cell.phi[a] = x[4 * v[a] + 3];
        cell.dV_n[a] = volume / 4;
        cell.F_n[a] = Mat3::Identity();
      }
      UPhiVectorT<3> re = UPhiVectorT<3>::Zero();
      UPhiMatrixT<3> Ke = UPhiMatrixT<3>::Zero();
      Mat3 Ft[4];
      if (!uphi_internal(material, 0.5, cell, Ft, re, &Ke)) return false;
      scatter(v, 4, re, Ke);
    }
  }
  K.resize(x.size(), x.size());
  K.setFromTriplets(triplets.begin(), triplets.end());
  return true;
}

// Prescribes u = (F - I) X on the boundary, solves for the rest by Newton from a random perturbation of the
// exact state (3 % of the smallest cell: a start at u = 0 would invert the cells next to the boundary) and returns the largest nodal
// deviation from the affine map (and from phi = det F), relative to |F - I| times the box size.
template <class M>
double patch_error(const M& material, Element e, const Mat3& F, bool from_file = false) {
  const Patch p = make_patch(e, from_file);
  const int S = p.per_node;
  const Index n_dofs = Index(p.X.size()) * S;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n_dofs), exact(n_dofs);
  std::mt19937 rng(5);
  double h = INFINITY;  // the smallest cell size, (6 V)^(1/3) over the corner tetrahedra
  for (std::size_t c = 0; c < p.cells.size(); c += std::size_t(p.nen)) {
    const Index* v = p.cells.data() + c;
    h = std::min(h, std::cbrt(6.0 * tet_volume(p.X[std::size_t(v[0])], p.X[std::size_t(v[1])], p.X[std::size_t(v[2])], p.X[std::size_t(v[3])])));
  }
  std::uniform_real_distribution<double> noise(-0.03 * h, 0.03 * h);
  std::vector<Index> free;
  for (std::size_t i = 0; i < p.X.size(); ++i) {
    exact.segment<3>(S * Index(i)) = (F - Mat3::Identity()) * p.X[i];
    if (S == 4) exact[S * Index(i) + 3] = F.determinant(), x[S * Index(i) + 3] = 1.0, free.push_back(S * Index(i) + 3);
    for (int k = 0; k < 3; ++k) {
      if (p.on_boundary[i]) x[S * Index(i) + k] = exact[S * Index(i) + k];
      else free.push_back(S * Index(i) + k), x[S * Index(i) + k] = exact[S * Index(i) + k] + noise(rng);
    }
  }
  std::sort(free.begin(), free.end());
  Eigen::SparseMatrix<double> P(Index(free.size()), n_dofs);  // picks the free dofs
  for (std::size_t j = 0; j < free.size(); ++j) P.insert(Index(j), free[j]) = 1.0;
  for (int it = 0; it < 20; ++it) {
    Eigen::VectorXd r;
    Eigen::SparseMatrix<double> K;
    if (!assemble(material, e, p, x, r, K)) {
      ADD_FAILURE() << "a cell inverted at iteration " << it;
      return INFINITY;
    }
    const Eigen::SparseMatrix<double> Kf = P * K * P.transpose();
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(Kf);
    EXPECT_EQ(lu.info(), Eigen::Success);
    const Eigen::VectorXd dx = P.transpose() * lu.solve(-(P * r));
    x += dx;
    if (dx.norm() < 1e-14 * x.norm()) break;
  }
  double worst = 0.0;
  for (std::size_t i = 0; i < p.X.size(); ++i) {
    worst = std::max(worst, (x.segment<3>(S * Index(i)) - exact.segment<3>(S * Index(i))).norm() / (F - Mat3::Identity()).norm());
    if (S == 4) worst = std::max(worst, std::abs(x[S * Index(i) + 3] - F.determinant()));
  }
  return worst;
}

Mat3 shear_with_stretch() {
  Mat3 F;
  F << 1.05, 0.1, 0.15, 0.02, 0.97, -0.1, 0.08, 0.12, 1.03;
  return F;
}

}  // namespace

TEST(TetPatch, Tet4ReproducesAHomogeneousDeformation) {
  EXPECT_LE(patch_error(LinearElastic{2.0, 0.6}, Element::tet4, shear_with_stretch()), 1e-13);
  EXPECT_LE(patch_error(NeoHooke{2.0, 0.6}, Element::tet4, shear_with_stretch()), 1e-13);
}

TEST(TetPatch, Tet10ReproducesAHomogeneousDeformation) {
  EXPECT_LE(patch_error(LinearElastic{2.0, 0.6}, Element::tet10, shear_with_stretch()), 1e-13);
  EXPECT_LE(patch_error(NeoHooke{2.0, 0.6}, Element::tet10, shear_with_stretch()), 1e-13);
}

TEST(TetPatch, UnstructuredGmshMeshesReproduceAHomogeneousDeformation) {
  EXPECT_LE(patch_error(NeoHooke{2.0, 0.6}, Element::tet4, shear_with_stretch(), true), 1e-13);
  EXPECT_LE(patch_error(NeoHooke{2.0, 0.6}, Element::tet10, shear_with_stretch(), true), 1e-13);
  EXPECT_LE(patch_error(NeoHooke{1000.0, 1.0}, Element::uphi, shear_with_stretch(), true), 1e-13);
}

TEST(TetPatch, MixedTetReproducesAHomogeneousDeformationNearIncompressibility) {
  // lambda / mu = 1000 (nu = 0.4995): the dilatation phi settles at det F at every node.
  EXPECT_LE(patch_error(LinearElastic{1000.0, 1.0}, Element::uphi, shear_with_stretch()), 1e-13);
  EXPECT_LE(patch_error(NeoHooke{1000.0, 1.0}, Element::uphi, shear_with_stretch()), 1e-13);
}

}  // namespace loom
