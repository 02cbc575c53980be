// Cook's membrane at nu = 0.4999 (scenes/cooks_membrane_nearly_incompressible.toml): refinement series of the
// three elements on the 'right' pattern, Neo-Hooke, E = 70, dead load 0.0625 (total 1), plane strain.
// Reference (../shared/REFERENCES.md): u_y(C) = 0.2761 at nu = 0.499 and 0.2758 at nu = 0.5; at nu = 0.4999
// (ten times closer to the limit) the nearer value 0.2758 is used; the two differ by 0.1 %, below every
// tolerance here.
//
// Observed u_y(C) (n x n divisions; n = 128 from the scene with --set, not run here):
//   n          4        8        16       32       64       128
//   p1         0.07373  0.07446  0.07587  0.08068  0.09577  0.13246
//   tri6       0.21541  0.25236  0.26659  0.27216  0.27441  0.27535
//   p1p1_uphi  0.14023  0.20871  0.24919  0.26554  0.27174  0.27421
// tri6 and p1p1_uphi rise monotonically toward the reference from below; the observed rates on 16-32-64 are
// 1.31 (tri6) and 1.40 (p1p1_uphi), about 1 as expected at the corner C, where the stress is singular
// (REFERENCES.md: "with a uniform traction the corner converges at rate about 1 even for quadratic
// elements"). Richardson on 16-32-64 gives 0.27594 (tri6, +0.05 %) and 0.27552 (p1p1_uphi, -0.10 %).
// p1 locks: 27-35 % of the reference up to n = 64.
//
// Tolerances on the finest mesh (n = 64), from the Richardson estimate of its remaining error
// d_64 / (d_32 / d_64 - 1) (d_n = u_n - u_{n/2}): 0.0015 (0.55 %) for tri6 and 0.0038 (1.4 %) for
// p1p1_uphi. The test allows 1 % and 2 %, i.e. the estimate with a margin for the rate still drifting
// (n = 128 confirms: 0.16 % and 0.58 % off there). The extrapolated limits must lie within 0.3 % of the
// reference (observed -0.10 ... +0.05 %; 0.3 % covers the span between the two published references three
// times over and the drift of the rate).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

constexpr double kReference = 0.2758;

double tip_displacement(const std::string& element, int n) {
  const SceneSpec scene = load_scene(verification::scene_path("cooks_membrane_nearly_incompressible.toml"),
                                     {"body[0].mesh.divisions=[" + std::to_string(n) + "," + std::to_string(n) + "]",
                                      "body[0].element=" + element, "output.every=0"});
  const auto r = verification::run_scene(scene);
  EXPECT_TRUE(r.summary.converged) << element << ", n = " << n << ": " << r.summary.failure;
  EXPECT_LE(r.probes.at("newton"), 6) << element << ", n = " << n;  // 3-4 observed
  std::printf("[cooks nearly incompressible] %-9s n = %2d: u_y(C) = %.5f (%5.1f %% of %.4f), %d Newton, %.2f s\n", element.c_str(), n,
              r.probes.at("uy_C"), 100 * r.probes.at("uy_C") / kReference, kReference, int(r.probes.at("newton")), r.seconds);
  return r.probes.at("uy_C");
}

TEST(CooksMembraneNearlyIncompressible, CommittedSceneIsTri6AtNu04999OnTheLockingPattern) {
  const SceneSpec scene = load_scene(verification::scene_path("cooks_membrane_nearly_incompressible.toml"), {"output.every=0"});
  ASSERT_EQ(scene.bodies.size(), 1u);
  EXPECT_EQ(scene.bodies[0].element, Formulation::tri6);
  EXPECT_EQ(scene.bodies[0].mesh.pattern, GridPattern::right);
  EXPECT_EQ(scene.materials[0].model, MaterialModel::neo_hooke);
  EXPECT_DOUBLE_EQ(scene.materials[0].E, 70.0);
  EXPECT_DOUBLE_EQ(scene.materials[0].nu, 0.4999);
}

TEST(CooksMembraneNearlyIncompressible, P1LocksWhileTri6AndP1P1UPhiConvergeToTheReference) {
  const std::vector<int> ns = {4, 8, 16, 32, 64};
  std::map<std::string, std::vector<double>> u;
  for (const char* element : {"p1", "tri6", "p1p1_uphi"})
    for (int n : ns) u[element].push_back(tip_displacement(element, n));

  // 1. p1 locks: under 40 % of the reference and of tri6 on every mesh (observed 27-35 %).
  for (std::size_t k = 0; k < ns.size(); ++k) {
    EXPECT_LT(u["p1"][k], 0.4 * kReference) << "n = " << ns[k];
    EXPECT_LT(u["p1"][k], 0.4 * u["tri6"][k]) << "n = " << ns[k];
  }

  // 2. tri6 and p1p1_uphi: monotone from below, rate about 1 (between 1 and 2), Richardson limit and
  //    finest value within the tolerances of the header.
  const std::map<std::string, double> finest_tolerance = {{"tri6", 0.01}, {"p1p1_uphi", 0.02}};
  for (const auto& [element, tol] : finest_tolerance) {
    SCOPED_TRACE(element);
    const std::vector<double>& v = u[element];
    for (std::size_t k = 0; k < v.size(); ++k) {
      EXPECT_LT(v[k], kReference) << "n = " << ns[k];
      if (k > 0) {
        EXPECT_GT(v[k], v[k - 1]) << "n = " << ns[k];
      }
    }
    const std::size_t m = v.size() - 1;  // n = 64
    const double d1 = v[m - 1] - v[m - 2], d2 = v[m] - v[m - 1];
    const double rate = std::log2(d1 / d2), limit = v[m] + d2 / (d1 / d2 - 1.0);
    std::printf("[cooks nearly incompressible] %-9s 16-32-64: rate %.2f, Richardson limit %.5f (%+.2f %%), n = 64 off by %.2f %%\n",
                element.c_str(), rate, limit, 100 * (limit - kReference) / kReference, 100 * (kReference - v[m]) / kReference);
    EXPECT_GT(rate, 1.0);
    EXPECT_LT(rate, 2.0);
    EXPECT_LE(verification::relative_error(limit, kReference), 3e-3);
    EXPECT_LE(verification::relative_error(v[m], kReference), tol);
  }
  // 3. On every mesh tri6 is closer to the reference than p1p1_uphi (the mixed P1 has a third of the
  //    unknowns of tri6 per mesh: 833 against 2112 dofs at n = 16).
  for (std::size_t k = 0; k < ns.size(); ++k) EXPECT_GT(u["tri6"][k], u["p1p1_uphi"][k]) << "n = " << ns[k];
}

}  // namespace
}  // namespace loom
