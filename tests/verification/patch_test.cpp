// Patch tests of the three element formulations (p1, tri6, p1p1_uphi; displacement patch test of the
// engineering FE literature, e.g. Zienkiewicz & Taylor, The Finite Element Method vol. 1, §10.3): an affine
// displacement u = (F - I) X prescribed on every boundary node of an irregular mesh must be reproduced at
// every interior node, because the affine field is an exact discrete solution (constant F, constant stress,
// zero internal force at every interior node) for any material and any mesh, and the solution is unique.
//  - tri6: the three-point rule integrates grad N^A (linear on a straight cell) exactly, so the interior
//    residuals P int grad N^A dV vanish exactly as for p1; mid-nodes are interior or outline nodes like any.
//  - quad9 (distorted convex quadrilaterals, the quad9 map bilinear): grad N^A det J is a polynomial of degree
//    at most 3 per direction, which the 3 x 3 Gauss rule integrates exactly; affine fields are in the span.
//  - p1p1_uphi: phi = J (uniform) makes F~ = F, and the dilatation residual -int N^A J + K_phiphi^AB phi^B
//    vanishes: sum_B M^AB = m^A and, the P1 m^B being all equal to A/3, the projection term
//    sum_B (M^AB - m^B/3) J = (m^A - A/3) J = 0. So the nodal phi must come out equal to det F.
//  - es_up, es_u, fem_up, fem_u (seed 001): the smoothed gradients are linearly complete (sum_I x_I (x) b~_I
//    = I), so every domain sees the same f and stress; the domain forces sum to P oint N^A N dS as for p1
//    (the domains tile the body). The u-p constraint holds with the uniform p = K ln J / J (Hencky) or
//    K tr eps (linear), and the PPP term vanishes on a constant pressure.
//
// Reactions (the "reaction force to 1e-8 relative against the analytic value"): for a constant P the
// nodal internal force is f^A = P int grad N^A dV = P oint N^A N dS (divergence theorem; interior edges
// cancel). Summed over the nodes of the right edge, the shape functions add up to 1 on that edge, giving
// P N_right H, plus the corner nodes' shares on the top and bottom edges, P12 (c_top - c_bottom): the outline
// nodes are not distorted and the rows are evenly spaced, so c_top = c_bottom and the corner terms cancel
// exactly. Hence reaction_x(right) = P11 H, reaction_y(right) = P21 H, reaction_y(top) = P22 W,
// reaction_x(top) = P12 W, with P from F analytically (Neo-Hooke, seed 000 eq 51: P = mu F + (lambda ln J -
// mu) F^-T; linear elastic: P = lambda tr(eps) I + 2 mu eps, eps = sym(F - I)). The precondition (outline
// spacing at the corners) is asserted.
//
// Tolerances: 1e-10 on |u_h - (F - I) X| (absolute, the displacements are O(0.1-1)) and 1e-8 relative on
// the reactions (the figure). Newton is run to |r| <= 1e-13 |r_0| and the discrete system is well
// conditioned (40-330 dofs), so the errors are round-off, observed 1e-15 .. 1e-13 (printed); a wrong element
// (a transposed gradient, a missing F_n in the pull-back, a wrong dV_0, a phi residual that does not vanish
// at phi = J) gives errors of order |F - I|.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <unsupported/Eigen/MatrixFunctions>

#include "engine/methods/model/build_mesh.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

struct PatchCase {
  std::string model;    // neo_hooke | linear_elastic
  std::string element;  // p1 | tri6 | p1p1_uphi | es_up | es_u | fem_up | fem_u
  Eigen::Matrix2d F;    // final deformation gradient (in-plane); F33 = 1
  int steps = 1;
  std::string pattern;
};

