// Extrusion equivalence: Cook's membrane extruded along z with u_z = 0 on both z faces
// (scenes/cooks_membrane_3d.toml) is a plane-strain problem, so its 3D solution must agree with the 2D one on the
// same trapezoid up to the difference between the discretisations (each 2D triangle's prism is cut into three
// tetrahedra, so the 3D mesh is not the 2D mesh times a layer). The criterion: within the 2D
// discretisation error of the same mesh, i.e. |u3D - u2D| smaller than |u2D - reference|; asserted with a
// margin of five (observed: 0.05, 0.05 and 0.03 of it).
//  - linear, E = 250, nu = 0.4999, F = 100: tet10 against tri6, reference u_y(C) = 7.771;
//  - Neo-Hooke, E = 70, nu = 0.499, F = 1: tet10 against tri6 and the mixed tet against the mixed triangle
//    (p1p1_uphi), reference u_y(C) = 0.2761 (REFERENCES: both from converged plane-strain P2-P1 solutions).
// The clamped face's reaction balances the load to the solver's tolerance in both dimensions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "tests/support/test_support.hpp"
#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

struct Cook {
  double uy_C, reaction;
};

template <int D>
Cook run(const std::string& scene_file, const std::vector<std::string>& sets) {
  std::vector<std::string> all = {"output.every=0"};
  all.insert(all.end(), sets.begin(), sets.end());
  const SceneSpec scene = load_scene(verification::scene_path(scene_file), all);
  EXPECT_EQ(scene.scene.dimension, D);
  testing::TempDir dir("extrusion_" + std::to_string(D) + "d");
  const RunSummary summary = testing::make_fem_run<D>(scene, dir.path())->run();
  EXPECT_TRUE(summary.converged) << summary.failure;
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  return {probes.column("uy_C").back(), probes.column("reaction_y").back()};
}

void compare(const std::string& what, const Cook& three, const Cook& two, double reference, double load) {
  const double gap = std::abs(three.uy_C - two.uy_C), error_2d = std::abs(two.uy_C - reference);
  std::printf("[extrusion] %-28s u_y(C): 3D %.6f, 2D %.6f, reference %.4f; |3D - 2D| = %.2e = %.3f of the 2D error\n", what.c_str(),
              three.uy_C, two.uy_C, reference, gap, gap / error_2d);
  EXPECT_LT(gap, 0.2 * error_2d) << what;
  EXPECT_NEAR(three.reaction, -load, 1e-6 * load) << what;  // per unit depth: the layer is 1 deep
  EXPECT_NEAR(two.reaction, -load, 1e-6 * load) << what;
}

// The 2D counterpart of cooks_membrane_3d.toml: the same trapezoid, divisions and diagonals.
const std::vector<std::string> kTwoD = {"body[0].mesh.divisions=[16,16]", "body[0].mesh.pattern=\"right\""};

TEST(ExtrusionEquivalence, LinearCookTet10MatchesPlaneStrainTri6) {
  const Cook three = run<3>("cooks_membrane_3d.toml", {});
  std::vector<std::string> two_sets = kTwoD;
  two_sets.push_back("body[0].element=\"tri6\"");
  const Cook two = run<2>("cooks_membrane_linear.toml", two_sets);
  compare("linear, tet10 vs tri6", three, two, 7.771, 100.0);
}

TEST(ExtrusionEquivalence, NeoHookeCookMatchesPlaneStrain) {
  // Both scenes switched to the same Neo-Hooke set-up (the loaded boundary is [3] in 3D, [1] in 2D).
  const std::vector<std::string> neo_hooke = {"material[0].model=\"neo_hooke\"", "material[0].E=70", "material[0].nu=0.499", "time.steps=5",
                                              "time.dt=0.2"};
  for (const auto& [element3, element2] : {std::pair{"tet10", "tri6"}, std::pair{"p1p1_uphi", "p1p1_uphi"}}) {
    std::vector<std::string> s3 = neo_hooke, s2 = neo_hooke;
    s3.insert(s3.end(), {std::string("body[0].element=\"") + element3 + "\"", "boundary[3].traction.y=0.0625"});
    s2.insert(s2.end(), kTwoD.begin(), kTwoD.end());
    s2.insert(s2.end(), {std::string("body[0].element=\"") + element2 + "\"", "boundary[1].traction.y=0.0625"});
    compare(std::string("Neo-Hooke, ") + element3 + " vs " + element2, run<3>("cooks_membrane_3d.toml", s3),
            run<2>("cooks_membrane_linear.toml", s2), 0.2761, 1.0);
  }
}

}  // namespace
}  // namespace loom
