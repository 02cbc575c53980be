// Rigid walls with a penalty contact (systems/assemble/wall_contact.hpp; seed 001 §1.8), against closed forms.
//  - A linear elastic block with nu = 0 resting on a frictionless ground under its weight, held only at x = 0 by a
//    roller: sigma_yy = -rho g (H - y), the other stresses zero, u = (0, f(y)) with f quadratic (in the span of
//    quad9) and a flat base, is the exact solution, so the contact pressure is uniform, p = rho g H, and every
//    bottom node sinks by the same g = p / k_N (its force k_N A_i g balances the consistent load p A_i of a uniform
//    pressure: A_i is that share). The wall force is the weight to Newton's tolerance, the penetration p / k_N to
//    round-off. (With nu > 0 the block spreads more at its base, u_x = a (H - y) x, which makes u_y vary as
//    a x^2 / 2 along a free base: on a flat wall the pressure is then not uniform.)
//  - The same block on a frictionless incline (gravity rotated by theta): the wall pushes along its normal only,
//    the internal forces cancel, so the mass-weighted mean displacement along the incline follows the body force
//    exactly: Newmark from the equilibrium acceleration integrates it as g sin(theta) t^2 / 2. With slip = stick
//    (static) the base is held: its nodes move only by the tangential penalty's give, about rho g sin(theta) H / k_N.
//  - A column of nearly incompressible es_up material in a box of walls: the nodal pressure is hydrostatic,
//    p = -rho g (H - y), up to the elastic factor (1 + nu) / (3 (1 - nu)) = 0.9997 at nu = 0.4999 and an O(h)
//    offset of the boundary nodes, whose nodal domains are one-sided (1.6 % of rho g H at h = 1/20, 0.5 % at 1/60).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "tests/support/test_support.hpp"

