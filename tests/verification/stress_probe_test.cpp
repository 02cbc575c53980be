// The stress probe (kind = "stress") reproduces a linear stress field exactly with tri6: plane-strain pure
// bending, sigma_xx = c y and the other in-plane components zero, has the quadratic displacement
//   u_x = a x y,   u_y = -(a x^2 + b y^2) / 2,   a = c (1 - nu^2) / E,   b = c nu (1 + nu) / E
// (eps_xx = a y, eps_yy = -b y, eps_xy = 0), which 6-node triangles represent exactly. Prescribed on the
// whole boundary of a unit square, the solution is this field to round-off; the probe's linear fit of the
// three quadrature points' stresses then returns sigma_xx = c y and sigma_zz = nu c y at any point, inside a
// cell or at a node shared by several. quad9 on straight-sided (bilinearly mapped) quadrilaterals holds every
// quadratic of x, y too (x^2 = (bilinear in xi, eta)^2 is in Q2); its probe interpolates the 3 x 3 Gauss values
// biquadratically, exact for the linear stress.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "engine/scene/scene_loader.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

constexpr double kE = 1000.0, kNu = 0.3, kC = 10.0;

std::string scene_text(const std::string& element) {
  const double a = kC * (1 - kNu * kNu) / kE, b = kC * kNu * (1 + kNu) / kE;
  std::ostringstream s;
  s.precision(17);
  s << "[scene]\nname = \"bending\"\nmethod = \"fem\"\n[time]\ndt = 1.0\nsteps = 1\n"
    << "[[material]]\nname = \"m\"\nmodel = \"linear_elastic\"\nE = " << kE << "\nnu = " << kNu << "\n"
    << "[[body]]\nname = \"square\"\nmaterial = \"m\"\nelement = \"" << element << "\"\n"
    << "mesh = { generator = \"rectangle\", size = [1.0, 1.0], divisions = [3, 3], "
    << (element == "quad9" ? "" : "pattern = \"alternating\", ") << "distortion = 0.2 }\n";
  const char* boxes[] = {"[[0.0, 0.0], [1.0, 0.0]]", "[[0.0, 1.0], [1.0, 1.0]]", "[[0.0, 0.0], [0.0, 1.0]]", "[[1.0, 0.0], [1.0, 1.0]]"};
  for (int k = 0; k < 4; ++k)
    s << "[[boundary]]\nname = \"side" << k << "\"\nregion = { box = " << boxes[k] << " }\n"
      << "displacement = { x = \"" << a << " * x * y\", y = \"-(" << a << " * x^2 + " << b << " * y^2) / 2\" }\n";
  const double points[][2] = {{0.3, 0.7}, {0.55, 0.2}, {1.0 / 3, 2.0 / 3}, {0.0, 1.0}};
  const char* components[] = {"xx", "yy", "xy", "zz"};
  for (int p = 0; p < 4; ++p)
    for (const char* c : components)
      s << "[[probe]]\nname = \"s" << c << "_" << p << "\"\nkind = \"stress\"\nat = [" << points[p][0] << ", " << points[p][1] << "]\ncomponent = \"" << c
        << "\"\n";
  s << "[output]\nevery = 0\n";
  return s.str();
}

void check_bending(const std::string& element) {
  SCOPED_TRACE(element);
  const SceneSpec scene = load_scene_text(scene_text(element), "bending.toml", {});
  auto r = testing::make_fem_run(scene);
  ASSERT_TRUE(r->run().converged);
  // The points' y: inside cells of the distorted mesh, and the corner node (0, 1), which boundaries do not move.
  const double y[] = {0.7, 0.2, 2.0 / 3, 1.0};
  for (int p = 0; p < 4; ++p) {
    const double* v = r->probe_values().data() + 4 * p;
    EXPECT_NEAR(v[0], kC * y[p], 1e-10 * kC) << "point " << p;
    EXPECT_NEAR(v[1], 0.0, 1e-10 * kC) << "point " << p;
    EXPECT_NEAR(v[2], 0.0, 1e-10 * kC) << "point " << p;
    EXPECT_NEAR(v[3], kNu * kC * y[p], 1e-10 * kC) << "point " << p;
  }
}

TEST(StressProbe, ReproducesTheLinearStressOfPureBendingAtAnyPointWithTri6) { check_bending("tri6"); }

TEST(StressProbe, ReproducesTheLinearStressOfPureBendingAtAnyPointWithQuad9) { check_bending("quad9"); }

// 3D: pure bending of a unit cube, sigma_xx = c y and the other five components zero, has the quadratic displacement
//   u_x = c x y / E,   u_y = -c (x^2 + nu (y^2 - z^2)) / (2 E),   u_z = -nu c y z / E,
// which 10-node tetrahedra represent exactly; prescribed on the whole boundary of a distorted box, the probe's linear
// fit of each cell's four point stresses returns sigma_xx = c y and zero shear at any point, inside a cell, on a face
// and at a node. Every component is read.
// The six faces of the unit cube as region boxes.
const char* const kCubeFaces[6] = {"[[0.0, 0.0, 0.0], [0.0, 1.0, 1.0]]", "[[1.0, 0.0, 0.0], [1.0, 1.0, 1.0]]", "[[0.0, 0.0, 0.0], [1.0, 0.0, 1.0]]",
                                   "[[0.0, 1.0, 0.0], [1.0, 1.0, 1.0]]", "[[0.0, 0.0, 0.0], [1.0, 1.0, 0.0]]", "[[0.0, 0.0, 1.0], [1.0, 1.0, 1.0]]"};

