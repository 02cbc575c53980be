// solver.linear = "petsc": Krylov solvers with algebraic multigrid from PETSc, on one process or on the ranks of
// `mpirun -n N loom run` (petsc_system.hpp: each rank gives PETSc its own rows of the replicated system).
//
// Built as a plugin (libloom_petsc.so) that linear_solver.cpp opens the first time a scene asks for it, so that a loom
// process that does not use PETSc neither loads its ~100 shared libraries nor starts MPI. The plugin is self-contained:
// it uses loom's headers only (LinearSolver is all inline) and exports one C function, loom_make_petsc_solver.
//
// The matrix PETSc sees is whole nodes, not loom's free equations (whole_node_layout.hpp): the eliminated dofs are
// decoupled rows with a scaled identity and a zero right-hand side. The block size is then the dofs per node, which the
// smoothed-aggregation multigrid (GAMG) needs with its near-null space (the rigid-body modes of the nodes'
// coordinates), and a mixed u-p system splits into its fields by stride.
// Defaults (docs/petsc.md): CG + GAMG for symmetric displacement tangents, GMRES + GAMG for unsymmetric ones, FGMRES with
// a lower Schur-complement fieldsplit (GAMG on u, Jacobi on selfp) for mixed ones; solver.petsc_options overrides them.
#include <mpi.h>
#include <petscksp.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "engine/linalg/linear_solver.hpp"
#include "engine/linalg/petsc_system.hpp"

namespace loom {
namespace {

static_assert(sizeof(PetscInt) == sizeof(int), "whole_node_layout numbers rows with int, as Debian's PETSc does");

bool petsc_finalised = false;
bool mpi_started_here = false;

// MPI with MPI_THREAD_SERIALIZED (loom calls PETSc from whichever oneTBB worker runs the solve node, one at a time),
// then PETSc without its signal handlers (loom's own report a crash); both finalised at exit.
bool start_petsc() {
  static bool started = false;
  static std::once_flag once;
  std::call_once(once, [] {
    int ready = 0;
    MPI_Initialized(&ready);
    if (!ready) {
      int provided = 0;
      if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS || provided < MPI_THREAD_SERIALIZED) return;
      mpi_started_here = true;
    }
    static char program[] = "loom", no_signals[] = "-no_signal_handler";
    static char* arguments[] = {program, no_signals, nullptr};
    int count = 2;
    char** argv = arguments;
    if (PetscInitialize(&count, &argv, nullptr, nullptr) != 0) return;
    PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);  // errors come back as codes, never abort
    // At exit, on the thread that calls exit(): loom's main thread, the one that constructed the solver and so
    // initialised MPI (the solves run on oneTBB workers, one at a time: MPI_THREAD_SERIALIZED).
    std::atexit([] {
      petsc_finalised = true;
      PetscFinalize();
      int finalised = 0;
      MPI_Finalized(&finalised);
      if (!finalised && mpi_started_here) MPI_Finalize();
    });
    started = true;
  });
  return started;
}

// The option names a user wrote ("-ksp_type cg -pc_type gamg" -> -ksp_type, -pc_type).
std::vector<std::string> option_names(const std::string& options) {
  std::vector<std::string> names;
  std::istringstream in(options);
  for (std::string word; in >> word;)
    if (word.size() > 1 && word[0] == '-' && !std::isdigit(static_cast<unsigned char>(word[1])) && word[1] != '.') names.push_back(word);
  return names;
}

