// solver.linear = "petsc" (engine/linalg/petsc_solver.cpp): PETSc's direct LU reproduces UMFPACK to round-off, its
// default Krylov + multigrid reproduces the direct solvers' runs to the linear tolerance (3D displacement, 2D and 3D
// mixed u-phi, the smoothed mixed u-p elements at finite strain, MPM's grid with mixed u-p), the multigrid's iterations barely grow under refinement, a Krylov solve
// that fails is a failed solve with PETSc's reason, and options PETSc never used are reported. One process for all
// of them (registered as one ctest, not one per case: PETSc and MPI start once, in about a second).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <vector>

#include "engine/core/errors.hpp"
#include "engine/linalg/linear_solver.hpp"
#include "engine/scene/scene_loader.hpp"
#include "tests/support/run_comparison.hpp"

namespace loom {
namespace {

// A 1D Laplacian + shift, n x n (SPD for shift > 0), or with an unsymmetric convection term.
SparsePattern banded(int n, double shift, double convection = 0.0) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 + shift);
    if (i + 1 < n) t.emplace_back(i, i + 1, -1.0 + convection), t.emplace_back(i + 1, i, -1.0 - convection);
  }
  SparsePattern p;
  p.matrix.resize(n, n);
  p.matrix.setFromTriplets(t.begin(), t.end());
  p.matrix.makeCompressed();
  p.version = 1;
  return p;
}

double relative_error(LinearSolve& s, const SparsePattern& p) {
  Eigen::VectorXd known(p.matrix.rows());
  for (Index i = 0; i < known.size(); ++i) known[i] = std::sin(0.3 * double(i)) + 0.1 * double(i % 3);
  const Eigen::VectorXd b = p.matrix * known;
  if (!s.factorize(p)) return INFINITY;
  Eigen::VectorXd x;
  if (!s.solve(b, x)) return INFINITY;
  return (x - known).norm() / known.norm();
}

TEST(PetscSolve, LuEqualsUmfpackToRoundOff) {
  for (double convection : {0.0, 0.4}) {
    const SparsePattern p = banded(200, 0.01, convection);
    LinearSolve petsc(LinearSolverKind::petsc, 1e-10, false, "-ksp_type preonly -pc_type lu");
    LinearSolve umfpack(LinearSolverKind::umfpack);
    EXPECT_LE(relative_error(petsc, p), 1e-12);
    EXPECT_LE(relative_error(umfpack, p), 1e-12);
  }
}

// PETSc's parallel direct solver (MUMPS), on one process or across the ranks of mpirun (petsc_solver_mpi_test).
TEST(PetscSolve, MumpsLuEqualsUmfpackToRoundOff) {
  for (double convection : {0.0, 0.4}) {
    const SparsePattern p = banded(200, 0.01, convection);
    LinearSolve petsc(LinearSolverKind::petsc, 1e-10, false, "-ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps");
    EXPECT_LE(relative_error(petsc, p), 1e-12);
  }
}

// The ranks the program was launched on: mpirun -n N (Open MPI says so in the environment), else one.
int launched_ranks() {
  const char* size = std::getenv("OMPI_COMM_WORLD_SIZE");
  return size ? std::atoi(size) : 1;
}

// Under `mpirun -n 2` (the ctest petsc_solver_mpi_test runs this program so) PETSc works across the launcher's ranks,
// each giving it its rows, and every rank gets the same solution back, bit for bit (the replicated stores go on from it).
TEST(PetscSolve, SolvesAcrossTheLaunchedRanksAndEveryRankGetsTheSameSolution) {
  EXPECT_EQ(petsc_ranks(), launched_ranks());
  const SparsePattern p = banded(301, 0.01, 0.4);
  LinearSolve s(LinearSolverKind::petsc, 1e-12);
  ASSERT_TRUE(s.factorize(p));
  Eigen::VectorXd x;
  ASSERT_TRUE(s.solve(Eigen::VectorXd::LinSpaced(301, 1.0, 2.0), x));
  std::uint64_t bits = 1469598103934665603ull;  // FNV-1a of the solution's bytes, folded to 31 bits
  for (Index i = 0; i < x.size(); ++i) {
    std::uint64_t word;
    std::memcpy(&word, &x[i], sizeof word);
    bits = (bits ^ word) * 1099511628211ull;
  }
  const int mine = int(bits & 0x7fffffff);
  const MaxOverRanks largest = petsc_max_over_ranks();
  ASSERT_NE(largest, nullptr);
  EXPECT_EQ(largest(mine), mine);    // no rank's is larger
  EXPECT_EQ(-largest(-mine), mine);  // nor smaller
}