namespace loom {
namespace {

constexpr double kRho = 1000.0, kG = 9.81, kW = 1.0, kH = 0.5, kE = 1e6;

std::string block_scene(const std::string& extra, const std::string& nu = "0.3") {
  return "[scene]\nname = \"wall-block\"\nmethod = \"fem\"\n"
         "[[material]]\nname = \"m\"\nmodel = \"linear_elastic\"\nE = 1e6\nnu = " + nu + "\ndensity = 1000.0\n"
         "[[body]]\nname = \"block\"\nmaterial = \"m\"\nelement = \"quad9\"\n"
         "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [1.0, 0.5], divisions = [8, 4] }\n"
         "[[probe]]\nname = \"Fx\"\nkind = \"wall_force\"\nwall = \"ground\"\ncomponent = \"x\"\n"
         "[[probe]]\nname = \"Fy\"\nkind = \"wall_force\"\nwall = \"ground\"\ncomponent = \"y\"\n"
         "[[probe]]\nname = \"Fn\"\nkind = \"wall_force\"\nwall = \"ground\"\ncomponent = \"normal\"\n"
         "[[probe]]\nname = \"gap\"\nkind = \"penetration\"\nwall = \"ground\"\n"
         "[output]\nevery = 0\n" + extra;
}

TEST(WallContact, BlockRestingOnTheGroundCarriesItsWeightAndSinksByPOverK) {
  for (const double k : {1e9, 0.0}) {  // 0: the default 100 E / h
    SCOPED_TRACE("penalty " + std::to_string(k));
    const SceneSpec scene = testing::scene_from_text(block_scene(
        "[time]\nintegrator = \"static\"\ndt = 1.0\nsteps = 1\n[solver]\nresidual_relative = 1e-12\n"
        "[body_force]\ny = -9.81\n"
        "[[boundary]]\nname = \"roller\"\nregion = { box = [[0.0, 0.0], [0.0, 0.5]] }\ndisplacement = { x = 0.0 }\n"
        "[[wall]]\nname = \"ground\"\npoint = [0.0, 0.0]\nnormal = [0.0, 2.0]\npenalty = " + std::to_string(k) + "\n",
        "0.0"));
    auto run = testing::make_fem_run(scene);
    const RunSummary summary = run->run();
    ASSERT_TRUE(summary.converged) << summary.failure;
    const auto& v = run->probe_values();
    const double weight = kRho * kG * kW * kH, p = kRho * kG * kH;
    const double k_n = k > 0 ? k : 100.0 * kE / 0.125;  // every boundary edge of the 8 x 4 cells is 0.125 long
    EXPECT_NEAR(v[1], weight, 1e-8 * weight);
    EXPECT_NEAR(v[2], weight, 1e-8 * weight);
    EXPECT_NEAR(v[0], 0.0, 1e-10 * weight);
    EXPECT_NEAR(v[3], p / k_n, 1e-8 * p / k_n);
    // Every bottom node sinks by the same amount, and no node lies behind the wall by more than the probe says.
    const Nodes<2>& nodes = run->nodes();
    for (Index i = 0; i < nodes.size(); ++i) {
      EXPECT_GE(nodes.position_n(i).y(), -v[3] * (1 + 1e-12)) << "node " << i;
      if (nodes.X[i].y() == 0.0) {
        EXPECT_NEAR(nodes.u_n[i].y(), -p / k_n, 1e-8 * p / k_n) << "node " << i;
      }
    }
    std::printf("[wall] resting block, k_N %.3g: wall force %.10g (weight %.10g), penetration %.6e (p / k_N %.6e, %.2e of h)\n", k_n, v[1],
                weight, v[3], p / k_n, v[3] / 0.125);
  }
}

// Mass-weighted mean of the x displacement (lumped masses).
double mean_ux(const Nodes<2>& nodes) {
  double mu = 0.0, m = 0.0;
  for (Index i = 0; i < nodes.size(); ++i) mu += nodes.lumped_mass[i] * nodes.u_n[i].x(), m += nodes.lumped_mass[i];
  return mu / m;
}

TEST(WallContact, BlockSlidesDownAFrictionlessInclineAtGSinTheta) {
  const double theta = M_PI / 6, T = 0.5, slide = 0.5 * kG * std::sin(theta) * T * T;
  char gravity[120];
  std::snprintf(gravity, sizeof gravity, "[body_force]\nx = %.17g\ny = %.17g\n", kG * std::sin(theta), -kG * std::cos(theta));
  const SceneSpec scene = testing::scene_from_text(block_scene(
      std::string("[time]\nintegrator = \"newmark\"\ndt = 0.01\nsteps = 50\ninitial_acceleration = \"equilibrium\"\n"
                  "[solver]\nresidual_relative = 1e-12\n") +
      gravity + "[[wall]]\nname = \"ground\"\npoint = [0.0, 0.0]\nnormal = [0.0, 1.0]\npenalty = 1e9\n"));
  auto run = testing::make_fem_run(scene);
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const double mean = mean_ux(run->nodes());
  EXPECT_NEAR(mean, slide, 1e-9 * slide);
  EXPECT_NEAR(run->probe_values()[0], 0.0, 1e-12);  // a frictionless wall pushes along its normal only
  std::printf("[wall] free incline: mass-weighted mean u_x %.12g, g sin(theta) T^2 / 2 = %.12g\n", mean, slide);
}

// Stick, static: nothing but the wall holds the block on the incline. Its base stays at its first-contact points
// up to the penalty's give (the base tractions over k_N, a few times rho g sin(theta) H / k_N where the block's ends
// concentrate them), and the block deforms about as the same block with its base clamped (a boundary with u = 0
// on y = 0 instead of the wall), except that the contact is one-sided: the uphill corner, where the clamped block's
// base is in tension, lifts off (2.5e-4 here, against 3e-3 for the largest displacement).
TEST(WallContact, BlockStaysPutOnAnInclineWithStick) {
  const double theta = M_PI / 6, k = 1e9;
  char gravity[120];
  std::snprintf(gravity, sizeof gravity, "[body_force]\nx = %.17g\ny = %.17g\n", kG * std::sin(theta), -kG * std::cos(theta));
  // Step 2 starts from the areas of the deformed base (a residual of 1e-3 of the load); the penalty's round-off,
  // k_N A x 1e-16 |x|, is about 1e-8 N: an absolute tolerance above it.
  const std::string time = "[time]\nintegrator = \"static\"\ndt = 1.0\nsteps = 2\n[solver]\nresidual_relative = 1e-12\nresidual_absolute = 1e-6\n";
  const SceneSpec stick = testing::scene_from_text(
      block_scene(time + gravity + "[[wall]]\nname = \"ground\"\npoint = [0.0, 0.0]\nnormal = [0.0, 1.0]\npenalty = 1e9\nslip = \"stick\"\n"));
  std::string clamped_text = block_scene(time + gravity + "[[boundary]]\nname = \"base\"\nregion = { box = [[0.0, 0.0], [1.0, 0.0]] }\n"
                                                          "displacement = { x = 0.0, y = 0.0 }\n");
  clamped_text = clamped_text.substr(0, clamped_text.find("[[probe]]")) + "[output]\nevery = 0\n" +
                 clamped_text.substr(clamped_text.find("[time]"));
  auto a = testing::make_fem_run(stick), b = testing::make_fem_run(testing::scene_from_text(clamped_text));
  const RunSummary sa = a->run(), sb = b->run();
  ASSERT_TRUE(sa.converged) << sa.failure;
  ASSERT_TRUE(sb.converged) << sb.failure;
  const Nodes<2>&na = a->nodes(), &nb = b->nodes();
  ASSERT_EQ(na.size(), nb.size());
  const double give = kRho * kG * std::sin(theta) * kH / k;
  double base = 0.0, largest = 0.0, clamped = 0.0, diff = 0.0;
  for (Index i = 0; i < na.size(); ++i) {
    if (na.X[i].y() == 0.0) base = std::max(base, std::abs(na.u_n[i].x()));
    largest = std::max(largest, na.u_n[i].norm());
    clamped = std::max(clamped, nb.u_n[i].norm());
    diff = std::max(diff, (na.u_n[i] - nb.u_n[i]).norm());
  }
  EXPECT_LE(base, 5.0 * give);
  EXPECT_NEAR(largest, clamped, 0.15 * clamped);
  EXPECT_LE(diff, 0.15 * clamped);
  EXPECT_NEAR(a->probe_values()[0], -kRho * kG * std::sin(theta) * kW * kH, 1e-8 * kRho * kG * kW * kH);  // holds the weight's x part
  std::printf("[wall] stick incline: base |u_x| <= %.3e (rho g sin(theta) H / k_N %.3e); largest |u| %.3e, clamped block %.3e, "
              "largest difference %.3e\n", base, give, largest, clamped, diff);
}

TEST(WallContact, ColumnInABoxOfWallsIsHydrostatic) {
  const double H = 1.0, nu = 0.4999;
  const SceneSpec scene = testing::scene_from_text(
      "[scene]\nname = \"wall-column\"\nmethod = \"fem\"\n[time]\nintegrator = \"static\"\ndt = 1.0\nsteps = 1\n"
      "[solver]\nresidual_relative = 1e-10\n"
      "[[material]]\nname = \"m\"\nmodel = \"linear_elastic\"\nE = 1e6\nnu = 0.4999\ndensity = 1000.0\n"
      "[[body]]\nname = \"column\"\nmaterial = \"m\"\nelement = \"es_up\"\nalpha_stab = 0.5\n"
      "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [0.2, 1.0], divisions = [6, 60], pattern = \"right\" }\n"
      "[body_force]\ny = -9.81\n"
      "[[wall]]\nname = \"box\"\nbox = [[0.0, 0.0], [0.2, 10.0]]\n"
      "[[probe]]\nname = \"Fy\"\nkind = \"wall_force\"\nwall = \"box\"\ncomponent = \"y\"\n"
      "[output]\nevery = 0\n");
  auto run = testing::make_fem_run(scene);
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const Nodes<2>& nodes = run->nodes();
  const double scale = kRho * kG * H, factor = (1 + nu) / (3 * (1 - nu));
  double worst = 0.0;
  Index at = 0;
  for (Index i = 0; i < nodes.size(); ++i) {
    const double exact = -kRho * kG * (H - nodes.X[i].y());
    if (std::abs(nodes.p_n[i] - exact) / scale > worst) worst = std::abs(nodes.p_n[i] - exact) / scale, at = i;
  }
  EXPECT_LE(worst, 1e-2);
  EXPECT_NEAR(run->probe_values()[0], kRho * kG * H * 0.2, 1e-8 * kRho * kG * H * 0.2);
  std::printf("[wall] column in a box: worst |p - p_hydrostatic| / (rho g H) = %.2e at (%g, %g) (elastic factor %.4f)\n", worst,
              nodes.X[at].x(), nodes.X[at].y(), factor);
}

// PFEM: a block of p1p1_uphi rubber dropped from 5 cm onto the ground, remeshed before every step, with the default
// penalty (100 E / h). It lands at t = 0.1 s, bounces and settles (Bossak alpha = -0.3 damps it). At every step no
// particle lies behind the wall by more than the penetration probe, which stays below 1 % of h = 0.1; over the
// steps after the landing the wall carries the weight on average (observed 0.993 over t in (0.2, 0.8] s).
TEST(WallContact, PfemBlockDroppedOnTheGroundComesToRestOnIt) {
  const SceneSpec scene = testing::scene_from_text(
      "[scene]\nname = \"pfem-drop\"\nmethod = \"pfem\"\n"
      "[time]\nintegrator = \"bossak\"\nalpha = -0.3\ndt = 0.01\nsteps = 80\n"
      "[[material]]\nname = \"rubber\"\nmodel = \"neo_hooke\"\nE = 1e6\nnu = 0.3\ndensity = 1000.0\n"
      "[[body]]\nname = \"block\"\nmaterial = \"rubber\"\nelement = \"p1p1_uphi\"\n"
      "mesh = { generator = \"rectangle\", origin = [0.0, 0.05], size = [1.0, 0.5], divisions = [10, 5], pattern = \"alternating\" }\n"
      "[body_force]\ny = -9.81\n"
      "[[wall]]\nname = \"ground\"\npoint = [0.0, 0.0]\nnormal = [0.0, 1.0]\n"
      "[[probe]]\nname = \"Fy\"\nkind = \"wall_force\"\nwall = \"ground\"\ncomponent = \"y\"\n"
      "[[probe]]\nname = \"gap\"\nkind = \"penetration\"\n"
      "[[probe]]\nname = \"ymin\"\nkind = \"extent\"\ncomponent = \"y\"\nbound = \"min\"\n"
      "[output]\nevery = 0\n");
  testing::TempDir dir("wall_pfem_drop");
  auto run = testing::make_fem_run(scene, dir.path());
  const RunSummary summary = run->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  const auto F = probes.column("Fy"), gap = probes.column("gap"), ymin = probes.column("ymin"), t = probes.column("time");
  const double weight = kRho * kG * 1.0 * 0.5;
  double mean = 0.0, worst_gap = 0.0;
  int n = 0, landed = -1;
  for (std::size_t k = 0; k < F.size(); ++k) {
    EXPECT_GE(ymin[k], -gap[k] * (1 + 1e-12)) << "step " << k;
    worst_gap = std::max(worst_gap, gap[k]);
    if (landed < 0 && F[k] > 0.0) landed = int(k);
    if (t[k] > 0.2 + 1e-12) mean += F[k], ++n;
  }
  mean /= n;
  EXPECT_LE(worst_gap, 0.01 * 0.1);
  EXPECT_GE(landed, 10);  // sqrt(2 x 0.05 / 9.81) = 0.101 s, and a_0 = 0 starts the fall half a step late: step 11
  EXPECT_LE(landed, 12);
  EXPECT_NEAR(mean, weight, 0.05 * weight);
  std::printf("[wall] pfem drop: lands at step %d, largest penetration %.2e (%.2e of h), mean wall force after 0.2 s %.1f (weight %.1f)\n", landed,
              worst_gap, worst_gap / 0.1, mean, weight);
}

}  // namespace
}  // namespace loom