// A static linear elastic unit cube of n^3 distorted Kuhn boxes of `element` (3D), without boundaries or probes.
void write_cube_scene(std::ostringstream& s, const char* element, int n) {
  s.precision(17);
  s << "[scene]\nname = \"cube\"\nmethod = \"fem\"\ndimension = 3\n[time]\ndt = 1.0\nsteps = 1\n"
    << "[[material]]\nname = \"m\"\nmodel = \"linear_elastic\"\nE = " << kE << "\nnu = " << kNu << "\n"
    << "[[body]]\nname = \"cube\"\nmaterial = \"m\"\nelement = \"" << element << "\"\n"
    << "mesh = { generator = \"box\", origin = [0.0, 0.0, 0.0], size = [1.0, 1.0, 1.0], divisions = [" << n << ", " << n << ", " << n
    << "], distortion = 0.2 }\n";
}

std::string bending_3d_text() {
  std::ostringstream s;
  write_cube_scene(s, "tet10", 2);
  for (int k = 0; k < 6; ++k)
    s << "[[boundary]]\nname = \"face" << k << "\"\nregion = { box = " << kCubeFaces[k] << " }\n"
      << "displacement = { x = \"" << kC / kE << " * x * y\", y = \"-" << kC / (2 * kE) << " * (x^2 + " << kNu << " * (y^2 - z^2))\", z = \"-"
      << kNu * kC / kE << " * y * z\" }\n";
  const double points[][3] = {{0.3, 0.7, 0.4}, {0.55, 0.2, 0.9}, {0.5, 1.0 / 3, 0.0}, {0.0, 1.0, 1.0}};
  const char* components[] = {"xx", "yy", "zz", "xy", "yz", "xz", "von_mises", "pressure"};
  for (int p = 0; p < 4; ++p)
    for (const char* c : components)
      s << "[[probe]]\nname = \"s" << c << "_" << p << "\"\nkind = \"stress\"\nat = [" << points[p][0] << ", " << points[p][1] << ", "
        << points[p][2] << "]\ncomponent = \"" << c << "\"\n";
  s << "[output]\nevery = 0\n";
  return s.str();
}

TEST(StressProbe, ReproducesTheLinearStressOfPureBendingAtAnyPointWithTet10) {
  const SceneSpec scene = load_scene_text(bending_3d_text(), "bending.toml", {});
  auto r = testing::make_fem_run<3>(scene);
  ASSERT_TRUE(r->run().converged);
  const double y[] = {0.7, 0.2, 1.0 / 3, 1.0};
  for (int p = 0; p < 4; ++p) {
    const double* v = r->probe_values().data() + 8 * p;
    const double sxx = kC * y[p];
    EXPECT_NEAR(v[0], sxx, 1e-10 * kC) << "point " << p;
    for (int k = 1; k < 6; ++k) EXPECT_NEAR(v[k], 0.0, 1e-10 * kC) << "point " << p << ", component " << k;
    EXPECT_NEAR(v[6], std::abs(sxx), 1e-10 * kC) << "point " << p;  // uniaxial: von Mises = |sigma_xx|
    EXPECT_NEAR(v[7], -sxx / 3.0, 1e-10 * kC) << "point " << p;
  }
}

// 3D, a homogeneous strain with every shear component: u = G X on the boundary of a distorted box of linear
// tetrahedra; sigma = lambda tr(eps) I + 2 mu eps, eps = sym(G), read to round-off at a point and at a node.
TEST(StressProbe, ReadsEveryComponentOfAHomogeneousStressWithLinearTetrahedra) {
  Mat3 G;
  G << 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 10.0;
  G *= 1e-3;
  std::ostringstream s;
  write_cube_scene(s, "p1", 3);
  for (int k = 0; k < 6; ++k) {
    s << "[[boundary]]\nname = \"face" << k << "\"\nregion = { box = " << kCubeFaces[k] << " }\ndisplacement = { ";
    for (int i = 0; i < 3; ++i)
      s << "xyz"[i] << " = \"" << G(i, 0) << " * x + " << G(i, 1) << " * y + " << G(i, 2) << " * z\"" << (i < 2 ? ", " : " }\n");
  }
  const char* components[] = {"xx", "yy", "zz", "xy", "yz", "xz", "von_mises", "pressure"};
  const char* points[] = {"[0.4, 0.45, 0.6]", "[1.0, 0.0, 1.0]"};
  for (int p = 0; p < 2; ++p)
    for (const char* c : components)
      s << "[[probe]]\nname = \"s" << c << "_" << p << "\"\nkind = \"stress\"\nat = " << points[p] << "\ncomponent = \"" << c << "\"\n";
  s << "[output]\nevery = 0\n";
  auto r = testing::make_fem_run<3>(load_scene_text(s.str(), "homogeneous.toml", {}));
  ASSERT_TRUE(r->run().converged);
  const double lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu)), mu = kE / (2 * (1 + kNu));
  const Mat3 eps = 0.5 * (G + G.transpose());
  const Mat3 sigma = lambda * eps.trace() * Mat3::Identity() + 2 * mu * eps;
  const Mat3 dev = sigma - sigma.trace() / 3.0 * Mat3::Identity();
  const double expected[] = {sigma(0, 0), sigma(1, 1), sigma(2, 2), sigma(0, 1), sigma(1, 2), sigma(0, 2), std::sqrt(1.5 * dev.squaredNorm()),
                             -sigma.trace() / 3.0};
  for (int p = 0; p < 2; ++p)
    for (int k = 0; k < 8; ++k) EXPECT_NEAR(r->probe_values()[std::size_t(8 * p + k)], expected[k], 1e-10 * sigma.norm()) << "point " << p << ", component " << k;
}

}  // namespace
}  // namespace loom