TEST(PetscSolve, DefaultsReachTheLinearToleranceOnSymmetricAndUnsymmetricMatrices) {
  for (double convection : {0.0, 0.4}) {
    LinearSolve s(LinearSolverKind::petsc, 1e-12);
    EXPECT_LE(relative_error(s, banded(300, 0.01, convection)), 1e-8) << convection;
    EXPECT_GT(s.linear_iterations(), 0);
  }
}

TEST(PetscSolve, AKrylovSolveThatFailsIsAFailedSolveWithPetscsReason) {
  LinearSolve s(LinearSolverKind::petsc, 1e-12, false, "-pc_type none -ksp_max_it 3");
  EXPECT_EQ(relative_error(s, banded(300, 0.01)), INFINITY);
  EXPECT_NE(s.failure().find("DIVERGED_ITS after 3 iterations"), std::string::npos) << s.failure();
}

testing::ProbeTable probes_of(const std::string& scene_file, std::vector<std::string> sets, const std::string& linear, RunSummary* summary = nullptr) {
  sets.push_back("solver.linear=\"" + linear + "\"");
  const SceneSpec scene = load_scene(std::string(LOOM_SOURCE_DIR) + "/" + scene_file, sets);
  return testing::run_for_probes(scene, "petsc_" + linear, summary);
}

// 3D displacement elements (tet10 Cook's membrane at nu = 0.3): CG + GAMG with the rigid-body modes against CHOLMOD.
// (At the scene's nu = 0.4999 GAMG on the displacement-only tangent diverges: near incompressibility wants the mixed
// elements and their fieldsplit, below.)
TEST(PetscSolve, Fem3dCookMembraneAsCholmodToTheLinearTolerance) {
  RunSummary summary;
  const std::vector<std::string> sets = {"body[0].mesh.divisions=[8,8,1]", "material[0].nu=0.3"};
  const testing::ProbeTable petsc = probes_of("scenes/cooks_membrane_3d.toml", sets, "petsc", &summary);
  const testing::ProbeTable direct = probes_of("scenes/cooks_membrane_3d.toml", sets, "cholmod");
  EXPECT_LE(testing::probe_difference(petsc, direct), 1e-7);
  EXPECT_EQ(summary.linear_solver, "petsc");
  EXPECT_GT(summary.linear_iterations, 0);
}

// Mixed u-phi tetrahedra near incompressibility (the step-44 block, nu = 0.4999): the Schur-complement fieldsplit.
TEST(PetscSolve, MixedBlock3dAsUmfpackToTheLinearTolerance) {
  const std::vector<std::string> sets = {"body[0].mesh.divisions=[4,4,4]", "time.steps=3"};
  EXPECT_LE(testing::probe_difference(probes_of("scenes/block_3d.toml", sets, "petsc"), probes_of("scenes/block_3d.toml", sets, "umfpack")), 1e-7);
}

// The smoothed mixed elements at finite strain (es_up with Hencky on the homogeneous compression, 2D and 3D): their
// tangent is symmetric at the undeformed start and unsymmetric after it; the fieldsplit is configured once (setting
// its index sets again on the symmetry change crashed PETSc in MatCreateSubMatrix).
TEST(PetscSolve, SmoothedMixedElementsAtFiniteStrainAsUmfpack) {
  for (const char* scene : {"scenes/homogeneous_compression.toml", "scenes/homogeneous_compression_3d.toml"}) {
    const std::vector<std::string> sets = {"body[0].element=\"es_up\"", "body[0].alpha_stab=0.5", "material[0].model=\"hencky_perzyna\"",
                                           "time.steps=4"};
    RunSummary summary;
    const testing::ProbeTable petsc = probes_of(scene, sets, "petsc", &summary);
    EXPECT_TRUE(summary.completed) << scene << ": " << summary.failure;
    EXPECT_LE(testing::probe_difference(petsc, probes_of(scene, sets, "umfpack")), 1e-7) << scene;
  }
}