constexpr double kX0 = 0.5, kY0 = -0.25, kW = 2.0, kH = 1.0;  // an offset patch: X = 0 is not a node
constexpr double kE = 10.0, kNu = 0.3;

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
  auto probe = [](const char* name, const char* boundary, const char* component) {
    return std::string("[[probe]]\nname = \"") + name + "\"\nkind = \"reaction\"\nboundary = \"" + boundary +
           "\"\ncomponent = \"" + component + "\"\n";
  };
  const double x1 = kX0 + kW, y1 = kY0 + kH;
  std::string s = "[scene]\nname = \"patch\"\n";
  s += "[time]\nintegrator = \"static\"\ndt = " + std::to_string(1.0 / c.steps) + "\nsteps = " + std::to_string(c.steps) + "\n";
  s += "[solver]\nresidual_relative = 1e-13\nresidual_absolute = 1e-14\n";
  s += "[[material]]\nname = \"m\"\nmodel = \"" + c.model + "\"\nE = 10.0\nnu = 0.3\n";
  s += "[[body]]\nname = \"patch\"\nmaterial = \"m\"\nelement = \"" + c.element + "\"\n";
  if (c.element == "es_up" || c.element == "fem_up") s += "alpha_stab = 0.5\n";
  const std::string pattern = c.element == "quad9" ? "" : "pattern = \"" + c.pattern + "\", ";
  s += "mesh = { generator = \"rectangle\", origin = [0.5, -0.25], size = [2.0, 1.0], divisions = [6, 4], " + pattern +
       "distortion = 0.25, seed = 11 }\n";
  s += "[[boundary]]\nname = \"left\"\n" + box(kX0, kY0, kX0, y1) + disp;
  s += "[[boundary]]\nname = \"right\"\n" + box(x1, kY0, x1, y1) + disp;
  s += "[[boundary]]\nname = \"bottom\"\n" + box(kX0, kY0, x1, kY0) + disp;
  s += "[[boundary]]\nname = \"top\"\n" + box(kX0, y1, x1, y1) + disp;
  s += probe("right_x", "right", "x") + probe("right_y", "right", "y") + probe("top_x", "top", "x") + probe("top_y", "top", "y");
  s += "[output]\nevery = 0\n";
  return s;
}

bool on_outline(const Vec2& X) {
  const double tol = 1e-12;
  return std::abs(X.x() - kX0) < tol || std::abs(X.x() - kX0 - kW) < tol || std::abs(X.y() - kY0) < tol ||
         std::abs(X.y() - kY0 - kH) < tol;
}

// First Piola-Kirchhoff stress of the in-plane F (F33 = 1) in closed form.
Eigen::Matrix2d analytic_P(const std::string& model, const Eigen::Matrix2d& F) {
  const double mu = kE / (2.0 * (1.0 + kNu)), lambda = kE * kNu / ((1.0 + kNu) * (1.0 - 2.0 * kNu));
  if (model == "hencky_perzyna") {
    // Hencky: tau = 2 mu dev ln V + K tr(ln V) I, ln V = log(F F^T) / 2 (matrix logarithm), P = tau F^-T.
    const double K = lambda + 2.0 * mu / 3.0;
    Mat3 F3 = Mat3::Identity();
    F3.topLeftCorner<2, 2>() = F;
    const Mat3 lnV = 0.5 * Mat3(F3 * F3.transpose()).log();
    const Mat3 tau = 2.0 * mu * (lnV - lnV.trace() / 3.0 * Mat3::Identity()) + K * lnV.trace() * Mat3::Identity();
    return Mat3(tau * F3.inverse().transpose()).topLeftCorner<2, 2>();
  }
  if (model == "neo_hooke") {
    // F = diag(F_2d, 1): J = det F_2d and F^-T is block diagonal (seed 000 eq 51).
    return mu * F + (lambda * std::log(F.determinant()) - mu) * F.inverse().transpose();
  }
  if (model == "neo_hooke_split") {  // mu J^(-2/3) (F - F:F / 3 F^-T) + kappa (J - 1) J F^-T with F:F = |F_2d|^2 + 1, kappa = K
    const double J = F.determinant(), K = lambda + 2.0 * mu / 3.0;
    const Eigen::Matrix2d FinvT = F.inverse().transpose();
    return mu * std::pow(J, -2.0 / 3.0) * (F - (F.squaredNorm() + 1.0) / 3.0 * FinvT) + K * (J - 1.0) * J * FinvT;
  }
  const Eigen::Matrix2d eps = 0.5 * (F + F.transpose()) - Eigen::Matrix2d::Identity();  // eps33 = 0
  return lambda * eps.trace() * Eigen::Matrix2d::Identity() + 2.0 * mu * eps;
}

