// Checkpoints and restarts (`[output] checkpoint_every`, `loom run --stop-after N`, `--restart DIR`) and a
// clean stop on SIGINT. The contract: a run stopped after step N and continued from its checkpoint writes
// the same probes.csv as the run that never stopped, byte for byte, and the same last frame -- for fem
// (static and dynamic), for pfem across remeshes that change the connectivity (both before and after the
// checkpoint), and for mpm (ASGS, and OSGS whose residual projections are carried by the particles).
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <thread>

#include "engine/core/interrupt.hpp"
#include "engine/scene/scene_loader.hpp"
#include "tests/scenes/scene_checks.hpp"
#include "tests/support/test_support.hpp"

namespace loom::testing {
namespace {

const std::string kSource = LOOM_SOURCE_DIR;

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& sets) {
  for (const auto& s : sets) args.push_back("--set"), args.push_back(s);
  return args;
}

// Runs `loom run SCENE --quiet --out OUT` with the overrides in a child process, sends it SIGINT once `wait_for`
// exists (or after 60 s) and returns its wait status; its stderr is left in OUT.err.
int interrupt_when(const std::string& scene, const std::string& out, const std::vector<std::string>& sets, const std::string& wait_for) {
  std::vector<std::string> args = with({LOOM_BINARY, "run", scene, "--quiet", "--out", out}, sets);
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    freopen((out + ".err").c_str(), "w", stderr);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(LOOM_BINARY, argv.data());
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!std::filesystem::exists(wait_for) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

// Runs the scene whole, then stopped after `stop` and continued; returns the whole run's probes.
ProbeTable expect_restart_reproduces(const std::string& name, const std::string& scene, const std::vector<std::string>& sets, int stop,
                                      int steps, const std::string& last_frame) {
  TempDir dir("restart_" + name);
  const std::string full = dir.file("full"), part = dir.file("part");
  const Command a = run_loom(with({"run", scene, "--quiet", "--out", full}, sets));
  EXPECT_EQ(a.exit_code, 0) << a.err;
  const Command b = run_loom(with({"run", scene, "--quiet", "--out", part, "--stop-after", std::to_string(stop)}, sets));
  EXPECT_EQ(b.exit_code, 0) << b.err;
  EXPECT_NE(b.err.find("stopped as asked after step " + std::to_string(stop)), std::string::npos) << b.err;
  EXPECT_NE(b.err.find("--restart " + part), std::string::npos) << b.err;
  const Json stopped = parse_json(read_text(part + "/run.json"));
  EXPECT_EQ(stopped.at("status").string, "stopped");
  EXPECT_EQ(stopped.at("last_converged_step").number, double(stop));
  EXPECT_TRUE(std::filesystem::exists(part + "/checkpoint_" + std::string(6 - std::to_string(stop).size(), '0') + std::to_string(stop) + ".loom"));
  const Command c = run_loom(with({"run", scene, "--quiet", "--restart", part}, sets));
  EXPECT_EQ(c.exit_code, 0) << c.err;
  const std::string probes = read_text(full + "/probes.csv");
  EXPECT_EQ(read_text(part + "/probes.csv"), probes) << name << ": the continued run's probes differ from the whole run's";
  EXPECT_EQ(read_probes(part + "/probes.csv").rows.size(), std::size_t(steps) + 1);
  const Json whole = parse_json(read_text(full + "/run.json")), continued = parse_json(read_text(part + "/run.json"));
  EXPECT_EQ(continued.at("status").string, "completed");
  EXPECT_EQ(continued.at("restarted_from_step").number, double(stop));
  EXPECT_EQ(continued.at("steps_done").number, double(steps));
  EXPECT_EQ(continued.at("newton_iterations").number, whole.at("newton_iterations").number);
  EXPECT_EQ(read_text(part + "/" + last_frame), read_text(full + "/" + last_frame)) << last_frame;
  EXPECT_FALSE(read_text(part + "/" + last_frame).empty()) << last_frame;
  for (const auto& f : files_under(part)) EXPECT_EQ(f.find(".tmp"), std::string::npos) << f;
  return read_probes(full + "/probes.csv");
}

TEST(Restart, FemStaticContinuesBitForBit) {
  expect_restart_reproduces("fem", kSource + "/scenes/constrained_block_fem.toml",
                            {"output.every=20", "output.checkpoint_every=25"}, 57, 200, "constrained-block-fem_000200.vtu");
}

TEST(Restart, FemDynamicContinuesBitForBit) {
  expect_restart_reproduces("fem_dynamic", kSource + "/tests/stress/scenes/cantilever_release.toml",
                            {"time.steps=60", "output.every=30"}, 23, 60, "cantilever-release_000060.vtu");
}

// Seed 001's elements carry their history on the integration domains (b^e_n of every edge) and the pressure
// as a nodal unknown; the Bossak cantilever needs both plus a_n in the checkpoint.
TEST(Restart, EsFemBossakContinuesBitForBit) {
  expect_restart_reproduces("es_fem", kSource + "/scenes/cantilever_dynamic_es.toml",
                            {"time.steps=40", "output.every=20", "body[0].mesh.divisions=[16,4]"}, 17, 40,
                            "cantilever-dynamic-es_000040.vtu");
}

// es_pfem: the edges are rebuilt at every remesh (every second step here, 14 connectivity changes in 30 steps);
// the checkpoint of step 16 holds remeshed edges, and step 17 runs on them without a remesh (their colouring
// is rebuilt on restore: it is not a column).
TEST(Restart, EsPfemContinuesBitForBitAcrossRemeshes) {
  expect_restart_reproduces("es_pfem", kSource + "/tests/scenes/es_pfem_bingham_column.toml", {"output.every=10"}, 16, 30,
                            "es-pfem-bingham-column_000030.vtu");
}

// The moderately constrained block first changes its connectivity at step 138 and then 118 more times up
// to step 220: the checkpoint of step 150 holds a remeshed mesh (not the generated one), and the continued
// run remeshes it on, with TRI6 mid-nodes re-created at every remesh.
TEST(Restart, PfemContinuesBitForBitAcrossConnectivityChanges) {
  for (const char* element : {"p1p1_uphi", "tri6"}) {
    SCOPED_TRACE(element);
    const ProbeTable table = expect_restart_reproduces(
        std::string("pfem_") + element, kSource + "/scenes/moderate_block_pfem.toml",
        {"time.steps=200", "output.every=50", std::string("body[0].element=\"") + element + "\""}, 150, 200, "moderate-block-pfem_000200.vtu");
    const auto changed = table.column("changed");
    int before = 0, after = 0;
    for (std::size_t s = 1; s < changed.size(); ++s) (s <= 150 ? before : after) += changed[s] == 1.0;
    EXPECT_GT(before, 0);
    EXPECT_GT(after, 0);
  }
}

TEST(Restart, MpmContinuesBitForBit) {
  expect_restart_reproduces("mpm", kSource + "/scenes/cooks_membrane_mpm_dynamic.toml",
                            {"time.steps=16", "output.every=8", "body[0].particles_per_cell=3"}, 7, 16,
                            "cooks-membrane-mpm-dynamic_000016_particles.vtp");
  expect_restart_reproduces("mpm_osgs", kSource + "/scenes/cooks_membrane_mpm_dynamic.toml",
                            {"time.steps=8", "output.every=4", "body[0].particles_per_cell=3", "body[0].stabilisation=\"osgs\""}, 3, 8,
                            "cooks-membrane-mpm-dynamic_000008_grid.vtu");
}

// hencky_perzyna at the particles: b^e is part of the particles' checkpoint. A block that yields under its weight, by
// both schemes (the particles' b^e changes every step; without it the continued run would restart from b^e = I).
TEST(Restart, MpmBinghamContinuesBitForBit) {
  const std::vector<std::string> yielding = {"output.every=5", "time.steps=10", "material[0].tau0=3000", "material[0].viscosity=1e5"};
  expect_restart_reproduces("mpm_bingham", kSource + "/tests/scenes/mpm_bingham_block.toml", yielding, 4, 10,
                            "mpm-bingham-block_000010_particles.vtp");
  std::vector<std::string> particle_newmark = yielding;
  for (const char* set : {"mpm.scheme=\"particle_newmark\"", "grid.cells=\"quad4\"", "grid.ghost_penalty=0", "time.integrator=\"newmark\"",
                          "time.beta=0.49", "time.gamma=0.9"})
    particle_newmark.push_back(set);
  expect_restart_reproduces("mpm_bingham_particle_newmark", kSource + "/tests/scenes/mpm_bingham_block.toml", particle_newmark, 4, 10,
                            "mpm-bingham-block_000010_particles.vtp");
}

// ... and at the quadrature points of fem's tri6 (QuadPoints::be_n in the checkpoint).
TEST(Restart, FemBinghamContinuesBitForBit) {
  expect_restart_reproduces("fem_bingham", kSource + "/tests/scenes/fem_bingham_block.toml", {}, 4, 10, "fem-bingham-block_000010.vtu");
  // pfem: the checkpoint of step 4 holds remeshed cells with mapped b^e (the block's connectivity changes in most steps).
  expect_restart_reproduces("pfem_bingham", kSource + "/tests/scenes/fem_bingham_block.toml", {"scene.method=\"pfem\""}, 4, 10,
                            "fem-bingham-block_000010.vtu");
}

// SIGINT stops the run after the step in progress: exit 130, run.json says "interrupted" with the last
// completed step, timings.json is written, no temporary file is left, and the checkpoint it writes
// continues to the very probes of an uninterrupted run. Where the signal lands does not matter.
TEST(Restart, SigintStopsCleanlyAndTheRunContinuesBitForBit) {
  TempDir dir("restart_sigint");
  const std::string scene = kSource + "/scenes/moderate_block_pfem.toml";
  const std::vector<std::string> sets = {"time.steps=400", "output.every=20", "output.checkpoint_every=50"};
  const std::string out = dir.file("run");
  // Interrupt once the first periodic checkpoint exists (the run is then past step 50 of 400).
  const int status = interrupt_when(scene, out, sets, out + "/checkpoint_000050.loom");
  ASSERT_TRUE(WIFEXITED(status)) << "killed by a signal instead of stopping cleanly";
  const std::string err = read_text(out + ".err");
  ASSERT_EQ(WEXITSTATUS(status), 130) << err;
  EXPECT_NE(err.find("interrupted by SIGINT after step "), std::string::npos) << err;
  const Json run = parse_json(read_text(out + "/run.json"));
  EXPECT_EQ(run.at("status").string, "interrupted");
  EXPECT_EQ(run.at("interrupted_by").string, "SIGINT");
  const int last = int(run.at("last_converged_step").number);
  EXPECT_GE(last, 50);
  EXPECT_LT(last, 400);
  EXPECT_EQ(read_probes(out + "/probes.csv").rows.size(), std::size_t(last) + 1);
  EXPECT_NO_THROW(parse_json(read_text(out + "/timings.json")));
  for (const auto& f : files_under(out)) EXPECT_EQ(f.find(".tmp"), std::string::npos) << f;
  const std::string checkpoint = out + "/checkpoint_" + std::string(6 - std::to_string(last).size(), '0') + std::to_string(last) + ".loom";
  EXPECT_TRUE(std::filesystem::exists(checkpoint)) << "an interrupted run with checkpoints enabled writes one of its last step";
  const Command c = run_loom(with({"run", scene, "--quiet", "--restart", out}, sets));
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const Command whole = run_loom(with({"run", scene, "--quiet", "--out", dir.file("whole")}, sets));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(read_text(out + "/probes.csv"), read_text(dir.file("whole") + "/probes.csv"));
  EXPECT_EQ(parse_pvd(read_text(out + "/moderate-block-pfem.pvd")).size(), parse_pvd(read_text(dir.file("whole") + "/moderate-block-pfem.pvd")).size());
}

TEST(Restart, BadRestartsAreBadInput) {
  TempDir dir("restart_bad");
  const std::string scene = kSource + "/scenes/constrained_block_fem.toml";
  const Command none = run_loom({"run", scene, "--quiet", "--restart", dir.path()});
  EXPECT_EQ(none.exit_code, 2) << none.err;
  EXPECT_NE(none.err.find("no checkpoint in this directory"), std::string::npos) << none.err;
  const Command stop = run_loom({"run", scene, "--quiet", "--out", dir.path(), "--stop-after", "10"});
  ASSERT_EQ(stop.exit_code, 0) << stop.err;
  const std::string checkpoint = dir.file("checkpoint_000010.loom");
  // Another method's scene.
  const Command other = run_loom({"run", kSource + "/scenes/constrained_block_pfem.toml", "--quiet", "--restart", dir.path()});
  EXPECT_EQ(other.exit_code, 2) << other.err;
  EXPECT_NE(other.err.find("the checkpoint is of a method fem run; the scene runs method pfem"), std::string::npos) << other.err;
  // --out elsewhere.
  const Command out = run_loom({"run", scene, "--quiet", "--restart", dir.path(), "--out", dir.file("elsewhere")});
  EXPECT_EQ(out.exit_code, 2) << out.err;
  EXPECT_NE(out.err.find("a restarted run continues in the directory of its checkpoint"), std::string::npos) << out.err;
  // --stop-after at or before the checkpoint's step.
  const Command early = run_loom({"run", scene, "--quiet", "--restart", dir.path(), "--stop-after", "10"});
  EXPECT_EQ(early.exit_code, 2) << early.err;
  EXPECT_NE(early.err.find("--stop-after 10: error: the run continues from the checkpoint of step 10"), std::string::npos) << early.err;
  // A truncated file.
  std::string bytes = read_text(checkpoint);
  write_text(checkpoint, bytes.substr(0, bytes.size() / 2));
  const Command cut = run_loom({"run", scene, "--quiet", "--restart", checkpoint});
  EXPECT_EQ(cut.exit_code, 2) << cut.err;
  EXPECT_NE(cut.err.find("truncated or corrupt"), std::string::npos) << cut.err;
  for (const Command* c : {&none, &other, &out, &early, &cut}) EXPECT_FALSE(looks_like_crash(c->err)) << c->err;
}

// A checkpoint of another mesh or other particles than the scene builds is bad input, not a crash (it loaded
// columns of any size into stores whose system was built for the scene: a segfault, or a singular tangent).
TEST(Restart, ACheckpointOfAnotherMeshIsBadInput) {
  const struct {
    std::string name, scene, set;
  } cases[] = {{"fem", "constrained_block_fem.toml", "body[0].mesh.divisions=[16,8]"},
               {"pfem", "constrained_block_pfem.toml", "body[0].mesh.divisions=[16,8]"},
               {"mpm", "cooks_membrane_mpm_dynamic.toml", "body[0].particles_per_cell=3"}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    TempDir dir("restart_mesh_" + c.name);
    const std::string scene = kSource + "/scenes/" + c.scene;
    const Command stop = run_loom({"run", scene, "--quiet", "--out", dir.path(), "--set", c.set, "--set", "output.every=0", "--stop-after", "1"});
    ASSERT_EQ(stop.exit_code, 0) << stop.err;
    const Command other = run_loom({"run", scene, "--quiet", "--restart", dir.path(), "--set", "output.every=0"});
    EXPECT_EQ(other.exit_code, 2) << other.err;
    EXPECT_NE(other.err.find("differs from the one the checkpoint was written for"), std::string::npos) << other.err;
    EXPECT_FALSE(looks_like_crash(other.err)) << other.err;
  }
}

// A restart into a directory that holds more than the checkpoint -- the whole run, which went on past its
// last checkpoint: probes.csv is cut back to the checkpoint's step, later frames go, the collection lists the
// frames up to the checkpoint, and the continued run writes the same files again.
TEST(Restart, ContinuingADirectoryThatWentPastItsCheckpointRewritesTheSameFiles) {
  TempDir dir("restart_past");
  const std::string scene = kSource + "/scenes/constrained_block_fem.toml";
  const std::vector<std::string> sets = {"time.steps=100", "output.every=20", "output.checkpoint_every=30"};
  const Command whole = run_loom(with({"run", scene, "--quiet", "--out", dir.path()}, sets));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_TRUE(std::filesystem::exists(dir.file("checkpoint_000090.loom")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("checkpoint_000060.loom"))) << "only the newest checkpoint is kept";
  const std::string probes = read_text(dir.file("probes.csv")), last = read_text(dir.file("constrained-block-fem_000100.vtu"));
  const std::string pvd = read_text(dir.file("constrained-block-fem.pvd"));
  const Command again = run_loom(with({"run", scene, "--quiet", "--restart", dir.path()}, sets));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(read_text(dir.file("probes.csv")), probes);
  EXPECT_EQ(read_text(dir.file("constrained-block-fem_000100.vtu")), last);
  EXPECT_EQ(read_text(dir.file("constrained-block-fem.pvd")), pvd);
  EXPECT_EQ(parse_json(read_text(dir.file("run.json"))).at("restarted_from_step").number, 90.0);
}

// A run continued with another time step (a slow flow after its pouring, say) goes on from the checkpoint's time
// in steps of the new size. Its steps once ended at n dt counted from t = 0, so the first continued step ran
// from the checkpoint's time to n dt_new at once, or, with n dt_new behind it, the steps did nothing.
// time.adaptive_dt on a mesh method (es_pfem: Bossak, remeshing) does in one run what a run stopped and
// continued with another time.dt does: 10 steps of 2 ms, then 20 of 4 ms. The two differ only by round-off in
// t (summed steps against n dt), so the probes agree to 1e-9, not to the bit.
TEST(Restart, AnAdaptiveStepDoesInOneRunWhatARestartWithANewStepDoes) {
  TempDir dir("restart_adaptive");
  const std::string scene = kSource + "/tests/scenes/es_pfem_bingham_column.toml";
  const std::string phased = dir.file("phased"), adaptive = dir.file("adaptive");
  const Command first = run_loom({"run", scene, "--quiet", "--out", phased, "--set", "output.every=0", "--stop-after", "10"});
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const Command second = run_loom({"run", scene, "--quiet", "--restart", phased, "--set", "output.every=0", "--set", "time.dt=4e-3"});
  ASSERT_EQ(second.exit_code, 0) << second.err;
  const Command one = run_loom({"run", scene, "--quiet", "--out", adaptive, "--set", "output.every=0", "--set", "time.steps=40", "--set",
                                "time.adaptive_dt={ probe = \"top\", expression = \"t < 0.019 ? 2e-3 : 4e-3\" }", "--set", "time.end=0.1"});
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const ProbeTable a = read_probes(phased + "/probes.csv"), b = read_probes(adaptive + "/probes.csv");
  ASSERT_EQ(a.names, b.names);
  ASSERT_EQ(a.rows.size(), 31u);
  ASSERT_EQ(b.rows.size(), 31u);  // time.end = 0.1 s closes the run after 30 steps
  const auto time = b.column("time");
  for (int n = 1; n <= 30; ++n) EXPECT_NEAR(time[std::size_t(n)], n <= 10 ? 2e-3 * n : 0.02 + 4e-3 * (n - 10), 1e-14) << "step " << n;
  for (std::size_t r = 0; r < a.rows.size(); ++r)
    for (std::size_t k = 0; k < a.names.size(); ++k)
      EXPECT_NEAR(b.rows[r][k], a.rows[r][k], 1e-9 * std::max(1.0, std::abs(a.rows[r][k]))) << a.names[k] << " at step " << r;
  const auto changed = a.column("changed");
  EXPECT_GT(std::count(changed.begin() + 11, changed.end(), 1.0), 0) << "no remesh changed the connectivity after the switch";
}

TEST(Restart, ANewTimeStepGoesOnFromTheCheckpointsTime) {
  TempDir dir("restart_dt");
  const std::string scene = kSource + "/tests/stress/scenes/cantilever_release.toml";
  const Command stop = run_loom({"run", scene, "--quiet", "--out", dir.path(), "--set", "time.steps=30", "--set", "output.every=0", "--stop-after", "10"});
  ASSERT_EQ(stop.exit_code, 0) << stop.err;
  for (const char* dt : {"0.05", "0.4"}) {
    SCOPED_TRACE(dt);
    const std::string part = dir.file(std::string("dt_") + dt);
    std::filesystem::create_directories(part);
    std::filesystem::copy(dir.file("checkpoint_000010.loom"), part + "/checkpoint_000010.loom");
    std::filesystem::copy(dir.file("probes.csv"), part + "/probes.csv");
    const Command c = run_loom({"run", scene, "--quiet", "--restart", part, "--set", "time.steps=30", "--set", "output.every=0",
                                "--set", std::string("time.dt=") + dt});
    ASSERT_EQ(c.exit_code, 0) << c.err;
    EXPECT_NE(c.err.find("differ from those of the run that wrote the checkpoint"), std::string::npos) << c.err;
    const auto time = read_probes(part + "/probes.csv").column("time");
    ASSERT_EQ(time.size(), 31u);
    EXPECT_NEAR(time[10], 1.0, 1e-12);
    for (int n = 11; n <= 30; ++n) EXPECT_NEAR(time[std::size_t(n)], 1.0 + (n - 10) * std::stod(dt), 1e-12) << "step " << n;
    const Json run = parse_json(read_text(part + "/run.json"));
    EXPECT_EQ(run.at("status").string, "completed");
    EXPECT_NEAR(run.at("last_converged_time").number, 1.0 + 20 * std::stod(dt), 1e-12);
  }
}

// Interrupted before its first step: the checkpoint of step 0 continues like a fresh run (step 0's row and
// frame are not written twice), and its directory can be continued again.
TEST(Restart, ACheckpointOfStepZeroContinuesLikeAFreshRun) {
  TempDir dir("restart_zero");
  const std::string scene = kSource + "/scenes/constrained_block_fem.toml";
  const std::vector<std::string> sets = {"time.steps=20", "output.every=5", "output.checkpoint_every=7"};
  {
    const SceneSpec spec = load_scene(scene, sets);
    auto run = make_fem_run(spec, dir.file("part"));
    request_interrupt(SIGINT);
    const RunSummary s = run->run();
    clear_interrupt();
    EXPECT_EQ(s.interrupted_by, SIGINT);
    EXPECT_EQ(s.last_converged_step, 0);
  }
  ASSERT_TRUE(std::filesystem::exists(dir.file("part/checkpoint_000000.loom")));
  const Command c = run_loom(with({"run", scene, "--quiet", "--restart", dir.file("part")}, sets));
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const Command whole = run_loom(with({"run", scene, "--quiet", "--out", dir.file("whole")}, sets));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(read_text(dir.file("part/probes.csv")), read_text(dir.file("whole/probes.csv")));
  EXPECT_EQ(read_text(dir.file("part/constrained-block-fem.pvd")), read_text(dir.file("whole/constrained-block-fem.pvd")));
}

// SIGINT without [output] checkpoint_every: the run still leaves a checkpoint of its last step and that step as the
// last frame of its collection (it left nothing to continue from and ended the collection at the last periodic
// frame); the continued run's probes and collection are those of a run that never stopped.
TEST(Restart, SigintWithoutCheckpointEveryLeavesACheckpointAndTheLastFrame) {
  TempDir dir("restart_sigint_plain");
  const std::string scene = kSource + "/scenes/moderate_block_pfem.toml";
  const std::vector<std::string> sets = {"time.steps=400", "output.every=20"};
  const std::string out = dir.file("run");
  const int status = interrupt_when(scene, out, sets, out + "/moderate-block-pfem_000040.vtu");
  ASSERT_TRUE(WIFEXITED(status)) << "killed by a signal instead of stopping cleanly";
  const std::string err = read_text(out + ".err");
  ASSERT_EQ(WEXITSTATUS(status), 130) << err;
  EXPECT_NE(err.find("; continue with: "), std::string::npos) << err;
  const int last = int(parse_json(read_text(out + "/run.json")).at("last_converged_step").number);
  ASSERT_GE(last, 40);
  ASSERT_LT(last, 400);
  std::ostringstream checkpoint;
  checkpoint << out << "/checkpoint_" << std::setw(6) << std::setfill('0') << last << ".loom";
  EXPECT_TRUE(std::filesystem::exists(checkpoint.str())) << checkpoint.str();
  const ProbeTable probes = read_probes(out + "/probes.csv");
  ASSERT_EQ(probes.rows.size(), std::size_t(last) + 1);
  const auto entries = parse_pvd(read_text(out + "/moderate-block-pfem.pvd"));
  ASSERT_FALSE(entries.empty());
  EXPECT_EQ(entries.back().time, probes.column("time").back()) << "the collection does not end at the state the run reached";
  EXPECT_TRUE(std::filesystem::exists(out + "/" + entries.back().file)) << entries.back().file;

  const Command c = run_loom(with({"run", scene, "--quiet", "--restart", out}, sets));
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const Command whole = run_loom(with({"run", scene, "--quiet", "--out", dir.file("whole")}, sets));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(read_text(out + "/probes.csv"), read_text(dir.file("whole") + "/probes.csv"));
  EXPECT_EQ(read_text(out + "/moderate-block-pfem.pvd"), read_text(dir.file("whole") + "/moderate-block-pfem.pvd"));
  if (last % 20 != 0) {  // the interrupted state's frame, not one of the run's, is gone from the directory
    std::ostringstream extra;
    extra << "moderate-block-pfem_" << std::setw(6) << std::setfill('0') << last << ".vtu";
    EXPECT_FALSE(std::filesystem::exists(out + "/" + extra.str())) << extra.str();
  }
}

// A run that ends at time.end (time.adaptive_dt) ends between frames: its last state is still the last frame (the
// collection ended at the last frame step before it).
TEST(Restart, AnAdaptiveRunEndsItsCollectionAtTimeEnd) {
  TempDir dir("adaptive_last_frame");
  const Command c = run_loom({"run", kSource + "/tests/scenes/es_pfem_bingham_column.toml", "--quiet", "--out", dir.path(), "--set",
                              "output.every=7", "--set", "time.steps=40", "--set",
                              "time.adaptive_dt={ probe = \"top\", expression = \"t < 0.019 ? 2e-3 : 4e-3\" }", "--set", "time.end=0.1"});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const auto entries = parse_pvd(read_text(dir.file("es-pfem-bingham-column.pvd")));
  ASSERT_GE(entries.size(), 2u);
  EXPECT_NEAR(entries.back().time, 0.1, 1e-12);
  EXPECT_EQ(entries.back().file, "es-pfem-bingham-column_000030.vtu");
  EXPECT_TRUE(std::filesystem::exists(dir.file(entries.back().file)));
  EXPECT_NEAR(entries[entries.size() - 2].time, 0.02 + 4e-3 * 18, 1e-12);  // step 28, the last frame step
}

}  // namespace
}  // namespace loom::testing
