// The 3D patch test of the face-smoothed elements (es_up, es_u) and their element-integrated twins (fem_up,
// fem_u) through the fem recipe: a distorted Kuhn box and a distorted BCC lattice whose six faces are held at
// u = t (F - I) X reproduce the affine field at every node, the deformation gradient of every tetrahedron, the
// nodal pressure p = K tr(eps) (Hooke) or K ln J / J (Hencky), and the face reactions P N A (a uniform P gives the
// nodal forces P int grad N_I dV whatever the smoothing, and the strips along a face's edges cancel in pairs on
// the undistorted outline). Small strain over one and four steps (the history carries the earlier strain), and a
// finite deformation with every component of F off the identity: Hencky, neo_hooke and neo_hooke_split (the nodal
// pressure then the material's mean stress tr tau / (3 J), and kappa (J - 1)).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include <unsupported/Eigen/MatrixFunctions>

#include "tests/support/test_support.hpp"

namespace loom {
namespace {

const Vec3 kOrigin(0.5, -0.25, 0.1), kSize(2.0, 1.0, 1.2);
constexpr double kE = 10.0, kNu = 0.3;

struct Case {
  std::string model, element, lattice;
  Mat3 F;
  int steps = 1;
};

std::string scene_text(const Case& c) {
  const char* axis[3] = {"x", "y", "z"};
  std::string disp = "displacement = { ";
  for (int i = 0; i < 3; ++i) {
    char u[200];
    std::snprintf(u, sizeof u, "%s = \"t * (%.17g * x + %.17g * y + %.17g * z)\"%s", axis[i], c.F(i, 0) - (i == 0), c.F(i, 1) - (i == 1),
                  c.F(i, 2) - (i == 2), i < 2 ? ", " : " }\n");
    disp += u;
  }
  const Vec3 hi = kOrigin + kSize;
  const auto face = [&](const char* name, int axis_index, double at) {
    Vec3 lo = kOrigin, up = hi;
    lo[axis_index] = up[axis_index] = at;
    char b[300];
    std::snprintf(b, sizeof b, "[[boundary]]\nname = \"%s\"\nregion = { box = [[%.17g, %.17g, %.17g], [%.17g, %.17g, %.17g]] }\n", name,
                  lo.x(), lo.y(), lo.z(), up.x(), up.y(), up.z());
    return std::string(b) + disp;
  };
  std::string s = "[scene]\nname = \"patch-3d\"\ndimension = 3\n";
  s += "[time]\nintegrator = \"static\"\ndt = " + std::to_string(1.0 / c.steps) + "\nsteps = " + std::to_string(c.steps) + "\n";
  s += "[solver]\nresidual_relative = 1e-13\nresidual_absolute = 1e-14\n";
  s += "[[material]]\nname = \"m\"\nmodel = \"" + c.model + "\"\nE = 10.0\nnu = 0.3\n";
  s += "[[body]]\nname = \"patch\"\nmaterial = \"m\"\nelement = \"" + c.element + "\"\n";
  if (c.element == "es_up" || c.element == "fem_up") s += "alpha_stab = 0.5\n";
  s += "mesh = { generator = \"box\", origin = [0.5, -0.25, 0.1], size = [2.0, 1.0, 1.2], divisions = [4, 3, 3], lattice = \"" + c.lattice +
       "\", distortion = 0.25, seed = 3 }\n";
  s += face("x0", 0, kOrigin.x()) + face("x1", 0, hi.x()) + face("y0", 1, kOrigin.y()) + face("y1", 1, hi.y()) + face("z0", 2, kOrigin.z()) +
       face("z1", 2, hi.z());
  for (const char* b : {"x1", "y1", "z1"})
    for (const char* a : axis)
      s += std::string("[[probe]]\nname = \"") + b + "_" + a + "\"\nkind = \"reaction\"\nboundary = \"" + b + "\"\ncomponent = \"" + a + "\"\n";
  s += "[output]\nevery = 0\n";
  return s;
}

Mat3 analytic_P(const std::string& model, const Mat3& F) {
  const double mu = kE / (2.0 * (1.0 + kNu)), lambda = kE * kNu / ((1.0 + kNu) * (1.0 - 2.0 * kNu)), K = lambda + 2.0 * mu / 3.0;
  const double J = F.determinant();
  const Mat3 FinvT = F.inverse().transpose();
  if (model == "neo_hooke") return mu * F + (lambda * std::log(J) - mu) * FinvT;
  if (model == "neo_hooke_split")  // mu J^(-2/3) (F - F:F / 3 F^-T) + kappa (J - 1) J F^-T, kappa = K
    return mu * std::pow(J, -2.0 / 3.0) * (F - F.squaredNorm() / 3.0 * FinvT) + K * (J - 1.0) * J * FinvT;
  if (model == "hencky_perzyna") {
    const Mat3 lnV = 0.5 * Mat3(F * F.transpose()).log();
    const Mat3 tau = 2.0 * mu * (lnV - lnV.trace() / 3.0 * Mat3::Identity()) + K * lnV.trace() * Mat3::Identity();
    return tau * F.inverse().transpose();
  }
  const Mat3 eps = 0.5 * (F + F.transpose()) - Mat3::Identity();
  return lambda * eps.trace() * Mat3::Identity() + 2.0 * mu * eps;
}

void run_patch(const Case& c) {
  SCOPED_TRACE(c.model + ", " + c.element + ", " + c.lattice + ", steps " + std::to_string(c.steps));
  const SceneSpec scene = testing::scene_from_text(scene_text(c));
  auto run = testing::make_fem_run<3>(scene);
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const Nodes<3>& nodes = run->nodes();
  double u_error = 0.0;
  int interior = 0;
  for (Index i = 0; i < nodes.size(); ++i) {
    const Vec3 X = nodes.X[i];
    u_error = std::max(u_error, (nodes.u_n[i] - (c.F - Mat3::Identity()) * X).norm());
    const Vec3 s = (X - kOrigin).cwiseQuotient(kSize);
    interior += s.minCoeff() > 1e-12 && s.maxCoeff() < 1 - 1e-12;
  }
  EXPECT_GE(interior, 12);  // 3 x 2 x 2 interior lattice nodes at least, moved off the lattice by the distortion
  EXPECT_LE(u_error, 1e-12);
  double F_error = 0.0;
  for (const auto& q : run->quad_points())
    for (Index p = 0; p < q.size(); ++p) F_error = std::max(F_error, (q.F_n[p] - c.F).cwiseAbs().maxCoeff());
  EXPECT_LE(F_error, 1e-12);
  double p_error = 0.0;
  if (c.element == "es_up" || c.element == "fem_up") {
    const double mu = kE / (2.0 * (1.0 + kNu)), lambda = kE * kNu / ((1.0 + kNu) * (1.0 - 2.0 * kNu)), K = lambda + 2.0 * mu / 3.0;
    const double J = c.F.determinant();
    // The mean Cauchy stress: Hooke K tr eps, Hencky K ln J / J, neo_hooke tr tau / (3 J), neo_hooke_split kappa (J - 1).
    const double tr_tau = (analytic_P(c.model, c.F) * c.F.transpose()).trace();
    const double p_exact = c.model == "linear_elastic"   ? K * (c.F.trace() - 3.0)
                           : c.model == "hencky_perzyna" ? K * std::log(J) / J
                           : c.model == "neo_hooke"      ? tr_tau / (3.0 * J)
                                                         : K * (J - 1.0);
    for (Index i = 0; i < nodes.size(); ++i) p_error = std::max(p_error, std::abs(nodes.p_n[i] - p_exact));
    EXPECT_LE(p_error, 1e-11 * (1.0 + std::abs(p_exact))) << "p exact " << p_exact;
  }
  const Mat3 P = analytic_P(c.model, c.F);
  const double area[3] = {kSize.y() * kSize.z(), kSize.x() * kSize.z(), kSize.x() * kSize.y()};
  double reaction_error = 0.0;
  for (int face = 0; face < 3; ++face)
    for (int i = 0; i < 3; ++i) {
      const double expected = P(i, face) * area[face];
      const double value = run->probe_values()[std::size_t(3 * face + i)];
      reaction_error = std::max(reaction_error, std::abs(value - expected));
      EXPECT_NEAR(value, expected, 1e-11 * P.cwiseAbs().maxCoeff() * area[face]) << "face " << face << " component " << i;
    }
  std::printf("[patch 3d] %-14s %-6s %-4s steps %d: max |u - u_exact| %.1e, |F - F_exact| %.1e, |p - p_exact| %.1e, reactions %.1e, "
              "Newton %lld\n",
              c.model.c_str(), c.element.c_str(), c.lattice.c_str(), c.steps, u_error, F_error, p_error, reaction_error,
              summary.newton_iterations);
}

TEST(SmoothedPatch3d, AffineFieldsAreExactOnDistortedTetrahedra) {
  Mat3 small, finite;
  small << 1.0 + 2e-3, 1.5e-3, -0.5e-3, -0.7e-3, 1.0 - 1e-3, 0.4e-3, 0.9e-3, 0.3e-3, 1.0 + 0.6e-3;
  finite << 1.3, 0.2, -0.1, -0.1, 0.9, 0.15, 0.05, -0.2, 1.1;
  for (const char* element : {"es_up", "es_u", "fem_up", "fem_u"})
    for (const char* lattice : {"kuhn", "bcc"}) {
      run_patch({"linear_elastic", element, lattice, small, 1});
      run_patch({"linear_elastic", element, lattice, small, 4});
      run_patch({"hencky_perzyna", element, lattice, finite, 4});
      run_patch({"neo_hooke", element, lattice, finite, 4});
      run_patch({"neo_hooke_split", element, lattice, finite, 4});
    }
}

}  // namespace
}  // namespace loom
