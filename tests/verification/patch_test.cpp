// Patch tests of the P1 updated-Lagrangian element (displacement patch test of the engineering FE
// literature, e.g. Zienkiewicz & Taylor, The Finite Element Method vol. 1, §10.3): an affine displacement
// u = (F - I) X prescribed on every boundary node of an irregular mesh must be reproduced at every interior
// node, because the affine field is an exact discrete solution (constant F, constant stress, zero internal
// force at every interior node) for any material and any mesh, and the solution is unique.
//
// Tolerance 1e-10 on |u_h - (F - I) X| (absolute, the displacements are O(0.1-1)): Newton is run to
// |r| <= 1e-13 |r_0| and the discrete system is well conditioned (about 40 dofs), so the error is round-off,
// observed 1e-15 .. 1e-14; a wrong element (a transposed gradient, a missing F_n in the pull-back, a
// wrong dV_0) gives errors of order |F - I|.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "engine/methods/build_mesh.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

struct PatchCase {
  std::string model;  // neo_hooke | linear_elastic
  Eigen::Matrix2d F;  // final deformation gradient (in-plane); F33 = 1
  int steps = 1;
  std::string pattern;
};

constexpr double kX0 = 0.5, kY0 = -0.25, kW = 2.0, kH = 1.0;  // an offset patch: X = 0 is not a node

std::string scene_text(const PatchCase& c) {
  char ux[160], uy[160];
  // Load ramp u(t) = t (F - I) X with t = step / steps: every intermediate state is affine too.
  std::snprintf(ux, sizeof ux, "t * (%.17g * x + %.17g * y)", c.F(0, 0) - 1.0, c.F(0, 1));
  std::snprintf(uy, sizeof uy, "t * (%.17g * x + %.17g * y)", c.F(1, 0), c.F(1, 1) - 1.0);
  const std::string disp = std::string("displacement = { x = \"") + ux + "\", y = \"" + uy + "\" }\n";
  auto box = [](double x0, double y0, double x1, double y1) {
    char b[160];
    std::snprintf(b, sizeof b, "region = { box = [[%.17g, %.17g], [%.17g, %.17g]] }\n", x0, y0, x1, y1);
    return std::string(b);
  };
  const double x1 = kX0 + kW, y1 = kY0 + kH;
  std::string s = "[scene]\nname = \"patch\"\n";
  s += "[time]\nintegrator = \"static\"\ndt = " + std::to_string(1.0 / c.steps) + "\nsteps = " + std::to_string(c.steps) + "\n";
  s += "[solver]\nresidual_relative = 1e-13\nresidual_absolute = 1e-14\n";
  s += "[[material]]\nname = \"m\"\nmodel = \"" + c.model + "\"\nE = 10.0\nnu = 0.3\n";
  s += "[[body]]\nname = \"patch\"\nmaterial = \"m\"\n";
  s += "mesh = { generator = \"rectangle\", origin = [0.5, -0.25], size = [2.0, 1.0], divisions = [6, 4], pattern = \"" +
       c.pattern + "\", distortion = 0.25, seed = 11 }\n";
  s += "[[boundary]]\nname = \"left\"\n" + box(kX0, kY0, kX0, y1) + disp;
  s += "[[boundary]]\nname = \"right\"\n" + box(x1, kY0, x1, y1) + disp;
  s += "[[boundary]]\nname = \"bottom\"\n" + box(kX0, kY0, x1, kY0) + disp;
  s += "[[boundary]]\nname = \"top\"\n" + box(kX0, y1, x1, y1) + disp;
  s += "[output]\nevery = 0\n";
  return s;
}

bool on_outline(const Vec2& X) {
  const double tol = 1e-12;
  return std::abs(X.x() - kX0) < tol || std::abs(X.x() - kX0 - kW) < tol || std::abs(X.y() - kY0) < tol ||
         std::abs(X.y() - kY0 - kH) < tol;
}

void run_patch(const PatchCase& c) {
  SCOPED_TRACE(c.model + ", pattern " + c.pattern);
  const SceneSpec scene = testing::scene_from_text(scene_text(c));

  // The mesh is irregular: interior nodes moved off the structured grid (boundary nodes stay on it).
  MeshSpec regular_spec = scene.bodies[0].mesh;
  regular_spec.distortion = 0.0;
  const MeshData regular = generate_body_mesh(regular_spec);

  auto run = testing::make_fem_run(scene);
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  EXPECT_EQ(summary.steps_done, c.steps);

  const Nodes<2>& nodes = run->nodes();
  ASSERT_EQ(std::size_t(nodes.size()), regular.X.size());
  int interior = 0;
  double max_offset = 0.0, max_error = 0.0;
  for (Index i = 0; i < nodes.size(); ++i) {
    const Vec2 X = nodes.X[i];
    const Vec2 exact = (c.F - Eigen::Matrix2d::Identity()) * X;
    const double error = (nodes.u_n[i] - exact).norm();
    max_error = std::max(max_error, error);
    EXPECT_LE(error, 1e-10) << "node " << i << " at (" << X.x() << ", " << X.y() << ")";
    if (!on_outline(X)) {
      ++interior;
      max_offset = std::max(max_offset, (X - regular.X[std::size_t(i)]).norm());
    }
  }
  EXPECT_GE(interior, 15);           // 5 x 3 interior grid nodes at least
  EXPECT_GT(max_offset, 0.05 * 0.25);  // moved by more than 5 % of the grid spacing (0.25 across)

  // The stored deformation gradient of every cell is the prescribed one (the converged history F_n).
  double max_F_error = 0.0;
  for (const auto& q : run->quad_points())
    for (Index p = 0; p < q.size(); ++p) {
      Mat3 exact = Mat3::Identity();
      exact.topLeftCorner<2, 2>() = c.F;
      max_F_error = std::max(max_F_error, (q.F_n[p] - exact).cwiseAbs().maxCoeff());
    }
  EXPECT_LE(max_F_error, 1e-10);
  std::printf("[patch] %-14s %-11s steps %d: interior nodes %d, max offset %.3f, max |u - u_exact| %.2e, max |F - F_exact| %.2e, Newton %lld\n",
              c.model.c_str(), c.pattern.c_str(), c.steps, interior, max_offset, max_error, max_F_error,
              summary.newton_iterations);
}

TEST(PatchTest, LinearElasticReproducesAnAffineSmallDisplacement) {
  Eigen::Matrix2d F;
  F << 1.0 + 2e-3, 1.5e-3, -0.5e-3, 1.0 - 1e-3;
  for (const char* pattern : {"right", "alternating", "shifted"}) run_patch({"linear_elastic", F, 1, pattern});
}

TEST(PatchTest, NeoHookeReproducesAFiniteAffineDeformationOverSeveralSteps) {
  // Stretch 1.3 along x with shear 0.2, plus a lateral contraction and a small rotation-like F21 so that
  // every component of F differs from I (a transposed index cannot pass): J = 1.3 * 0.9 + 0.2 * 0.1 = 1.19.
  Eigen::Matrix2d F;
  F << 1.3, 0.2, -0.1, 0.9;
  for (const char* pattern : {"right", "alternating", "shifted"}) run_patch({"neo_hooke", F, 4, pattern});
}

}  // namespace
}  // namespace loom