class PetscSolver final : public LinearSolver {
 public:
  // reuse (solver.reuse_factor): keep the preconditioner across new matrices of the same pattern, rebuilt only when a
  // solve needs more than kRebuildAbove times the iterations of the first solve after the last set-up.
  static constexpr double kRebuildAbove = 2.0;
  PetscSolver(double tolerance, std::string options, bool reuse)
      : tolerance_(tolerance), user_options_(std::move(options)), reuse_(reuse) {}
  ~PetscSolver() override {
    if (petsc_finalised) return;
    report_unused_options();
    destroy();
  }
  const char* name() const override { return "petsc"; }
  bool wants_structure() const override { return true; }
  void set_structure(SolveStructure s) override { structure_ = std::move(s); }
  bool estimates_condition() const override { return false; }
  double rcond() override { return NAN; }
  std::string failure_reason() const override { return failure_; }
  std::string input_problem() const override { return input_problem_; }
  long long iterations() const override { return iterations_; }
  long long preconditioner_set_ups() const override { return set_ups_; }

  void analyze(const SparseMatrix& A) override {
    failure_.clear();
    try {
      destroy();
      system_.build(A, structure_);
      build_near_null_space();
      LOOM_PETSC_CALL(KSPCreate(PetscSystem::communicator(), &ksp_));
      configured_ = set_up_ = rebuild_next_ = false;
    } catch (const PetscFailure& f) {
      failure_ = "PETSc could not set up the linear solver: " + f.what;
    }
  }

  bool factorize(const SparseMatrix& A) override {
    if (ksp_ == nullptr) {
      if (failure_.empty()) failure_ = "PETSc's solver was not set up (no analysis of the pattern)";
      return false;
    }
    failure_.clear();
    const bool symmetric = is_symmetric(A, system_.layout().transpose, 1e-12);
    // A mixed system's options do not depend on symmetry, and its fieldsplit must be given its index sets once: a
    // finite-strain u-p tangent is symmetric at the undeformed start and not after it (configuring twice crashed PETSc).
    if (!configured_ || (symmetric != symmetric_ && !mixed())) {
      try {
        configure(symmetric);
      } catch (const PetscFailure& f) {  // an option PETSc refuses (-ksp_type cgg): the scene's fault
        input_problem_ = "PETSc refused the options (" + f.what + ")";
        failure_ = input_problem_;
        return false;
      }
    }
    try {
      copy_values(A);
      kept_now_ = reuse_ && set_up_ && !rebuild_next_;
      if (kept_now_) {  // the new matrix is the operator; the preconditioner stays
        LOOM_PETSC_CALL(KSPSetReusePreconditioner(ksp_, PETSC_TRUE));
        LOOM_PETSC_CALL(KSPSetOperators(ksp_, system_.matrix(), system_.matrix()));
      } else if (reuse_ && rebuild_next_) {
        rebuild();  // the kept one served badly: a new hierarchy, aggregates and all
      } else {
        LOOM_PETSC_CALL(set_up_afresh());  // the preconditioner's set-up: timed as the factorisation
      }
      set_up_ = true;
      rebuild_next_ = false;
      return true;
    } catch (const PetscFailure& f) {
      failure_ = "PETSc could not set up the preconditioner (" + f.what + "); solver.petsc_options can choose another";
      return false;
    }
  }