// Distance between the two outline nodes nearest to a corner along a side (x: along the top or bottom).
double corner_spacing(const Nodes<2>& nodes, double corner_x, double side_y) {
  double best = 1e300;
  for (Index i = 0; i < nodes.size(); ++i) {
    const Vec2 X = nodes.X[i];
    const double d = std::abs(X.x() - corner_x);
    if (std::abs(X.y() - side_y) < 1e-12 && d > 1e-12) best = std::min(best, d);
  }
  return best;
}
double corner_spacing_vertical(const Nodes<2>& nodes, double side_x, double corner_y) {
  double best = 1e300;
  for (Index i = 0; i < nodes.size(); ++i) {
    const Vec2 X = nodes.X[i];
    const double d = std::abs(X.y() - corner_y);
    if (std::abs(X.x() - side_x) < 1e-12 && d > 1e-12) best = std::min(best, d);
  }
  return best;
}

void run_patch(const PatchCase& c) {
  SCOPED_TRACE(c.model + ", " + c.element + ", pattern " + c.pattern);
  const SceneSpec scene = testing::scene_from_text(scene_text(c));

  // The mesh is irregular: interior corner nodes moved off the structured grid (outline nodes stay on it).
  MeshSpec regular_spec = scene.bodies[0].mesh;
  regular_spec.distortion = 0.0;
  const MeshData regular = generate_body_mesh(regular_spec);

  auto run = testing::make_fem_run(scene);
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  EXPECT_EQ(summary.steps_done, c.steps);

  const Nodes<2>& nodes = run->nodes();
  // tri6 appends one mid-node per edge after the corner nodes of the generated mesh.
  const std::size_t n_corners = regular.X.size();
  if (c.element == "tri6" || c.element == "quad9") ASSERT_GT(std::size_t(nodes.size()), n_corners);
  else ASSERT_EQ(std::size_t(nodes.size()), n_corners);
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
      if (std::size_t(i) < n_corners) max_offset = std::max(max_offset, (X - regular.X[std::size_t(i)]).norm());
    }
  }
  EXPECT_GE(interior, 15);             // 5 x 3 interior grid nodes at least
  EXPECT_GT(max_offset, 0.05 * 0.25);  // moved by more than 5 % of the grid spacing (0.25 across)

  // The stored deformation gradient of every point is the prescribed one (the converged history F_n; for
  // p1p1_uphi F~_n, equal to F because phi = J).
  Mat3 F_exact = Mat3::Identity();
  F_exact.topLeftCorner<2, 2>() = c.F;
  double max_F_error = 0.0;
  for (const auto& q : run->quad_points())
    for (Index p = 0; p < q.size(); ++p) max_F_error = std::max(max_F_error, (q.F_n[p] - F_exact).cwiseAbs().maxCoeff());
  EXPECT_LE(max_F_error, 1e-10);

  // es_up, fem_up: the nodal pressure is the uniform Cauchy mean stress of the material.
  if (c.element == "es_up" || c.element == "fem_up") {
    ASSERT_TRUE(nodes.p_n.used());
    const double mu = kE / (2.0 * (1.0 + kNu)), lambda = kE * kNu / ((1.0 + kNu) * (1.0 - 2.0 * kNu)), K = lambda + 2.0 * mu / 3.0;
    const double J = c.F.determinant();
    // The mean Cauchy stress (3D, plane strain): Hooke K tr eps, Hencky K ln J / J, neo_hooke tr tau / (3 J) with
    // tau_33 = lambda ln J, neo_hooke_split kappa (J - 1).
    const double tr_tau = (analytic_P(c.model, c.F) * c.F.transpose()).trace() + lambda * std::log(J);
    const double p_exact = c.model == "linear_elastic"   ? K * (c.F.trace() - 2.0)
                           : c.model == "hencky_perzyna" ? K * std::log(J) / J
                           : c.model == "neo_hooke"      ? tr_tau / (3.0 * J)
                                                         : K * (J - 1.0);
    double max_p_error = 0.0;
    for (Index i = 0; i < nodes.size(); ++i) max_p_error = std::max(max_p_error, std::abs(nodes.p_n[i] - p_exact));
    EXPECT_LE(max_p_error, 1e-10 * (1.0 + std::abs(p_exact))) << "p exact " << p_exact;
  }
  // p1p1_uphi: the nodal dilatation is det F everywhere (1e-10: the same round-off budget as u).
  double max_phi_error = 0.0;
  if (c.element == "p1p1_uphi") {
    ASSERT_TRUE(nodes.phi_n.used());
    for (Index i = 0; i < nodes.size(); ++i) max_phi_error = std::max(max_phi_error, std::abs(nodes.phi_n[i] - c.F.determinant()));
    EXPECT_LE(max_phi_error, 1e-10);
  }

  // Reactions against P N L (see the header); first the precondition that the corner shares cancel.
  EXPECT_NEAR(corner_spacing(nodes, kX0 + kW, kY0), corner_spacing(nodes, kX0 + kW, kY0 + kH), 1e-14);
  EXPECT_NEAR(corner_spacing_vertical(nodes, kX0, kY0 + kH), corner_spacing_vertical(nodes, kX0 + kW, kY0 + kH), 1e-14);
  const Eigen::Matrix2d P = analytic_P(c.model, c.F);
  const double expected[4] = {P(0, 0) * kH, P(1, 0) * kH, P(0, 1) * kW, P(1, 1) * kW};
  const char* names[4] = {"right_x", "right_y", "top_x", "top_y"};
  double worst_reaction = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double value = run->probe_values()[std::size_t(k)];
    ASSERT_EQ(scene.probes[std::size_t(k)].name, names[k]);
    const double error = std::abs(value - expected[k]) / std::abs(expected[k]);
    worst_reaction = std::max(worst_reaction, error);
    EXPECT_LE(error, 1e-8) << names[k] << ": " << value << ", analytic " << expected[k];
  }
  std::printf("[patch] %-14s %-9s %-11s steps %d: interior nodes %d, max offset %.3f, max |u - u_exact| %.2e, "
              "max |F - F_exact| %.2e, max |phi - J| %.2e, worst reaction rel. error %.2e, Newton %lld\n",
              c.model.c_str(), c.element.c_str(), c.pattern.c_str(), c.steps, interior, max_offset, max_error, max_F_error,
              max_phi_error, worst_reaction, summary.newton_iterations);
}

