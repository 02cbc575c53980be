// Cook's membrane, linear elasticity, plane strain (scenes/cooks_membrane_linear.toml): refinement series of
// the P1 element with n x n divisions, n = 4 ... 64, for both triangulation patterns.
//
// References (../shared/REFERENCES.md, "Cook's membrane, linear elasticity"; point C = (48, 60), the top
// right corner, M = (48, 52), the middle of the loaded edge; load F = 100, traction 6.25):
//   E = 70,  nu = 1/3:    u_y(C) = 32.28 (32.28-32.30; Calculix 32.27, Elmer 32.28)
//   E = 250, nu = 0.4999: u_y(C) = 7.771, u_y(M) = 7.405 (converged P2-P1, extrapolated)
// The full table (n up to 128) is docs/verification/cooks_membrane_linear_p1.csv; this test runs only the
// meshes its assertions need (20 linear solves, < 2 s).
//
// Findings the assertions pin down (numbers in the comments are the observed values):
//  - nu = 1/3: u_y(C) rises monotonically toward 32.28 from below on both patterns, at an observed rate of
//    about 1.4-1.5 (REFERENCES.md observes rate about 1 at this corner even for quadratic elements; P1
//    point values of smooth solutions converge at 2).
//  - nu = 0.4999 on the 'right' pattern: P1 locks. u_y(C) is 27-35 % of 7.771 on every mesh up to n = 64
//    (against 87-98 % for nu = 1/3 on the same n = 16-64 meshes) and its error shrinks by only 10 % from n = 16 to 64
//    (observed rate 0.08 against 1.47 compressible).
//  - nu = 0.4999 on the 'alternating' pattern: P1 does NOT lock. Every node of degree 4 of this
//    checkerboard triangulation is a "singular vertex" (its edges lie on two straight lines; the bilinear
//    map of the Cook's generator keeps grid lines straight), at which the divergence constraints of the
//    four cells are linearly dependent, so the constraint count falls below the dof count (Scott &
//    Vogelius 1985). u_y(C) converges to 7.771 at rate about 1.2, 91 % of it at n = 16. The committed scene
//    uses this pattern, so it is not a locking baseline; use pattern = "right" for that.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

constexpr double kRefCompressibleC = 32.28;  // E = 70, nu = 1/3
constexpr double kRefLockingC = 7.771;       // E = 250, nu = 0.4999
constexpr double kRefLockingM = 7.405;
const std::vector<int> kDivisions = {4, 8, 16, 32, 64};

struct Series {
  std::vector<double> uy_C, uy_M;
  std::vector<long long> dofs;
};

// Successive halvings u(h), u(h/2), u(h/4): observed rate p = log2(d1 / d2) and the Richardson limit
// u(h/4) + d2 / (2^p - 1), with d1 = u(h/2) - u(h), d2 = u(h/4) - u(h/2).
struct Extrapolation {
  double rate, limit;
};
Extrapolation extrapolate(double u_h, double u_h2, double u_h4) {
  const double d1 = u_h2 - u_h, d2 = u_h4 - u_h2, q = d1 / d2;
  return {std::log2(q), u_h4 + d2 / (q - 1.0)};
}

