// Highly constrained rubber block in PFEM (scenes/constrained_block_pfem.toml; seed 000 §5.1, Figs 8, 10, 11)
// against the same block in FEM (scenes/constrained_block_fem.toml): remeshed before every step with
// alpha = 1.1, l_char = 0.2 mm and CPM.
//
// What the paper says, and what we observe (u_pre = 0.001 mm per step):
//  - p1p1_uphi, alpha_s = K/10: no connectivity change, so CPM transfers nothing and PFEM equals FEM. Ours:
//    no change in 200 steps and the force curves agree bit for bit (6.49832724091945 N at the end).
//  - Connectivity changes occur only for alpha_s <= 100 MPa and only after u_pre = 0.168 mm. Ours: first
//    changes at step 176 (alpha_s = 1), 177 (10), 184 (100), none for 1e3 and 1e5; the curve equals FEM
//    bit for bit before the first change and deviates after it (by up to 0.075 N at alpha_s = 1: the CPM
//    transfer error the paper's Fig 8 detail shows as oscillations).
//  - TRI6 PFEM stops converging at u_pre = 0.172 mm, FEM TRI6 does not. Ours: the last converged step is
//    166 (sub-steps up to u_pre = 0.1665 mm); FEM TRI6 runs to 0.2 mm. Why (the paper: the mid-nodes reset
//    to straight edges at every remesh, Fig 11): PFEM TRI6 is 6.5 % stiffer than FEM TRI6 at step 166
//    (5.276 N against 4.952 N), its Newton iterations climb from 3 to 9 over steps 150-166 (FEM: 4-5), and
//    step 167 fails even cut to 1/64 of its increment (the line search accepts 1/32 of the first Newton step,
//    the residual stalls near 1.3 N). The corner triangles are no worse than in FEM (smallest radius ratio
//    0.203 against 0.210, at the right wall), so it is not a distorted triangle. The decisive evidence:
//    remeshing less often makes it fail earlier, and always at a remesh step: every 10 steps -> step 170,
//    every 20 -> 160, every 50 -> 150. The straightening of accumulated edge curvature, with the history F_n
//    kept at the moved quadrature points, is what Newton cannot absorb.
//    (docs/constrained_block/README.md shows the two meshes at step 166, drawn by tools/plot_mesh.py.)
//  - Fig 10: FEM-TRI6 is "slightly stiffer" than p1p1_uphi (K/10). The seed's "TRI6 PFEM-element bears another
//    difference to its FEM counterpart apart from variable mapping, which is the resetting of the edge-mid-nodes"
//    reads as: its FEM-TRI6 is the PFEM code without remeshing, eq-24 ties included. Ours, the PFEM scene with
//    remesh.every = 1000: 6.927 N against 6.498 N at the end (+6.6 %), but softer before step 140 (ratio 0.947 at
//    step 10, 0.975 at 100); the plain FEM tri6 (no ties) stays 5-7 % softer (6.095 N). The ties of the
//    indenter's mid-nodes (u_x tied to the corners' mean) do most of it; see docs/constrained_block/README.md.
// Each run takes 0.2-0.6 s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "tests/support/test_support.hpp"
#include "tests/verification/verification_support.hpp"