// 2D pfem, remeshed every step (the constrained block of Schewe et al.): its mixed p1p1_uphi triangles (fieldsplit) and
// tri6 with tied mid-nodes on the loaded boundary (decoupled rows in PETSc's matrix), each with UMFPACK's probes to the
// linear tolerance.
TEST(PetscSolve, PfemConstrainedBlockAsUmfpack) {
  for (const char* element : {"body[0].element=\"p1p1_uphi\"", "body[0].element=\"tri6\""}) {
    const std::vector<std::string> sets = {"time.steps=20", element};
    EXPECT_LE(testing::probe_difference(probes_of("scenes/constrained_block_pfem.toml", sets, "petsc"),
                               probes_of("scenes/constrained_block_pfem.toml", sets, "umfpack")),
              1e-7)
        << element;
  }
}

// The multigrid's iterations barely grow as the mesh is refined (CG + GAMG with the rigid-body modes; Jacobi-CG's
// double per halving of h, docs/solvers_3d.md): Cook's membrane in tet10 at nu = 0.3 from 1.9e3 to 1.4e4 dofs.
TEST(PetscSolve, MultigridIterationsBarelyGrowUnderRefinement) {
  std::vector<long long> iterations;
  for (const char* divisions : {"body[0].mesh.divisions=[8,8,1]", "body[0].mesh.divisions=[16,16,2]"}) {
    RunSummary summary;
    probes_of("scenes/cooks_membrane_3d.toml", {divisions, "material[0].nu=0.3"}, "petsc", &summary);
    EXPECT_EQ(summary.newton_iterations, 1);
    iterations.push_back(summary.linear_iterations);
  }
  EXPECT_LE(double(iterations[1]), 1.3 * double(iterations[0])) << iterations[0] << " -> " << iterations[1];
}

// MPM's grid: the 2D cantilever (displacement, CG + GAMG) and the 3D twisted column's mixed u-p system (FGMRES with the
// Schur-complement fieldsplit) against the direct solvers, step by step.
testing::ProbeTable mpm_probes_of(const std::string& scene_file, std::vector<std::string> sets, const std::string& linear) {
  sets.push_back("solver.linear=\"" + linear + "\"");
  const SceneSpec scene = load_scene(std::string(LOOM_SOURCE_DIR) + "/" + scene_file, sets);
  testing::TempDir dir("petsc_mpm_" + linear);
  if (scene.scene.dimension == 3) testing::make_mpm_run<3>(scene, dir.path())->run();
  else testing::make_mpm_run<2>(scene, dir.path())->run();
  return testing::read_probes(dir.file("probes.csv"));
}

TEST(PetscSolve, MpmCantileverAndMixedColumnAsTheDirectSolvers) {
  const std::vector<std::string> cantilever = {"time.steps=100"};
  EXPECT_LE(testing::probe_difference(mpm_probes_of("scenes/cantilever_mpm_grid_newmark.toml", cantilever, "petsc"),
                             mpm_probes_of("scenes/cantilever_mpm_grid_newmark.toml", cantilever, "cholmod")),
            1e-7);
  const std::vector<std::string> column = {"time.steps=4"};
  EXPECT_LE(testing::probe_difference(mpm_probes_of("scenes/column_twisting_mpm.toml", column, "petsc"),
                             mpm_probes_of("scenes/column_twisting_mpm.toml", column, "umfpack")),
            1e-7);
}