  // With a kept preconditioner the solve may take at most kKeptIterationCap times the iterations of the first solve
  // after the set-up (and at least kKeptIterationFloor); if it does not converge in them, the preconditioner is set up
  // afresh for this matrix and the solve repeated, so that a stale preconditioner costs a bounded number of
  // iterations and never fails a Newton iteration the fresh one would have solved.
  static constexpr PetscInt kKeptIterationCap = 3, kKeptIterationFloor = 30;

  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    if (ksp_ == nullptr || !set_up_) {
      failure_ = "PETSc's solver has no preconditioner set up (no successful factorisation)";
      return false;
    }
    failure_.clear();
    try {
      system_.set_rhs(b);
      KSPConvergedReason reason = krylov_solve(kept_now_ ? std::max(kKeptIterationFloor, kKeptIterationCap * iterations_after_set_up_) : 0);
      if (reason < 0 && kept_now_) {
        kept_now_ = false;
        rebuild();
        reason = krylov_solve(0);
        rebuild_next_ = false;
      }
      kept_now_ = false;
      if (indefinite(reason) && !mixed() && symmetric_ && !cg_refused_) {
        // CG met a preconditioner (or matrix) that is not positive definite, as GAMG's Chebyshev smoothing can be on a
        // symmetric but poorly conditioned tangent (MPM cells with few particles): GMRES needs no definiteness, so the
        // run goes on with it.
        cg_refused_ = true;
        rebuild();
        reason = krylov_solve(0);
      }
      if (!checked_options_) {
        checked_options_ = true;
        input_problem_ = unused_options(false);
        if (!input_problem_.empty()) return false;
      }
      if (reason < 0) {
        rebuild_next_ = true;
        failure_ = describe_failure(b.norm());
        return false;
      }
      system_.get_solution(x, b.size());
      return true;
    } catch (const PetscFailure& f) {
      failure_ = "PETSc's Krylov solve failed: " + f.what;
      return false;
    }
  }

 private:
  static bool indefinite(KSPConvergedReason reason) {
    return reason == KSP_DIVERGED_INDEFINITE_PC || reason == KSP_DIVERGED_INDEFINITE_MAT;
  }

  // KSPSolve from zero within `cap` iterations (0: the configured limit); counts the iterations and, after a set-up,
  // remembers the first solve's count.
  KSPConvergedReason krylov_solve(PetscInt cap) {
    LOOM_PETSC_CALL(KSPSetTolerances(ksp_, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, cap > 0 ? std::min(cap, max_iterations_) : max_iterations_));
    LOOM_PETSC_CALL(VecSet(system_.solution(), 0.0));
    LOOM_PETSC_CALL(KSPSolve(ksp_, system_.rhs(), system_.solution()));
    KSPConvergedReason reason;
    PetscInt its = 0;
    LOOM_PETSC_CALL(KSPGetConvergedReason(ksp_, &reason));
    LOOM_PETSC_CALL(KSPGetIterationNumber(ksp_, &its));
    iterations_ += its;
    if (iterations_after_set_up_ < 0) iterations_after_set_up_ = its;
    else if (double(its) > kRebuildAbove * double(std::max<PetscInt>(iterations_after_set_up_, 5))) rebuild_next_ = true;
    return reason;
  }

  // (The matrix is touched so that PCSetUp cannot take an unchanged matrix for a set-up already done.)
  PetscErrorCode set_up_afresh() {
    system_.touch();
    PetscCall(KSPSetReusePreconditioner(ksp_, PETSC_FALSE));
    PetscCall(KSPSetOperators(ksp_, system_.matrix(), system_.matrix()));
    PetscCall(KSPSetUp(ksp_));
    set_ups_ += 1, iterations_after_set_up_ = -1;
    return 0;
  }

  // A new KSP (configured as before) set up on the current matrix: GAMG keeps its interpolation across set-ups of one
  // KSP (-pc_gamg_reuse_interpolation), so a preconditioner that no longer serves is rebuilt from scratch.
  void rebuild() {
    LOOM_PETSC_CALL(KSPDestroy(&ksp_));
    LOOM_PETSC_CALL(KSPCreate(PetscSystem::communicator(), &ksp_));
    configure(symmetric_);
    LOOM_PETSC_CALL(set_up_afresh());
  }

  std::string describe_failure(double rhs_norm) const {
    const char* text = "?";
    KSPGetConvergedReasonString(ksp_, &text);
    PetscInt its = 0;
    KSPGetIterationNumber(ksp_, &its);
    PetscReal residual = NAN;
    KSPGetResidualNorm(ksp_, &residual);
    std::ostringstream os;
    os << "PETSc's Krylov solve did not converge (" << text << " after " << its << " iterations, residual norm " << residual
       << " against |b| = " << rhs_norm << ", solver.linear_tolerance " << tolerance_
       << "); solver.petsc_options can choose another Krylov method or preconditioner";
    return os.str();
  }

  // The rigid-body modes of the displacement dofs (GAMG's near-null space): on the matrix for a displacement system,
  // on the u field's index set for a mixed one (PCFIELDSPLIT hands it to the split's GAMG).
  void build_near_null_space() {
    if (!system_.layout().whole_nodes) return;
    const int dim = structure_.dim, per_node = structure_.dofs.per_node;
    if (structure_.coordinates.size() < std::size_t(structure_.dofs.n_nodes()) * std::size_t(dim)) return;
    if (per_node != dim && per_node != dim + 1) return;
    ::Vec coords = system_.node_coordinates(structure_);
    MatNullSpace modes;
    LOOM_PETSC_CALL(MatNullSpaceCreateRigidBody(coords, &modes));
    LOOM_PETSC_CALL(VecDestroy(&coords));
    if (per_node == dim) {
      LOOM_PETSC_CALL(MatSetNearNullSpace(system_.matrix(), modes));
    } else {
      system_.field_sets(dim, &u_field_, &p_field_);
      LOOM_PETSC_CALL(PetscObjectCompose(reinterpret_cast<PetscObject>(u_field_), "nearnullspace", reinterpret_cast<PetscObject>(modes)));
    }
    LOOM_PETSC_CALL(MatNullSpaceDestroy(&modes));
  }

  bool mixed() const { return u_field_ != nullptr; }

  std::string default_options(bool symmetric) const {
    std::ostringstream os;
    os.precision(17);
    os << "-ksp_rtol " << tolerance_ << " -ksp_max_it 2000 ";
    const char* gamg = "-pc_gamg_agg_nsmooths 1 -pc_gamg_reuse_interpolation true ";
    if (mixed())
      os << "-ksp_type fgmres -ksp_gmres_restart 200 -pc_type fieldsplit -pc_fieldsplit_type schur -pc_fieldsplit_schur_fact_type lower "
            "-pc_fieldsplit_schur_precondition selfp -fieldsplit_u_ksp_type preonly -fieldsplit_u_pc_type gamg -fieldsplit_u_"
         << gamg << "-fieldsplit_p_ksp_type preonly -fieldsplit_p_pc_type jacobi";
    else if (symmetric)
      os << "-ksp_type cg -ksp_norm_type unpreconditioned -pc_type gamg " << gamg;
    else
      os << "-ksp_type gmres -ksp_pc_side right -ksp_gmres_restart 200 -pc_type gamg " << gamg;
    return os.str();
  }

  // The options database holds loom's defaults, then PETSC_OPTIONS, then solver.petsc_options (the later win); it is
  // cleared first so that a second run in one process does not inherit the first's options.
  void configure(bool symmetric) {
    symmetric_ = symmetric;
    LOOM_PETSC_CALL(PetscOptionsClear(nullptr));
    LOOM_PETSC_CALL(PetscOptionsInsertString(nullptr, default_options(symmetric && !cg_refused_).c_str()));
    if (const char* env = std::getenv("PETSC_OPTIONS")) LOOM_PETSC_CALL(PetscOptionsInsertString(nullptr, env));
    LOOM_PETSC_CALL(PetscOptionsInsertString(nullptr, user_options_.c_str()));
    LOOM_PETSC_CALL(KSPSetFromOptions(ksp_));
    LOOM_PETSC_CALL(KSPGetTolerances(ksp_, nullptr, nullptr, nullptr, &max_iterations_));
    if (mixed()) {
      PC pc;
      LOOM_PETSC_CALL(KSPGetPC(ksp_, &pc));
      LOOM_PETSC_CALL(PCFieldSplitSetIS(pc, "u", u_field_));
      LOOM_PETSC_CALL(PCFieldSplitSetIS(pc, "p", p_field_));
    }
    configured_ = true;
  }

  // The decoupled rows' diagonal is the mean free diagonal, so that they do not spoil the scaling.
  void copy_values(const SparseMatrix& A) {
    const double scale = A.rows() > 0 ? A.diagonal().cwiseAbs().mean() : 1.0;
    system_.set_values(A, scale > 0.0 ? scale : 1.0);
  }

  // Of the user's options, those the options database still holds unused (PetscOptionsLeftGet names them without the
  // dash): after the first solve every option of the solver has been read, so an unused one is misspelt or not for
  // this solver. Options PETSc reads only at its end (-log_view and the like) are left to the end of the run
  // (at_end), and then only reported.
  static bool read_at_end(const std::string& name) {
    for (const char* prefix : {"-log", "-info", "-malloc", "-memory", "-objects", "-options", "-help"})
      if (name.rfind(prefix, 0) == 0) return true;
    return false;
  }
  std::string unused_options(bool at_end) const {
    PetscInt count = 0;
    char** names = nullptr;
    char** values = nullptr;
    if (PetscOptionsLeftGet(nullptr, &count, &names, &values) != 0) return {};
    std::string unused;
    for (const std::string& name : option_names(user_options_)) {
      if (read_at_end(name) != at_end) continue;
      for (PetscInt i = 0; i < count; ++i)
        if (name.substr(1) == names[i]) {
          unused += (unused.empty() ? "" : ", ") + name;
          break;
        }
    }
    PetscOptionsLeftRestore(nullptr, &count, &names, &values);
    if (unused.empty()) return {};
    return "PETSc did not use " + unused + " (misspelt, or not an option of the solver this scene runs: " +
           (mixed() ? "FGMRES with a fieldsplit named u and p" : symmetric_ ? "CG with GAMG" : "GMRES with GAMG") + " by default)";
  }
  void report_unused_options() const {
    const std::string unused = unused_options(true);
    if (!unused.empty()) std::cerr << "warning: solver.petsc_options: " << unused << "\n";
  }

  void destroy() {
    if (ksp_) KSPDestroy(&ksp_);
    system_.destroy();
    if (u_field_) ISDestroy(&u_field_);
    if (p_field_) ISDestroy(&p_field_);
  }

  double tolerance_;
  std::string user_options_;
  SolveStructure structure_;
  bool reuse_;
  PetscSystem system_;
  bool configured_ = false, symmetric_ = false;
  bool set_up_ = false, rebuild_next_ = false;  // reuse: a preconditioner exists; rebuild it at the next factorize
  bool kept_now_ = false;                       // the next solve runs on a kept preconditioner
  bool cg_refused_ = false;                     // CG met an indefinite preconditioner: GMRES from then on
  PetscInt max_iterations_ = 2000;              // the configured -ksp_max_it
  PetscInt iterations_after_set_up_ = -1;
  long long set_ups_ = 0;
  KSP ksp_ = nullptr;
  IS u_field_ = nullptr, p_field_ = nullptr;
  long long iterations_ = 0;
  std::string failure_, input_problem_;
  bool checked_options_ = false;  // the user's options were checked after the first solve
};

}  // namespace
}  // namespace loom

extern "C" __attribute__((visibility("default"))) int loom_petsc_interface() { return loom::kLinearSolverInterface; }

// The ranks PETSc runs on (MPI_COMM_WORLD), starting it if need be; 0 if MPI or PETSc does not start.
extern "C" __attribute__((visibility("default"))) int loom_petsc_ranks() { return loom::start_petsc() ? loom::PetscSystem::ranks() : 0; }

// The largest of every rank's value (collective: every rank calls it at the same point of the run).
extern "C" __attribute__((visibility("default"))) int loom_petsc_max_over_ranks(int value) {
  int largest = value;
  MPI_Allreduce(&value, &largest, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  return largest;
}

// Null if MPI or PETSc does not start.
extern "C" __attribute__((visibility("default"))) loom::LinearSolver* loom_make_petsc_solver(double tolerance, const char* options, int reuse) {
  if (!loom::start_petsc()) return nullptr;
  return new loom::PetscSolver(tolerance, options ? options : "", reuse != 0);
}
