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

}  // namespace
}  // namespace loom
