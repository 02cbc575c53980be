// Method es_pfem (seed 001 §3.5): the edges' history across remeshes (engine/methods/pfem/domain_transfer.hpp).
//  1. A homogeneous deformation stays exact when the connectivity changes: a block sheared and stretched by
//     prescribed affine boundary displacements is remeshed before every step, the Delaunay triangulation of
//     the sheared points flips diagonals, and the new edges take b_bar from the nearest old edge and J from
//     the particles. Every edge has the same b^e and every particle the same J = det F, so the transfer is
//     exact: u at every node, J^l = det F, det b^e = J^2 and one b^e for all edges (also when it flows
//     plastically, and with body[].j_projection, which projects every edge after every step), to round-off.
//  2. A resting yield-stress block (tau_eq < tau0 everywhere) remeshed before each of 1000 steps does not
//     creep: after the first step u, J^l and b^e do not change.
// Both on triangles (edge domains) and on tetrahedra (face domains, a BCC block whose Delaunay mesh a shear flips).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "tests/support/test_support.hpp"

namespace loom {
namespace {

template <int D>
using MatD = Eigen::Matrix<double, D, D>;

// u = t (F - I) X on every boundary node, as an expression of x, y (, z).
template <int D>
std::string affine_displacement(const MatD<D>& F) {
  const char* axis[3] = {"x", "y", "z"};
  std::string s = "displacement = { ";
  for (int i = 0; i < D; ++i) {
    std::string row = "t * (0.0";
    for (int j = 0; j < D; ++j) {
      char term[64];
      std::snprintf(term, sizeof term, " + %.17g * %s", F(i, j) - (i == j ? 1.0 : 0.0), axis[j]);
      row += term;
    }
    s += std::string(i ? ", " : "") + axis[i] + " = \"" + row + ")\"";
  }
  return s + " }\n";
}

template <int D>
std::string homogeneous_scene(const MatD<D>& F, int steps, const std::string& plastic, bool j_projection, double insert_above) {
  const std::string disp = affine_displacement<D>(F);
  std::string s = "[scene]\nname = \"es-pfem-homogeneous\"\nmethod = \"es_pfem\"\n";
  if (D == 3) s += "dimension = 3\n";
  char dt[64];
  std::snprintf(dt, sizeof dt, "%.17g", 1.0 / steps);
  s += "[time]\nintegrator = \"static\"\ndt = " + std::string(dt) + "\nsteps = " + std::to_string(steps) + "\n";
  s += "[solver]\nresidual_relative = 1e-13\nresidual_absolute = 1e-14\n";
  s += "[[material]]\nname = \"m\"\nmodel = \"hencky_perzyna\"\nE = 10.0\nnu = 0.3\n" + plastic;
  s += "[[body]]\nname = \"block\"\nmaterial = \"m\"\nelement = \"es_up\"\nalpha_stab = 0.5\n";
  if (j_projection) s += "j_projection = true\n";
  std::vector<const char*> sides;
  if constexpr (D == 2) {
    s += "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [1.0, 1.0], divisions = [6, 6], pattern = \"right\" }\n";
    sides = {"[[0.0, 0.0], [0.0, 1.0]]", "[[1.0, 0.0], [1.0, 1.0]]", "[[0.0, 0.0], [1.0, 0.0]]", "[[0.0, 1.0], [1.0, 1.0]]"};
  } else {
    s += "mesh = { generator = \"box\", size = [1.0, 1.0, 1.0], divisions = [3, 3, 3], lattice = \"bcc\" }\n";
    sides = {"[[0.0, 0.0, 0.0], [0.0, 1.0, 1.0]]", "[[1.0, 0.0, 0.0], [1.0, 1.0, 1.0]]", "[[0.0, 0.0, 0.0], [1.0, 0.0, 1.0]]",
             "[[0.0, 1.0, 0.0], [1.0, 1.0, 1.0]]", "[[0.0, 0.0, 0.0], [1.0, 1.0, 0.0]]", "[[0.0, 0.0, 1.0], [1.0, 1.0, 1.0]]"};
  }
  int side = 0;
  for (const char* box : sides) s += "[[boundary]]\nname = \"side" + std::to_string(side++) + "\"\nregion = { box = " + box + " }\n" + disp;
  s += "[remesh]\nalpha = 100.0\n";
  if (insert_above > 0.0) s += "insert_above = " + std::to_string(insert_above) + "\n";
  s += "[[probe]]\nname = \"changed\"\nkind = \"remesh\"\nquantity = \"changed\"\n";
  s += "[[probe]]\nname = \"inserted\"\nkind = \"remesh\"\nquantity = \"inserted\"\n";
  s += "[output]\nevery = 0\n";
  return s;
}

template <int D>
void check_homogeneous(const MatD<D>& F, const std::string& plastic, bool j_projection = false, double insert_above = 0.0) {
  SCOPED_TRACE(std::string(plastic.empty() ? "elastic" : "plastic") + (j_projection ? ", J projection every step" : ""));
  const int steps = 6;
  const SceneSpec scene = testing::scene_from_text(homogeneous_scene<D>(F, steps, plastic, j_projection, insert_above));
  testing::TempDir dir("es_pfem_homogeneous");
  auto run = testing::make_fem_run<D>(scene, dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  double changes = 0.0, inserted = 0.0;
  for (double c : probes.column("changed")) changes += c;
  for (double c : probes.column("inserted")) inserted += c;
  EXPECT_GE(changes, 2.0) << "the connectivity must change for the test to mean anything";
  if (insert_above > 0.0) {
    EXPECT_GE(inserted, 4.0) << "particles must be inserted for the test to mean anything";
  }
  const FemModelT<D>& m = run->model();
  const double J = F.determinant();
  double u_error = 0.0, J_error = 0.0, be_spread = 0.0, det_error = 0.0;
  for (Index i = 0; i < m.nodes.size(); ++i) {
    u_error = std::max(u_error, (m.nodes.u_n[i] - (F - MatD<D>::Identity()) * m.nodes.X[i]).norm());
    J_error = std::max(J_error, std::abs(m.nodes.J_node[i] - J));
  }
  const Mat3 be0 = m.edges.front().be_n[0];
  for (const Edges<D>& e : m.edges)
    for (Index k = 0; k < e.size(); ++k) {
      be_spread = std::max(be_spread, (e.be_n[k] - be0).cwiseAbs().maxCoeff());
      det_error = std::max(det_error, std::abs(std::sqrt(e.be_n[k].determinant()) - J));
    }
  std::printf("[es_pfem homogeneous %dD] %s%s: %g connectivity changes, %g particles inserted, max |u - u_exact| %.1e, |J^l - det F| %.1e, b^e spread %.1e, "
              "|sqrt(det b^e) - J| %.1e\n",
              D, plastic.empty() ? "elastic" : "plastic", j_projection ? ", J projection" : "", changes, inserted, u_error, J_error, be_spread, det_error);
  EXPECT_LE(u_error, 1e-12);
  EXPECT_LE(J_error, 1e-12);
  EXPECT_LE(be_spread, 1e-12);
  EXPECT_LE(det_error, 1e-12);
}

TEST(EsPfemRemesh, HomogeneousDeformationIsTransferredExactly) {
  Eigen::Matrix2d F;
  F << 1.1, -0.9, 0.05, 0.95;  // shear to the left: the 'right' diagonals become the long ones and flip
  check_homogeneous<2>(F, "");
  check_homogeneous<2>(F, "tau0 = 0.05\nviscosity = 0.1\n");  // flows plastically, still homogeneous
  check_homogeneous<2>(F, "tau0 = 0.05\nviscosity = 0.1\n", true);  // the projection of every edge after every step
}

TEST(EsPfemRemesh, HomogeneousDeformationIsTransferredExactlyOnTetrahedra) {
  Eigen::Matrix3d F;  // a shear in x-y and a stretch in z: the BCC lattice's Delaunay mesh flips
  F << 1.1, -1.5, 0.1, 0.05, 0.95, 0.0, 0.0, 0.1, 1.05;
  check_homogeneous<3>(F, "");
  check_homogeneous<3>(F, "tau0 = 0.05\nviscosity = 0.1\n");
  check_homogeneous<3>(F, "tau0 = 0.05\nviscosity = 0.1\n", true);
}

// Particles inserted at the midpoints of edges that a stretch made long (particle_insertion_3d.hpp): an affine state
// stays exact through the split cells and the remeshes that follow.
TEST(EsPfemRemesh, InsertedParticlesKeepAHomogeneousStateOnTetrahedra) {
  Eigen::Matrix3d F;  // stretched to 1.8 along x and sheared: the interior edges along x pass 1.3 h0
  F << 1.8, -0.5, 0.1, 0.05, 0.95, 0.0, 0.0, 0.1, 1.05;
  check_homogeneous<3>(F, "", false, 1.3);
  check_homogeneous<3>(F, "tau0 = 0.05\nviscosity = 0.1\n", true, 1.3);
}

// The state after step `settled` (the remeshes that follow the generated mesh's first sag have happened) and after
// step 1000 must agree.
template <int D>
void check_resting(const std::string& text, int settled) {
  auto state_after = [&](int steps, std::vector<Vec<D>>& u, std::vector<double>& J, std::vector<Mat3>& be, double& tau_eq_max) {
    const SceneSpec scene = testing::scene_from_text(text, {"time.steps=" + std::to_string(steps)});
    auto run = testing::make_fem_run<D>(scene);
    const RunSummary summary = run->run();
    ASSERT_TRUE(summary.converged) << summary.failure;
    const FemModelT<D>& m = run->model();
    for (Index i = 0; i < m.nodes.size(); ++i) u.push_back(m.nodes.u_n[i]), J.push_back(m.nodes.J_node[i]);
    tau_eq_max = 0.0;
    for (const Edges<D>& e : m.edges)
      for (Index k = 0; k < e.size(); ++k) {
        be.push_back(e.be_n[k]);
        const Mat3 s = e.stress[k] - e.stress[k].trace() / 3.0 * Mat3::Identity();
        tau_eq_max = std::max(tau_eq_max, std::sqrt(0.5 * s.squaredNorm()));
      }
  };
  std::vector<Vec<D>> u2, u1000;
  std::vector<double> J2, J1000;
  std::vector<Mat3> be2, be1000;
  double tau2 = 0.0, tau1000 = 0.0;
  state_after(settled, u2, J2, be2, tau2);
  state_after(1000, u1000, J1000, be1000, tau1000);
  ASSERT_EQ(u2.size(), u1000.size());
  ASSERT_EQ(be2.size(), be1000.size());
  double du = 0.0, dJ = 0.0, dbe = 0.0, u_scale = 0.0;
  for (std::size_t i = 0; i < u2.size(); ++i) {
    du = std::max(du, (u1000[i] - u2[i]).norm()), u_scale = std::max(u_scale, u2[i].norm());
    dJ = std::max(dJ, std::abs(J1000[i] - J2[i]));
  }
  for (std::size_t k = 0; k < be2.size(); ++k) dbe = std::max(dbe, (be1000[k] - be2[k]).cwiseAbs().maxCoeff());
  std::printf("[es_pfem resting %dD] |u| %.2e; change from step %d to 1000: u %.1e, J^l %.1e, b^e %.1e; tau_eq max %.3g (tau0 1e5)\n", D,
              u_scale, settled, du, dJ, dbe, tau1000);
  EXPECT_GT(u_scale, 0.0);
  EXPECT_LT(tau1000, 1e5);
  EXPECT_LE(du, 1e-12 * u_scale);
  EXPECT_LE(dJ, 1e-14);
  EXPECT_LE(dbe, 1e-14);
}

const char* kRestingMaterial =
    "[solver]\nresidual_relative = 1e-10\n"
    "[[material]]\nname = \"paste\"\nmodel = \"hencky_perzyna\"\nE = 1.0e6\nnu = 0.3\ntau0 = 1.0e5\nviscosity = 10.0\ndensity = 1000.0\n"
    "[remesh]\nalpha = 2.0\n[output]\nevery = 0\n";

TEST(EsPfemRemesh, RestingYieldStressBlockDoesNotCreep) {
  check_resting<2>(std::string("[scene]\nname = \"resting\"\nmethod = \"es_pfem\"\n[time]\nintegrator = \"static\"\ndt = 1.0\nsteps = 1000\n") +
                   kRestingMaterial +
                   "[[body]]\nname = \"block\"\nmaterial = \"paste\"\nelement = \"es_up\"\nalpha_stab = 200.0\n"
                   "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [1.0, 1.0], divisions = [8, 8], pattern = \"right\", "
                   "distortion = 0.2 }\nbody_force = { y = -9.81 }\n"
                   "[[boundary]]\nname = \"ground\"\nregion = { box = [[0.0, 0.0], [1.0, 0.0]] }\ndisplacement = { x = 0.0, y = 0.0 }\n",
                   2);
}

// The BCC block sags in the first step; the remeshes of steps 2 and 3 flip a few cells at its surface (4, then 2), and
// from then on the mesh is kept as it is (R3.7: still Delaunay) and nothing moves.
TEST(EsPfemRemesh, RestingYieldStressBlockDoesNotCreepOnTetrahedra) {
  check_resting<3>(std::string("[scene]\nname = \"resting\"\nmethod = \"es_pfem\"\ndimension = 3\n"
                               "[time]\nintegrator = \"static\"\ndt = 1.0\nsteps = 1000\n") +
                   kRestingMaterial +
                   "[[body]]\nname = \"block\"\nmaterial = \"paste\"\nelement = \"es_up\"\nalpha_stab = 200.0\n"
                   "mesh = { generator = \"box\", size = [1.0, 1.0, 1.0], divisions = [3, 3, 3], lattice = \"bcc\" }\n"
                   "body_force = { z = -9.81 }\n"
                   "[[boundary]]\nname = \"ground\"\nregion = { box = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0]] }\n"
                   "displacement = { x = 0.0, y = 0.0, z = 0.0 }\n",
                   5);
}

}  // namespace
}  // namespace loom
