// Cook's membrane with the biquadratic quadrilateral (element = "quad9", method fem): the committed Cook's
// scenes on n x n quadrilaterals instead of triangles (their `pattern` removed: quad9 keeps the
// quadrilaterals). References (../shared/REFERENCES.md; point C = (48, 60)):
//   linear, E = 70, nu = 1/3:                 u_y(C) = 32.28
//   linear, E = 250, nu = 0.4999:             u_y(C) = 7.771
//   Neo-Hooke, E = 70, nu = 0.4999, load 1:   u_y(C) = 0.2758
//
// Observed u_y(C):
//   n                     4        8        16       32       64
//   linear nu = 1/3       31.511   31.930   32.133   32.222   32.263
//   linear nu = 0.4999    6.709    7.298    7.549    7.666    7.722
//   Neo-Hooke 0.4999      0.23832  0.25934  0.26830  0.27242  0.27440
// Monotone from below at rate 1.1-1.2 (the corner C is singular: rate about 1 even for quadratic elements).
// quad9 on n x n has the nodes of tri6 on n x n (2n + 1)^2 and follows it closely (tri6 Neo-Hooke: 0.27216 at
// 32, 0.27441 at 64): the displacement element locks mildly at nu = 0.4999, as tri6 does, and converges.
// Richardson on 16-32-64: 32.298 (+0.06 %), 7.77x, 0.2762 (+0.16 %).
//
// Tolerances: the finest mesh run within 0.5 % (nu = 1/3, n = 32: -0.18 % observed) and 1 % (Neo-Hooke,
// n = 64: -0.51 %); the Richardson limits within 0.3 % of the references (as the tri6 tests).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/test_support.hpp"
#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

// The committed scene's text without its triangulation pattern.
std::string quadrilateral_scene(const std::string& file) {
  std::ifstream in(verification::scene_path(file));
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = std::regex_replace(text.str(), std::regex(R"(, pattern = "[a-z]+")"), "");
  EXPECT_NE(s, text.str()) << file << " names no pattern any more: drop the regex";
  return s;
}

double tip(const std::string& file, int n, std::vector<std::string> overrides) {
  overrides.insert(overrides.end(), {"body[0].element=quad9", "body[0].mesh.divisions=[" + std::to_string(n) + "," + std::to_string(n) + "]",
                                     "output.every=0"});
  const SceneSpec scene = testing::scene_from_text(quadrilateral_scene(file), overrides);
  EXPECT_EQ(scene.bodies[0].element, Formulation::quad9);
  const auto r = verification::run_scene(scene);
  EXPECT_TRUE(r.summary.converged) << file << ", n = " << n << ": " << r.summary.failure;
  std::printf("[cooks quad9] %-40s n = %2d: u_y(C) = %.5f, %.2f s\n", file.c_str(), n, r.probes.at("uy_C"), r.seconds);
  return r.probes.at("uy_C");
}

// u(h), u(h/2), u(h/4) -> the limit u(h/4) + d2 / (d1 / d2 - 1).
double richardson(double u1, double u2, double u3) {
  const double d1 = u2 - u1, d2 = u3 - u2;
  return u3 + d2 / (d1 / d2 - 1.0);
}

void check_series(const std::string& file, const std::vector<std::string>& overrides, const std::vector<int>& n, double reference,
                  double finest_tolerance) {
  std::vector<double> u;
  for (int k : n) u.push_back(tip(file, k, overrides));
  for (std::size_t k = 1; k < u.size(); ++k) EXPECT_GT(u[k], u[k - 1]) << "n = " << n[k];  // monotone from below
  EXPECT_LT(u.back(), reference);
  EXPECT_LE(std::abs(u.back() - reference) / reference, finest_tolerance);
  const double limit = richardson(u[u.size() - 3], u[u.size() - 2], u.back());
  EXPECT_LE(std::abs(limit - reference) / reference, 3e-3) << "Richardson limit " << limit;
  std::printf("[cooks quad9] %s: finest %.5f (%+.2f %%), Richardson %.5f (%+.2f %%)\n", file.c_str(), u.back(),
              100 * (u.back() / reference - 1), limit, 100 * (limit / reference - 1));
}

TEST(CooksMembraneQuad9, LinearCompressibleConvergesTo3228) {
  check_series("cooks_membrane_linear.toml", {"material[0].E=70", "material[0].nu=0.3333333333333333"}, {8, 16, 32}, 32.28, 5e-3);
}

TEST(CooksMembraneQuad9, NeoHookeNearlyIncompressibleConvergesTo02758) {
  check_series("cooks_membrane_nearly_incompressible.toml", {}, {16, 32, 64}, 0.2758, 1e-2);
}

}  // namespace
}  // namespace loom
