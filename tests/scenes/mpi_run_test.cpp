// `mpirun -n 2 loom run` (engine/cli/mpi_launch.hpp, engine/linalg/petsc_system.hpp): the ranks solve each Newton system
// together and rank 0 writes what a one-process run writes. Shown on the mixed u-phi block in 3D (fieldsplit) and the
// grid-Newmark MPM cantilever (CG + GAMG): the probes of one process to the linear tolerance, MUMPS across the ranks
// as UMFPACK on one process to round-off, two 2-rank runs byte-identical, a 2-rank run stopped and continued as the
// uninterrupted one, ranks signalled stopping after the same step, and a scene that cannot run on ranks refused once,
// naming the key. This program is not itself
// under mpirun: it starts mpirun (LOOM_MPIEXEC) for each run.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/scenes/scene_checks.hpp"
#include "tests/support/run_comparison.hpp"

namespace loom {
namespace {

using testing::TempDir;

// loom run SCENE --out DIR --quiet SETS... on `ranks` MPI ranks (1: without mpirun).
testing::Command run(int ranks, const std::string& scene, const std::string& out, std::vector<std::string> args) {
  std::string cmd = ranks > 1 ? std::string(LOOM_MPIEXEC) + " -n " + std::to_string(ranks) + " --oversubscribe " : "";
  cmd += testing::shell_quote(LOOM_BINARY) + " run " + testing::shell_quote(std::string(LOOM_SOURCE_DIR) + "/scenes/" + scene) + " --quiet --threads 1";
  if (!out.empty()) cmd += " --out " + testing::shell_quote(out);
  for (const auto& a : args) cmd.append(" ").append(testing::shell_quote(a));
  const std::string log = out.empty() ? std::filesystem::temp_directory_path().string() + "/loom_mpi_run" : out + ".log";
  cmd += " >" + testing::shell_quote(log + ".out") + " 2>" + testing::shell_quote(log + ".err");
  const int status = std::system(cmd.c_str());
  testing::Command c;
  c.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  c.out = testing::read_text(log + ".out");
  c.err = testing::read_text(log + ".err");
  return c;
}

const std::vector<std::string> kBlock = {"--set", "body[0].mesh.divisions=[4,4,4]", "--set", "time.steps=4", "--set", "solver.linear=\"petsc\""};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

TEST(MpiRun, TwoRanksGiveOneProcesssAnswerAndRankZeroWritesWhatOneProcessWrites) {
  TempDir one("mpi_one"), two("mpi_two"), again("mpi_again");
  const testing::Command a = run(1, "block_3d.toml", one.path() + "/out", kBlock);
  const testing::Command b = run(2, "block_3d.toml", two.path() + "/out", kBlock);
  const testing::Command c = run(2, "block_3d.toml", again.path() + "/out", kBlock);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  ASSERT_EQ(c.exit_code, 0) << c.err;
  // GAMG's aggregates depend on the partition: the same answer to the linear tolerance, not bit for bit.
  EXPECT_LE(testing::probe_difference(testing::read_probes(one.path() + "/out/probes.csv"), testing::read_probes(two.path() + "/out/probes.csv")), 1e-8);
  const std::vector<std::string> files = testing::files_under(two.path() + "/out");
  EXPECT_EQ(files, testing::files_under(one.path() + "/out"));  // nothing per rank, nothing missing
  const testing::Json report = testing::parse_json(testing::read_text(two.path() + "/out/run.json"));
  EXPECT_EQ(report.at("ranks").number, 2.0);
  EXPECT_EQ(report.at("status").string, "completed");
  // Two 2-rank runs: byte-identical frames and probes (PETSc assembles no value across ranks).
  for (const std::string& f : files) {
    if (f == "run.json" || f == "timings.json") continue;
    EXPECT_EQ(testing::read_text(two.path() + "/out/" + f), testing::read_text(again.path() + "/out/" + f)) << f;
  }
  EXPECT_EQ(b.out, "");  // --quiet; and rank 1 prints nothing at all
}

TEST(MpiRun, MumpsAcrossTwoRanksIsUmfpackToRoundOff) {
  TempDir mumps("mpi_mumps"), umfpack("mpi_umfpack");
  const testing::Command a =
      run(2, "block_3d.toml", mumps.path() + "/out", with(kBlock, {"--set", "solver.petsc_options=\"-ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps\""}));
  const testing::Command b = run(1, "block_3d.toml", umfpack.path() + "/out",
                                 {"--set", "body[0].mesh.divisions=[4,4,4]", "--set", "time.steps=4", "--set", "solver.linear=\"umfpack\""});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_LE(testing::probe_difference(testing::read_probes(mumps.path() + "/out/probes.csv"), testing::read_probes(umfpack.path() + "/out/probes.csv")), 1e-11);
}

// MPM's grid changes its active cells every step (a new pattern, a new partition of its rows): the 2-rank run follows
// the one-process run to the linear tolerance.
TEST(MpiRun, TheMpmCantileverOnTwoRanksFollowsOneProcess) {
  TempDir one("mpi_mpm_one"), two("mpi_mpm_two");
  const std::vector<std::string> args = {"--set", "time.steps=20", "--set", "solver.linear=\"petsc\""};
  const testing::Command a = run(1, "cantilever_mpm_grid_newmark.toml", one.path() + "/out", args);
  const testing::Command b = run(2, "cantilever_mpm_grid_newmark.toml", two.path() + "/out", args);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_LE(testing::probe_difference(testing::read_probes(one.path() + "/out/probes.csv"), testing::read_probes(two.path() + "/out/probes.csv")), 1e-7);
}

// A 2-rank run stopped after step 2 writes one checkpoint (rank 0's), and continued on two ranks it ends where the
// uninterrupted run ends (to the linear tolerance: GAMG's interpolation is rebuilt from a later matrix).
TEST(MpiRun, AStoppedTwoRankRunContinuesOnTwoRanks) {
  TempDir whole("mpi_whole"), parts("mpi_parts");
  const std::vector<std::string> args = with(kBlock, {"--set", "output.checkpoint_every=0"});
  ASSERT_EQ(run(2, "block_3d.toml", whole.path() + "/out", args).exit_code, 0);
  const testing::Command first = run(2, "block_3d.toml", parts.path() + "/out", with(args, {"--stop-after", "2"}));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const testing::Command rest = run(2, "block_3d.toml", "", with(args, {"--restart", parts.path() + "/out"}));
  ASSERT_EQ(rest.exit_code, 0) << rest.err;
  EXPECT_LE(testing::probe_difference(testing::read_probes(whole.path() + "/out/probes.csv"), testing::read_probes(parts.path() + "/out/probes.csv")), 1e-8);
  EXPECT_EQ(testing::files_under(whole.path() + "/out").size() + 1, testing::files_under(parts.path() + "/out").size());  // + the checkpoint
}

// SIGTERM sent to the ranks (not to mpirun, which kills its ranks a second after it is signalled) reaches each at its
// own moment; they agree at the next step boundary, all stop after the same step, and rank 0 writes that step's
// checkpoint, from which two ranks continue to the end.
TEST(MpiRun, SignalledRanksStopAfterTheSameStepAndContinueFromRankZerosCheckpoint) {
  TempDir dir("mpi_signal");
  const std::string out = dir.path() + "/out", code = dir.path() + "/code";
  const std::vector<std::string> args = with(kBlock, {"--set", "time.steps=100", "--set", "time.dt=0.01"});
  std::string cmd = std::string(LOOM_MPIEXEC) + " -n 2 --oversubscribe " + testing::shell_quote(LOOM_BINARY) + " run " +
                    testing::shell_quote(std::string(LOOM_SOURCE_DIR) + "/scenes/block_3d.toml") + " --quiet --out " + testing::shell_quote(out);
  for (const auto& a : args) cmd.append(" ").append(testing::shell_quote(a));
  ASSERT_EQ(std::system(("(" + cmd + " >/dev/null 2>&1; echo $? > " + testing::shell_quote(code) + ") &").c_str()), 0);
  auto lines = [](const std::string& path) {
    const std::string text = std::filesystem::exists(path) ? testing::read_text(path) : std::string();
    return std::count(text.begin(), text.end(), '\n');
  };
  for (int wait = 0; wait < 1200 && lines(out + "/probes.csv") < 4; ++wait) usleep(50000);  // step 2 written
  // The ranks' command lines start with the loom binary (mpirun's with mpiexec).
  const std::string ranks = std::string("^").append(LOOM_BINARY).append(" run .*").append(out);
  EXPECT_EQ(std::system(("pkill -TERM -f " + testing::shell_quote(ranks)).c_str()), 0) << "no rank was running";
  for (int wait = 0; wait < 1200 && !std::filesystem::exists(code); ++wait) usleep(50000);
  ASSERT_TRUE(std::filesystem::exists(code)) << "the ranks did not stop";
  const testing::Json report = testing::parse_json(testing::read_text(out + "/run.json"));
  ASSERT_EQ(report.at("status").string, "interrupted");
  EXPECT_EQ(report.at("interrupted_by").string, "SIGTERM");
  const int stopped = int(report.at("steps_done").number);
  EXPECT_LT(stopped, 100);
  char checkpoint[32];
  std::snprintf(checkpoint, sizeof checkpoint, "checkpoint_%06d.loom", stopped);
  EXPECT_TRUE(std::filesystem::exists(out + "/" + checkpoint)) << checkpoint;
  EXPECT_EQ(testing::read_probes(out + "/probes.csv").rows.size(), std::size_t(stopped) + 1);
  const testing::Command rest = run(2, "block_3d.toml", "", with(args, {"--restart", out}));
  ASSERT_EQ(rest.exit_code, 0) << rest.err;
  EXPECT_EQ(testing::parse_json(testing::read_text(out + "/run.json")).at("steps_done").number, 100.0);
}

TEST(MpiRun, ASceneThatDoesNotSolveWithPetscIsRefusedOnceNamingTheKey) {
  TempDir dir("mpi_refused");
  const testing::Command c = run(2, "block_3d.toml", dir.path() + "/out", {"--set", "body[0].mesh.divisions=[2,2,2]"});
  EXPECT_EQ(c.exit_code, 2) << c.err;
  const std::string key = "error: solver.linear: a run on 2 MPI ranks solves with solver.linear = \"petsc\"";
  const std::size_t first = c.err.find(key);
  ASSERT_NE(first, std::string::npos) << c.err;
  EXPECT_EQ(c.err.find(key, first + 1), std::string::npos) << "rank 1 repeated it:\n" << c.err;
  EXPECT_FALSE(testing::looks_like_crash(c.err)) << c.err;
}

}  // namespace
}  // namespace loom