// The disk falling on a plate of particles (method mpm, quad9 grid) has grid cells with few particles: its symmetric
// tangent is so poorly conditioned that GAMG's smoothing is not positive definite and CG stops (DIVERGED_INDEFINITE_PC,
// step 18); the back-end then goes on with GMRES, and the run follows the direct solver's.
TEST(PetscSolve, AnIndefinitePreconditionerUnderCgFallsBackToGmres) {
  auto run = [](const std::string& linear, const std::string& dir) {
    return testing::run_loom({"run", std::string(LOOM_SOURCE_DIR) + "/scenes/bouncing_disk_mpm_plate.toml", "--out", dir, "--quiet", "--threads",
                              "1", "--set", "time.end=0.12", "--set", "time.steps=40", "--set", "solver.linear=\"" + linear + "\""});
  };
  testing::TempDir petsc("petsc_disk"), direct("direct_disk");
  ASSERT_EQ(run("petsc", petsc.path()).exit_code, 0);
  ASSERT_EQ(run("auto", direct.path()).exit_code, 0);
  const testing::ProbeTable a = testing::read_probes(petsc.file("probes.csv")), b = testing::read_probes(direct.file("probes.csv"));
  ASSERT_EQ(a.rows.size(), b.rows.size());
  for (const char* name : {"centre_y", "bottom", "kinetic", "potential"}) {
    const std::vector<double> x = a.column(name), y = b.column(name);
    for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(x[i], y[i], 1e-8 * (1.0 + std::abs(y[i]))) << name << " at row " << i;
  }
}

// solver.reuse_factor with petsc keeps the preconditioner across Newton iterations and steps: fewer set-ups than
// solves, the same answer to the linear tolerance.
TEST(PetscSolve, ReuseKeepsThePreconditionerAndTheAnswer) {
  const std::vector<std::string> sets = {"body[0].mesh.divisions=[4,4,4]", "time.steps=3"};
  std::vector<std::string> reusing = sets;
  reusing.push_back("solver.reuse_factor=true");
  RunSummary fresh, kept;
  const testing::ProbeTable a = probes_of("scenes/block_3d.toml", sets, "petsc", &fresh);
  const testing::ProbeTable b = probes_of("scenes/block_3d.toml", reusing, "petsc", &kept);
  EXPECT_LE(testing::probe_difference(a, b), 1e-7);
  EXPECT_EQ(fresh.preconditioner_set_ups, fresh.factorizations);
  EXPECT_LT(kept.preconditioner_set_ups, kept.factorizations / 2);
}

// A kept preconditioner that no longer serves (Jacobi of a matrix whose diagonal has since grown up to 1e4-fold, smoothly
// along the rows) is set up afresh within the same solve, which then converges: two set-ups, no failure.
TEST(PetscSolve, AKeptPreconditionerThatNoLongerServesIsSetUpAfreshWithinTheSolve) {
  LinearSolve s(LinearSolverKind::petsc, 1e-10, true, "-pc_type jacobi");
  SparsePattern p = banded(300, 1.0);
  EXPECT_LE(relative_error(s, p), 1e-8);
  EXPECT_EQ(s.preconditioner_set_ups(), 1);
  for (Index j = 0; j < p.matrix.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(p.matrix, j); it; ++it)
      if (it.row() == it.col()) it.valueRef() *= 1.0 + 1e4 * std::pow(double(it.row()) / 300.0, 2);
  EXPECT_LE(relative_error(s, p), 1e-8);
  EXPECT_EQ(s.preconditioner_set_ups(), 2);
}

// Bad input: options for a solver the scene does not use.
TEST(PetscSolve, OptionsWithoutPetscAreRefused) {
  const std::string file = std::string(LOOM_SOURCE_DIR) + "/scenes/cooks_membrane_3d.toml";
  EXPECT_THROW(load_scene(file, {"solver.petsc_options=\"-pc_type lu\""}), InputError);
  EXPECT_NO_THROW(load_scene(file, {"solver.linear=\"petsc\"", "solver.petsc_options=\"-pc_type lu\""}));
}