class CooksMembraneLinear : public ::testing::Test {
 protected:
  // Runs are shared by the tests of the suite: material case ("compressible" | "nu_04999") and pattern.
  static const Series& series(const std::string& material, const std::string& pattern) {
    static std::map<std::string, Series> cache;
    const std::string key = material + "/" + pattern;
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    const auto start = std::chrono::steady_clock::now();
    Series s;
    for (int n : kDivisions) {
      std::vector<std::string> overrides = {"body[0].mesh.divisions=[" + std::to_string(n) + "," + std::to_string(n) + "]",
                                            "body[0].mesh.pattern=\"" + pattern + "\"", "output.every=0"};
      if (material == "compressible") {
        overrides.push_back("material[0].E=70.0");
        overrides.push_back("material[0].nu=0.3333333333333333");
      }
      const SceneSpec scene = load_scene(verification::scene_path("cooks_membrane_linear.toml"), overrides);
      const auto r = verification::run_scene(scene);
      EXPECT_TRUE(r.summary.converged) << key << " n = " << n << ": " << r.summary.failure;
      // Equilibrium of the whole membrane: the clamp carries the applied load 100 (a wrong traction
      // integration or load scaling fails here before any convergence argument).
      EXPECT_NEAR(r.probes.at("reaction_y"), -100.0, 1e-5) << key << " n = " << n;
      s.uy_C.push_back(r.probes.at("uy_C"));
      s.uy_M.push_back(r.probes.at("uy_M"));
      s.dofs.push_back(r.summary.dofs);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double ref = material == "compressible" ? kRefCompressibleC : kRefLockingC;
    std::printf("[cooks linear] %s, pattern %s (%.2f s)\n   n   dofs      u_y(C)      u_y(M)   u_y(C)/ref\n", material.c_str(),
                pattern.c_str(), seconds);
    for (std::size_t k = 0; k < kDivisions.size(); ++k)
      std::printf("%4d %6lld %11.6f %11.6f %10.4f\n", kDivisions[k], s.dofs[k], s.uy_C[k], s.uy_M[k], s.uy_C[k] / ref);
    return cache.emplace(key, s).first->second;
  }
};

TEST_F(CooksMembraneLinear, CompressibleTipDisplacementConvergesMonotonicallyToTheReference) {
  for (const char* pattern : {"right", "alternating"}) {
    SCOPED_TRACE(pattern);
    const Series& s = series("compressible", pattern);
    // Monotone approach from below (P1 is too stiff): every refinement increases u_y(C), never past 32.28.
    for (std::size_t k = 0; k < kDivisions.size(); ++k) {
      EXPECT_LT(s.uy_C[k], kRefCompressibleC) << "n = " << kDivisions[k];
      if (k > 0) {
        EXPECT_GT(s.uy_C[k], s.uy_C[k - 1]) << "n = " << kDivisions[k];
      }
    }
    const auto e = extrapolate(s.uy_C[2], s.uy_C[3], s.uy_C[4]);  // n = 16, 32, 64
    const double remaining = e.limit - s.uy_C[4], error = kRefCompressibleC - s.uy_C[4];
    std::printf("[cooks linear] nu = 1/3 %s: rate %.3f, Richardson limit %.4f (ref %.2f, rel %.1e), n = 64 error %.4f "
                "(%.2f %%), predicted %.4f\n",
                pattern, e.rate, e.limit, kRefCompressibleC, verification::relative_error(e.limit, kRefCompressibleC), error,
                100.0 * error / kRefCompressibleC, remaining);
    // Observed rates 1.47 (right) and 1.38 (alternating): between the corner-limited 1 and the smooth 2.
    EXPECT_GT(e.rate, 1.0);
    EXPECT_LT(e.rate, 2.0);
    // The series extrapolates to the reference: 32.275 (right) and 32.256 (alternating); 0.2 % is three
    // times the spread of the published values (32.27-32.30) and twice the worst observed gap, which comes
    // from the rate still drifting (alternating: 1.38 between 16-32-64, 1.30 between 32-64-128).
    EXPECT_LE(verification::relative_error(e.limit, kRefCompressibleC), 2e-3);
    // The finest mesh is as far from the reference as its observed rate predicts (error / predicted remaining
    // error: 1.01 right, 1.09 alternating): the reference lies where this series is going, at 1.8 % (right)
    // and 0.9 % (alternating) below it at n = 64.
    EXPECT_GT(error / remaining, 0.7);
    EXPECT_LT(error / remaining, 1.5);
    EXPECT_LT(error / kRefCompressibleC, 0.025);
  }
}

TEST_F(CooksMembraneLinear, NearlyIncompressibleLocksOnTheRightPattern) {
  const Series& locked = series("nu_04999", "right");
  const Series& compressible = series("compressible", "right");
  for (std::size_t k = 2; k < kDivisions.size(); ++k) {  // n = 16, 32, 64
    const double ratio = locked.uy_C[k] / kRefLockingC, ratio_compressible = compressible.uy_C[k] / kRefCompressibleC;
    std::printf("[cooks linear] right n = %d: u_y(C)/ref %.3f at nu = 0.4999 against %.3f at nu = 1/3\n", kDivisions[k], ratio,
                ratio_compressible);
    // Observed 0.273 / 0.865, 0.291 / 0.951, 0.345 / 0.982: locking keeps the answer near 30 %.
    EXPECT_LT(ratio, 0.4 * ratio_compressible) << "n = " << kDivisions[k];
    EXPECT_LT(ratio, 0.4) << "n = " << kDivisions[k];
  }
  // Slow approach: the error shrinks by only 10 % from n = 16 to 64 (observed rate 0.075 per halving,
  // against 1.47 for nu = 1/3 on the same meshes). Still increasing: it does converge, in the limit.
  const double e16 = kRefLockingC - locked.uy_C[2], e64 = kRefLockingC - locked.uy_C[4];
  const double rate = 0.5 * std::log2(e16 / e64);
  std::printf("[cooks linear] right, nu = 0.4999: error %.3f (n = 16) -> %.3f (n = 64), rate %.3f\n", e16, e64, rate);
  EXPECT_GT(rate, 0.0);
  EXPECT_LT(rate, 0.3);
  EXPECT_GT(e64 / kRefLockingC, 0.5);  // more than half of the answer is still missing at n = 64 (observed 65 %)
  for (std::size_t k = 1; k < kDivisions.size(); ++k) EXPECT_GT(locked.uy_C[k], locked.uy_C[k - 1]);
}

TEST_F(CooksMembraneLinear, NearlyIncompressibleDoesNotLockOnTheAlternatingPattern) {
  const Series& s = series("nu_04999", "alternating");
  const Series& compressible = series("compressible", "alternating");
  for (std::size_t k = 2; k < kDivisions.size(); ++k) {  // n = 16, 32, 64
    const double ratio = s.uy_C[k] / kRefLockingC, ratio_compressible = compressible.uy_C[k] / kRefCompressibleC;
    // Observed 0.908 / 0.946, 0.960 / 0.979, 0.983 / 0.991: within a few % of the compressible accuracy.
    EXPECT_GT(ratio, 0.9 * ratio_compressible) << "n = " << kDivisions[k];
    EXPECT_LT(ratio, 1.0) << "n = " << kDivisions[k];
  }
  const auto c = extrapolate(s.uy_C[2], s.uy_C[3], s.uy_C[4]);
  const auto m = extrapolate(s.uy_M[2], s.uy_M[3], s.uy_M[4]);
  std::printf("[cooks linear] alternating, nu = 0.4999: C rate %.3f limit %.4f (ref %.3f); M rate %.3f limit %.4f (ref %.3f)\n",
              c.rate, c.limit, kRefLockingC, m.rate, m.limit, kRefLockingM);
  // Observed: C rate 1.20, limit 7.773; M rate 1.55, limit 7.405. Same 0.2 % as the compressible case (the
  // P2-P1 reference itself is extrapolated; its n = 128 value differs from it by 0.06 %).
  EXPECT_GT(c.rate, 0.8);
  EXPECT_LE(verification::relative_error(c.limit, kRefLockingC), 2e-3);
  EXPECT_LE(verification::relative_error(m.limit, kRefLockingM), 2e-3);
}

TEST_F(CooksMembraneLinear, AlternatingIsMoreAccurateThanRightOnEveryMesh) {
  for (const char* material : {"compressible", "nu_04999"}) {
    const Series& right = series(material, "right");
    const Series& alternating = series(material, "alternating");
    for (std::size_t k = 0; k < kDivisions.size(); ++k) {
      EXPECT_EQ(right.dofs[k], alternating.dofs[k]);  // same nodes, different diagonals
      EXPECT_GT(alternating.uy_C[k], right.uy_C[k]) << material << " n = " << kDivisions[k];
    }
  }
}

// The README's default scene (scenes/cooks_membrane.toml: the same panel with tri6 on 64 x 64) against the converged
// reference, as its comment and the README state: u_y(C) -0.63 %, u_y(M) -0.34 %, no locking warning, the load carried.
TEST(CooksMembraneDefaultScene, QuadraticTrianglesAreWithinOnePercentOfTheReference) {
  const SceneSpec scene = load_scene(verification::scene_path("cooks_membrane.toml"), {"output.every=0"});
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
  const auto probes = testing::run_for_probes(scene, "cooks_membrane_default");
  const double C = probes.column("uy_C").back(), M = probes.column("uy_M").back();
  std::printf("[default scene] u_y(C) %.5f (%+.2f %%), u_y(M) %.5f (%+.2f %%)\n", C, 100 * (C / kRefLockingC - 1), M, 100 * (M / kRefLockingM - 1));
  EXPECT_LT(verification::relative_error(C, kRefLockingC), 0.01);
  EXPECT_LT(verification::relative_error(M, kRefLockingM), 0.01);
  EXPECT_LT(C, kRefLockingC);  // from below, as a conforming displacement element
  EXPECT_NEAR(probes.column("reaction_y").back(), -100.0, 1e-5);
}

}  // namespace
}  // namespace loom