namespace loom {
namespace {

constexpr int kSteps = 200;

struct Curve {
  std::vector<double> force, changed, newton;  // per step 0 .. last converged
  RunSummary summary;
  int first_change = -1;
};

Curve run_block(const std::string& file, const std::string& element, const std::string& alpha_s, const std::vector<std::string>& more = {}) {
  std::vector<std::string> overrides = {"output.every=0", "body[0].element=" + element};
  if (!alpha_s.empty()) overrides.push_back("body[0].alpha_s=" + alpha_s);
  overrides.insert(overrides.end(), more.begin(), more.end());
  const SceneSpec scene = load_scene(verification::scene_path(file), overrides);
  testing::TempDir dir("constrained_block_pfem_" + element + alpha_s + std::to_string(more.size()));
  auto run = testing::make_fem_run(scene, dir.path());
  Curve c;
  c.summary = run->run();
  const auto probes = testing::read_probes(dir.file("probes.csv"));
  for (double r : probes.column("reaction")) c.force.push_back(-r);
  c.newton = probes.column("newton");
  if (scene.scene.method == Method::pfem) {
    c.changed = probes.column("changed");
    for (std::size_t k = 1; k < c.changed.size() && c.first_change < 0; ++k)
      if (c.changed[k] == 1.0) c.first_change = int(k);
  }
  return c;
}

Curve pfem(const std::string& element, const std::string& alpha_s = "", const std::vector<std::string>& more = {}) {
  return run_block("constrained_block_pfem.toml", element, alpha_s, more);
}
Curve fem(const std::string& element, const std::string& alpha_s = "") { return run_block("constrained_block_fem.toml", element, alpha_s); }

double max_difference(const Curve& a, const Curve& b, std::size_t from, std::size_t to) {
  double d = 0.0;
  for (std::size_t k = from; k < std::min({to, a.force.size(), b.force.size()}); ++k) d = std::max(d, std::abs(a.force[k] - b.force[k]));
  return d;
}

TEST(ConstrainedBlockPfem, TheScenesDifferOnlyByTheRemeshing) {
  const SceneSpec p = load_scene(verification::scene_path("constrained_block_pfem.toml"));
  const SceneSpec f = load_scene(verification::scene_path("constrained_block_fem.toml"));
  EXPECT_EQ(p.scene.method, Method::pfem);
  EXPECT_EQ(f.scene.method, Method::fem);
  EXPECT_EQ(p.time.steps, f.time.steps);
  EXPECT_EQ(p.time.dt, f.time.dt);
  EXPECT_EQ(p.bodies[0].mesh.nx, f.bodies[0].mesh.nx);
  EXPECT_EQ(p.bodies[0].mesh.ny, f.bodies[0].mesh.ny);
  EXPECT_EQ(p.bodies[0].mesh.pattern, f.bodies[0].mesh.pattern);
  EXPECT_EQ(p.bodies[0].mesh.size, f.bodies[0].mesh.size);
  EXPECT_EQ(p.materials[0].K, f.materials[0].K);
  EXPECT_EQ(p.materials[0].G, f.materials[0].G);
  ASSERT_EQ(p.boundaries.size(), f.boundaries.size());
  for (std::size_t k = 0; k < p.boundaries.size(); ++k) {
    EXPECT_EQ(p.boundaries[k].box_min, f.boundaries[k].box_min);
    EXPECT_EQ(p.boundaries[k].box_max, f.boundaries[k].box_max);
  }
  EXPECT_DOUBLE_EQ(p.pfem.alpha, 1.1);   // seed 000 §5.1
  EXPECT_DOUBLE_EQ(p.pfem.lchar, 0.2);
  EXPECT_FALSE(p.pfem.local);
  EXPECT_FALSE(p.pfem.btm);              // CPM
}

// Fig 10: with K/10 no connectivity changes, CPM preserves the state perfectly and PFEM = FEM.
TEST(ConstrainedBlockPfem, P1P1UPhiWithKOver10EqualsFemBecauseNoConnectivityChanges) {
  const Curve p = pfem("p1p1_uphi"), f = fem("p1p1_uphi");
  ASSERT_TRUE(p.summary.converged) << p.summary.failure;
  ASSERT_TRUE(f.summary.converged) << f.summary.failure;
  ASSERT_EQ(p.force.size(), std::size_t(kSteps) + 1);
  EXPECT_EQ(p.first_change, -1);
  // Nothing is transferred and nothing rebuilt, so the computation is the FEM one: equal to the last bit
  // (an exact comparison is the point here).
  EXPECT_EQ(max_difference(p, f, 0, kSteps + 1), 0.0);
  EXPECT_NEAR(p.force.back(), 6.5, 0.01);
  std::printf("[constrained block pfem] p1p1_uphi K/10: no connectivity change; PFEM %.14f N, FEM %.14f N\n", p.force.back(), f.force.back());
}

// Fig 8: small alpha_s gives non-smooth deformations and late connectivity changes (after 0.168 mm in the
// paper); before them PFEM is FEM, after them the CPM transfer error shows.
TEST(ConstrainedBlockPfem, ConnectivityChangesOnlyLateAndOnlyForSmallAlphaS) {
  struct Case {
    const char* alpha_s;
    bool changes;
  };
  for (const Case c : {Case{"1", true}, Case{"10", true}, Case{"100", true}, Case{"1e3", false}, Case{"1e5", false}}) {
    SCOPED_TRACE(std::string("alpha_s = ") + c.alpha_s);
    const Curve p = pfem("p1p1_uphi", c.alpha_s), f = fem("p1p1_uphi", c.alpha_s);
    ASSERT_TRUE(p.summary.converged) << p.summary.failure;
    ASSERT_TRUE(f.summary.converged) << f.summary.failure;
    if (!c.changes) {
      EXPECT_EQ(p.first_change, -1);
      EXPECT_EQ(max_difference(p, f, 0, kSteps + 1), 0.0);
      continue;
    }
    ASSERT_GT(p.first_change, 0);
    EXPECT_GE(p.first_change, 168);  // u_pre >= 0.168 mm: observed 176, 177, 184
    const std::size_t first = std::size_t(p.first_change);
    EXPECT_EQ(max_difference(p, f, 0, first), 0.0);
    const double after = max_difference(p, f, first, kSteps + 1);
    EXPECT_GT(after, 1e-3);                   // the transfer is felt (0.034 ... 0.075 N observed)
    EXPECT_LT(after, 0.02 * f.force.back());  // but stays a small perturbation of the FEM curve
    int n_changes = 0;
    for (double ch : p.changed) n_changes += ch == 1.0;
    std::printf("[constrained block pfem] p1p1_uphi alpha_s %-4s: %d steps change the connectivity, the first at step %d (u_pre = %.3f mm); "
                "|F_pfem - F_fem| = 0 before, up to %.4f N after; final %.4f N (FEM %.4f N)\n",
                c.alpha_s, n_changes, p.first_change, 0.001 * p.first_change, after, p.force.back(), f.force.back());
  }
}

// Fig 10/11: TRI6 PFEM stops converging (the paper: at u_pre = 0.172 mm), FEM TRI6 does not.
TEST(ConstrainedBlockPfem, Tri6StopsConvergingWhereFemTri6DoesNot) {
  const Curve p = pfem("tri6"), f = fem("tri6");
  ASSERT_TRUE(f.summary.converged) << f.summary.failure;
  ASSERT_FALSE(p.summary.converged);
  const int last = p.summary.last_converged_step;
  EXPECT_GE(last, 155);  // observed 166 (paper: 172)
  EXPECT_LE(last, 180);
  EXPECT_EQ(p.first_change, -1);  // no connectivity change either: the mapping is not the cause
  // Stiffer than FEM TRI6 (the eq-24 ties: without remeshing the tied TRI6 is +8.7 % here), and harder to
  // converge towards the end.
  const auto k = std::size_t(last);
  EXPECT_GT(p.force[k], 1.03 * f.force[k]);  // observed +6.5 %
  EXPECT_GE(p.newton[k], p.newton[100] + 3);  // observed 9 against 3
  std::printf("[constrained block pfem] tri6: last converged step %d (u_pre %.4f mm; paper 0.172 mm), %s\n"
              "  at step %d: PFEM %.4f N vs FEM %.4f N (%+.1f %%), Newton iterations %g (step 100: %g; FEM: %g)\n",
              last, 0.001 * p.summary.last_converged_time, p.summary.failure.c_str(), last, p.force[k], f.force[k],
              100.0 * (p.force[k] / f.force[k] - 1.0), p.newton[k], p.newton[100], f.newton[k]);
}

// The cause: resetting the mid-nodes to straight edges. Remeshing every n steps instead of every step lets
// more curvature build up between resets; the run then fails earlier, at a step that resets.
TEST(ConstrainedBlockPfem, Tri6FailsAtAStepThatResetsTheMidNodes) {
  int previous = 1000;
  for (int every : {10, 20, 50}) {
    SCOPED_TRACE("remesh every " + std::to_string(every));
    const Curve p = pfem("tri6", "", {"remesh.every=" + std::to_string(every)});
    ASSERT_FALSE(p.summary.converged);
    const int failed = p.summary.last_converged_step + 1;
    EXPECT_EQ(failed % every, 0) << "failed at step " << failed;  // observed 170, 160, 150
    EXPECT_LT(failed, previous);
    previous = failed;
    std::printf("[constrained block pfem] tri6 remeshed every %2d steps: fails at step %d\n", every, failed);
  }
}

// Fig 10 with the paper's FEM-TRI6 read as its PFEM code without remeshing: the eq-24 ties of the boundary
// mid-nodes make tri6 cross p1p1_uphi (K/10) and end stiffer; without them (plain FEM) tri6 ends softer.
TEST(ConstrainedBlockPfem, Tri6WithEq24TiesAndNoRemeshingCrossesP1P1UPhiAndEndsStiffer) {
  const Curve tied = pfem("tri6", "", {"remesh.every=1000"}), plain = fem("tri6"), uphi = fem("p1p1_uphi");
  for (const Curve* c : {&tied, &plain, &uphi}) {
    ASSERT_TRUE(c->summary.converged) << c->summary.failure;
    ASSERT_EQ(c->force.size(), std::size_t(kSteps) + 1);
  }
  EXPECT_EQ(tied.first_change, -1);
  for (double ch : tied.changed) EXPECT_EQ(ch, 0.0);  // never remeshed (a remesh would report its change)
  const auto ratio = [&](const Curve& c, int step) { return c.force[std::size_t(step)] / uphi.force[std::size_t(step)]; };
  EXPECT_LT(ratio(tied, 100), 1.0);    // observed 0.975: still the softer one mid-way (crossing at step 140)
  EXPECT_GT(ratio(tied, kSteps), 1.03);  // observed 1.066 (6.927 against 6.498 N)
  EXPECT_LT(ratio(plain, kSteps), 0.97);  // observed 0.938 (6.095 N)
  int crossing = -1;
  for (int s = 1; s <= kSteps && crossing < 0; ++s)
    if (ratio(tied, s) > 1.0) crossing = s;
  std::printf("[constrained block pfem] Fig 10: tri6/p1p1_uphi(K/10) with eq-24 ties, no remesh: %.4f (step 10), %.4f (100), %.4f (200), "
              "above 1 from step %d; plain FEM tri6: %.4f (200); final %.4f / %.4f / %.4f N\n",
              ratio(tied, 10), ratio(tied, 100), ratio(tied, kSteps), crossing, ratio(plain, kSteps), tied.force.back(),
              plain.force.back(), uphi.force.back());
}

// Finer meshes stop much earlier (16x8: after step 60), and not for the mid-nodes: the constant l_char of
// the scene (0.2 mm, chosen for the 8x4 mesh) lets the alpha test (R < 1.1 l_char = 0.22 mm) admit the
// triangle that bridges the kink at the indenter's edge once it is small enough (R = 0.2188 mm at step 60
// on 16x8), and the new cell in the nearly incompressible block stops Newton. The failure says so; with
// l_char scaled to the mesh (0.1 mm) the same run goes on to step 160.
TEST(ConstrainedBlockPfem, Tri6OnAFinerMeshStopsWhenTheAlphaShapeBridgesTheIndenterKink) {
  const std::vector<std::string> mesh = {"body[0].mesh.divisions=[16,8]", "time.steps=70"};
  const Curve p = pfem("tri6", "", mesh);
  ASSERT_FALSE(p.summary.converged);
  EXPECT_EQ(p.summary.last_converged_step, 60);
  EXPECT_EQ(p.first_change, -1);  // every converged step kept the connectivity
  EXPECT_NE(p.summary.failure.find("the remesh before this step changed the connectivity"), std::string::npos) << p.summary.failure;
  std::vector<std::string> scaled = mesh;
  scaled.push_back("remesh.lchar=0.1");
  const Curve q = pfem("tri6", "", scaled);
  EXPECT_TRUE(q.summary.converged) << q.summary.failure;  // 70 steps (observed: up to step 160)
  std::printf("[constrained block pfem] tri6 16x8: l_char 0.2 mm stops after step %d (%s); l_char 0.1 mm runs %d steps\n",
              p.summary.last_converged_step, p.summary.failure.c_str(), q.summary.last_converged_step);
}

}  // namespace
}  // namespace loom