// loom run of a small, compressible Cook's membrane (tet10, 4 x 4 x 1) with solver.petsc_options = options.
testing::Command run_small_cook_with(const std::string& options) {
  testing::TempDir dir("petsc_options_run");
  return testing::run_loom({"run", std::string(LOOM_SOURCE_DIR) + "/scenes/cooks_membrane_3d.toml", "--out", dir.path(), "--quiet", "--set",
                            "body[0].mesh.divisions=[4,4,1]", "--set", "material[0].nu=0.3", "--set", "solver.linear=\"petsc\"", "--set",
                            "solver.petsc_options=\"" + options + "\""});
}

// A misspelt option is bad input: after the first solve (when PETSc has read every option of its solver) the run stops
// with exit 2 naming solver.petsc_options and the option. An option PETSc reads only at its end (-log_view) is not
// checked then.
TEST(PetscSolve, AnOptionPetscNeverUsedIsBadInput) {
  const testing::Command c = run_small_cook_with("-ksp_monitr -ksp_rtol 1e-11");
  EXPECT_EQ(c.exit_code, 2) << c.err;
  EXPECT_NE(c.err.find("solver.petsc_options: PETSc did not use -ksp_monitr ("), std::string::npos) << c.err;
  EXPECT_EQ(c.err.find("-ksp_rtol"), std::string::npos) << c.err;
}

// An option value PETSc refuses (a Krylov method it does not have) is bad input too, before any solve.
TEST(PetscSolve, AnOptionValuePetscRefusesIsBadInput) {
  const testing::Command c = run_small_cook_with("-ksp_type cgg");
  EXPECT_EQ(c.exit_code, 2) << c.err;
  EXPECT_NE(c.err.find("solver.petsc_options: PETSc refused the options"), std::string::npos) << c.err;
}

// A run stopped and restarted with petsc continues to the uninterrupted run's answer (to the linear tolerance: GAMG keeps
// the interpolation of a pattern's first set-up, which a restarted run builds from a later matrix).
TEST(PetscSolve, ARestartedRunEndsWhereTheUninterruptedOneDoes) {
  testing::TempDir stopped("petsc_restart"), whole("petsc_whole");
  const std::string scene = std::string(LOOM_SOURCE_DIR) + "/scenes/block_3d.toml";
  const std::vector<std::string> sets = {"--quiet", "--set", "solver.linear=\"petsc\"", "--set", "body[0].mesh.divisions=[4,4,4]",
                                         "--set", "time.steps=4"};
  auto with = [&](std::vector<std::string> args) {
    args.insert(args.end(), sets.begin(), sets.end());
    return testing::run_loom(args);
  };
  ASSERT_EQ(with({"run", scene, "--out", stopped.path(), "--stop-after", "2"}).exit_code, 0);
  ASSERT_EQ(with({"run", scene, "--restart", stopped.path()}).exit_code, 0);
  ASSERT_EQ(with({"run", scene, "--out", whole.path()}).exit_code, 0);
  const testing::ProbeTable a = testing::read_probes(stopped.file("probes.csv")), b = testing::read_probes(whole.file("probes.csv"));
  ASSERT_EQ(a.rows.size(), 5u);
  EXPECT_LE(testing::probe_difference(a, b), 1e-8);
}

// A plugin that does not load (moved, or a missing library) refuses the scene with exit 2, naming the key.
TEST(PetscSolve, APluginThatDoesNotLoadIsBadInputNamingTheKey) {
  testing::TempDir dir("petsc_missing_plugin");
  ::setenv("LOOM_PETSC_PLUGIN", "/nonexistent/libloom_petsc.so", 1);
  const testing::Command c = testing::run_loom({"run", std::string(LOOM_SOURCE_DIR) + "/scenes/cooks_membrane_3d.toml", "--out", dir.path(),
                                                "--quiet", "--set", "solver.linear=\"petsc\""});
  ::unsetenv("LOOM_PETSC_PLUGIN");
  EXPECT_EQ(c.exit_code, 2) << c.err;
  EXPECT_NE(c.err.find("solver.linear"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("the PETSc plugin does not load"), std::string::npos) << c.err;
}

}  // namespace
}  // namespace loom
