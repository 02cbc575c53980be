// Thread-count determinism for each method beyond `fem` (whose cases are in stability_test.cpp): the same
// scene with 1 and 2 oneTBB threads must give the same probes at every step and the same Newton
// iterations. PFEM cases are chosen so that the connectivity changes during the run (the remesh, the
// transfer and the rebuilt sparsity are then part of what is compared); MPM cases move particles across
// grid cells (locate, the transfers and the active set change every step).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/stress/stress_support.hpp"

namespace loom::stress {
namespace {

struct Case {
  std::string name, scene;
  std::vector<std::string> sets;
};

void check_cases(const std::string& group, const std::vector<Case>& cases) {
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const ThreadComparison t = run_with_one_and_two_threads(c.scene, c.sets);
    EXPECT_TRUE(t.same()) << c.name << ": " << t.detail();
    record(group, c.name, t.two, t.detail(), t.same() ? "holds" : "FAILS: results depend on the thread count");
  }
}

TEST(Stress, PfemOneAndTwoThreadsAgree) {
  const std::string moderate = scene_path("moderate_block_pfem.toml");
  check_cases("determinism (1 vs 2 threads)",
              {{"pfem: moderate block 16x16, p1p1_uphi, BTM-ISO2, 300 steps (connectivity changes)", moderate,
                {"map.scheme=\"btm\"", "map.iso=2", "time.steps=300", "output.every=0"}},
               {"pfem: moderate block 16x16, tri6, CPM, 300 steps (connectivity changes)", moderate,
                {"body[0].element=\"tri6\"", "time.steps=300", "output.every=0"}},
               {"pfem: constrained block 8x4, p1p1_uphi, alpha_s = 1 MPa, 200 steps (changes from step 176)",
                scene_path("constrained_block_pfem.toml"), {"body[0].alpha_s=1.0", "output.every=0"}}});
}

// 3D fem: the tetrahedral blocks are assembled colour by colour like the triangles.
TEST(Stress, Fem3dOneAndTwoThreadsAgree) {
  check_cases("determinism (1 vs 2 threads)",
              {{"fem 3D: Cook's membrane extruded, tet10, Neo-Hooke nu = 0.499, 5 steps", scene_path("cooks_membrane_3d.toml"),
                {"material[0].model=\"neo_hooke\"", "material[0].E=70", "material[0].nu=0.499", "boundary[3].traction.y=0.0625",
                 "time.steps=5", "time.dt=0.2", "output.every=0"}},
               {"fem 3D: compression of a 8x4x4 box, mixed tet, 10 steps", scene_path("homogeneous_compression_3d.toml"),
                {"body[0].element=\"p1p1_uphi\"", "body[0].mesh.divisions=[8,4,4]", "output.every=0"}}});
}

TEST(Stress, MpmOneAndTwoThreadsAgree) {
  check_cases("determinism (1 vs 2 threads)",
              {{"mpm: dynamic Cook's membrane, ASGS, 12 per cell, 40 steps", scene_path("cooks_membrane_mpm_dynamic.toml"),
                {"time.steps=40", "output.every=0"}},
               {"mpm: dynamic Cook's membrane, OSGS, 3 per cell, 20 steps", scene_path("cooks_membrane_mpm_dynamic.toml"),
                {"body[0].stabilisation=\"osgs\"", "body[0].particles_per_cell=3", "time.steps=20", "output.every=0"}},
               {"mpm: static Cook's membrane 32x32, PPP", scene_path("cooks_membrane_mpm_static.toml"),
                {"body[0].stabilisation=\"ppp\"", "output.every=0"}}});
}

}  // namespace
}  // namespace loom::stress