TEST(PatchTest, LinearElasticReproducesAnAffineSmallDisplacement) {
  // p1p1_uphi is not run with linear_elastic: its constraint phi = det F is a finite-strain one, and the
  // scene loader rejects the combination.
  Eigen::Matrix2d F;
  F << 1.0 + 2e-3, 1.5e-3, -0.5e-3, 1.0 - 1e-3;
  for (const char* element : {"p1", "tri6"})
    for (const char* pattern : {"right", "alternating", "shifted"}) run_patch({"linear_elastic", element, F, 1, pattern});
  run_patch({"linear_elastic", "quad9", F, 1, "quadrilaterals"});
}

TEST(PatchTest, NeoHookeReproducesAFiniteAffineDeformationOverSeveralSteps) {
  // Stretch 1.3 along x with shear 0.2, plus a lateral contraction and a small rotation-like F21 so that
  // every component of F differs from I (a transposed index cannot pass): J = 1.3 * 0.9 + 0.2 * 0.1 = 1.19.
  Eigen::Matrix2d F;
  F << 1.3, 0.2, -0.1, 0.9;
  for (const char* element : {"p1", "tri6", "p1p1_uphi"})
    for (const char* pattern : {"right", "alternating", "shifted"}) run_patch({"neo_hooke", element, F, 4, pattern});
  run_patch({"neo_hooke", "quad9", F, 4, "quadrilaterals"});
}

}  // namespace
}  // namespace loom

namespace loom {
namespace {

TEST(PatchTest, SmoothedFormulationsReproduceAffineFields) {
  Eigen::Matrix2d small, finite;
  small << 1.0 + 2e-3, 1.5e-3, -0.5e-3, 1.0 - 1e-3;
  finite << 1.3, 0.2, -0.1, 0.9;
  for (const char* element : {"es_up", "es_u", "fem_up", "fem_u"})
    for (const char* pattern : {"right", "shifted"}) {
      run_patch({"linear_elastic", element, small, 1, pattern});
      run_patch({"linear_elastic", element, small, 4, pattern});  // the strain of earlier steps is carried
      run_patch({"hencky_perzyna", element, finite, 4, pattern});
      run_patch({"neo_hooke", element, finite, 4, pattern});
      run_patch({"neo_hooke_split", element, finite, 4, pattern});
    }
}

}  // namespace
}  // namespace loom
