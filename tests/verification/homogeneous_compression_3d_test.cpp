// Compression of a Neo-Hooke block between rollers in 3D (scenes/homogeneous_compression_3d.toml) against the
// closed-form homogeneous solution at every step, for tet4 (p1), tet10 and the mixed tet4 u-phi, on a box of Kuhn
// tetrahedra with distorted interior nodes; and, with u_z = 0 on the face z = T too, against the plane-strain
// closed form of the 2D scene (the 3D engine reproduces plane strain exactly).
//
// Reference (homogeneous_compression_exact.hpp): F = diag(l, l2, l), l2 = 1 - d/H, the free faces x = W and
// z = T give P11 = P33 = mu l + (lambda ln(l^2 l2) - mu) / l = 0; the top reaction is P22 W T. An affine field
// is in every element's space, the four-point rules integrate tet10's gradients exactly on straight cells, and
// the mixed tet reproduces it with phi = J at every node (tests/verification/tet_patch_test.cpp), so the
// discrete solution is the exact one up to Newton's tolerance (residual_relative = 1e-12): 1e-9 relative is
// asserted, ~1e-14 observed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "tests/support/test_support.hpp"
#include "tests/verification/homogeneous_compression_exact.hpp"
#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

constexpr double kE = 10.0, kNu = 0.3, kW = 2.0, kH = 1.0, kT = 1.0, kFinal = 0.3;  // top moved by 0.3 H at t = 1

void check_compression(const std::string& element, bool plane_strain) {
  SCOPED_TRACE("element " + element + (plane_strain ? ", plane strain" : ""));
  std::vector<std::string> sets = {"output.every=0", "body[0].element=\"" + element + "\""};
  if (plane_strain) sets.push_back("boundary[3].displacement.z=0");
  const SceneSpec scene = load_scene(verification::scene_path("homogeneous_compression_3d.toml"), sets);
  ASSERT_EQ(scene.scene.dimension, 3);
  EXPECT_DOUBLE_EQ(scene.materials[0].E, kE);
  EXPECT_DOUBLE_EQ(scene.materials[0].nu, kNu);
  EXPECT_EQ(scene.bodies[0].mesh.size, Vec2(kW, kH));
  EXPECT_EQ(scene.bodies[0].mesh.size_z, kT);
  EXPECT_GT(scene.bodies[0].mesh.distortion, 0.0);

  testing::TempDir dir("homogeneous_compression_3d_" + element + (plane_strain ? "_ps" : ""));
  const RunSummary summary = testing::make_fem_run<3>(scene, dir.path())->run();
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  ASSERT_EQ(probes.rows.size(), std::size_t(scene.time.steps) + 1);
  const auto time = probes.column("time"), reaction = probes.column("reaction_top_y"), ux = probes.column("ux_right"),
             uz = probes.column("uz_front");
  double worst = 0.0;
  for (std::size_t n = 1; n < time.size(); ++n) {
    const double d = kFinal * kH * time[n];
    double exact_reaction, exact_ux, exact_uz;
    if (plane_strain) {
      const auto s = verification::homogeneous_compression_exact(kE, kNu, kW, kH, d);
      exact_reaction = s.reaction * kT, exact_ux = s.ux_right, exact_uz = 0.0;
    } else {
      const auto s = verification::homogeneous_compression_3d_exact(kE, kNu, kW, kH, kT, d);
      EXPECT_LT(std::abs(s.p11), 1e-13);
      exact_reaction = s.reaction, exact_ux = s.ux_right, exact_uz = s.uz_front;
    }
    const double er = verification::relative_error(reaction[n], exact_reaction), eu = verification::relative_error(ux[n], exact_ux);
    EXPECT_LE(er, 1e-9) << "step " << n << ": reaction " << reaction[n] << ", exact " << exact_reaction;
    EXPECT_LE(eu, 1e-9) << "step " << n << ": u_x " << ux[n] << ", exact " << exact_ux;
    EXPECT_NEAR(uz[n], exact_uz, 1e-9 * std::abs(exact_ux)) << "step " << n;
    worst = std::max({worst, er, eu});
  }
  std::printf("[compression 3d] %-9s %-12s worst relative error %.1e (final reaction %.12f)\n", element.c_str(),
              plane_strain ? "plane strain" : "free faces", worst, reaction.back());
}

TEST(HomogeneousCompression3d, Tet4MatchesClosedForm) { check_compression("p1", false); }
TEST(HomogeneousCompression3d, Tet10MatchesClosedForm) { check_compression("tet10", false); }
TEST(HomogeneousCompression3d, MixedTetMatchesClosedForm) { check_compression("p1p1_uphi", false); }
TEST(HomogeneousCompression3d, RollerZFacesGiveThePlaneStrainClosedForm) {
  check_compression("p1", true);
  check_compression("tet10", true);
}

}  // namespace
}  // namespace loom
