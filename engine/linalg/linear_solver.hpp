// Linear solver back-ends behind one interface (DESIGN §8: a distributed back-end must fit here later).
// The symbolic analysis is kept while the sparsity pattern is unchanged (SparsePattern::version).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "engine/linalg/dof_map.hpp"
#include "engine/linalg/sparse_pattern.hpp"

namespace loom {

enum class LinearSolverKind { automatic, cholmod, umfpack, cg, cholmod_bisected, petsc };

// The back-ends that take only symmetric positive definite matrices.
inline bool needs_spd(LinearSolverKind k) {
  return k == LinearSolverKind::cholmod || k == LinearSolverKind::cg || k == LinearSolverKind::cholmod_bisected;
}
inline const char* linear_solver_name(LinearSolverKind k) {
  switch (k) {
    case LinearSolverKind::automatic: return "auto (cholmod, umfpack if indefinite)";
    case LinearSolverKind::cholmod: return "cholmod";
    case LinearSolverKind::umfpack: return "umfpack";
    case LinearSolverKind::cg: return "cg (conjugate gradients, diagonal preconditioner)";
    case LinearSolverKind::cholmod_bisected: return "cholmod_bisected (two halves concurrently, Schur complement of the separator)";
    case LinearSolverKind::petsc: return "petsc (Krylov with algebraic multigrid, engine/linalg/petsc_solver.cpp)";
  }
  return "?";
}

// The scene's word for the kind (solver.linear).
inline const char* linear_solver_key(LinearSolverKind k) {
  switch (k) {
    case LinearSolverKind::automatic: return "auto";
    case LinearSolverKind::cholmod: return "cholmod";
    case LinearSolverKind::umfpack: return "umfpack";
    case LinearSolverKind::cg: return "cg";
    case LinearSolverKind::cholmod_bisected: return "cholmod_bisected";
    case LinearSolverKind::petsc: return "petsc";
  }
  return "?";
}

// What an iterative back-end needs to know of the equations beyond the matrix (the multigrid's near-null space and
// the fields of a mixed system): the dof numbering and the coordinates of the nodes (dim per node).
struct SolveStructure {
  int dim = 0;
  DofMap dofs;
  std::vector<double> coordinates;
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  virtual const char* name() const = 0;
  virtual void analyze(const SparseMatrix& A) = 0;      // symbolic
  virtual bool factorize(const SparseMatrix& A) = 0;    // numeric; false: singular / not SPD
  virtual bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) = 0;
  // The back-end's estimate of 1 / cond(A) from its pivots, after a successful factorize.
  virtual double rcond() = 0;
  // Non-zeros of the factor and flops of its numeric factorisation: CHOLMOD's prediction after analyze;
  // UMFPACK's estimate after analyze, its count after factorize. NaN where the back-end does not say.
  struct FactorSize {
    double entries = NAN, flops = NAN;
  };
  virtual FactorSize factor_size() { return {}; }
  // False for an iterative back-end: it has no pivots, and rcond() means nothing.
  virtual bool estimates_condition() const { return true; }
  // An iterative back-end that builds its preconditioner from the equations' structure says so; set_structure()
  // then comes before every analyze() of a new pattern.
  virtual bool wants_structure() const { return false; }
  virtual void set_structure(SolveStructure) {}
  // Why the last factorize() or solve() returned false, in the back-end's words ("" if it has none).
  virtual std::string failure_reason() const { return {}; }
  // Non-empty when a solve failed because of the scene (an option the back-end does not know): bad input, not a
  // failed Newton iteration.
  virtual std::string input_problem() const { return {}; }
  // Krylov iterations of all solves so far (0 for a direct back-end).
  virtual long long iterations() const { return 0; }
  // Preconditioner set-ups of an iterative back-end (fewer than factorize() calls when it keeps one).
  virtual long long preconditioner_set_ups() const { return 0; }
};

// Raised whenever LinearSolver or SolveStructure changes layout: the plugin and the program that opens it must agree.
inline constexpr int kLinearSolverInterface = 1;

// The PETSc back-end is a plugin (libloom_petsc.so, engine/linalg/petsc_solver.cpp) opened the first time a run asks
// for it, so that the processes that never do neither load PETSc's libraries nor start MPI. Empty if it can be
// opened, else why not (built without PETSc, or the plugin does not load).
std::string petsc_solver_problem();
// options: solver.petsc_options; tolerance: solver.linear_tolerance; reuse: solver.reuse_factor (keep the preconditioner
// while it serves: rebuilt when a solve needs more than twice the iterations of the first one after its set-up).
std::unique_ptr<LinearSolver> make_petsc_solver(double tolerance, const std::string& options, bool reuse = false);
// The ranks of MPI_COMM_WORLD as the plugin's MPI sees them (starting MPI and PETSc if need be), 0 if there is no
// plugin or it does not start: under `mpirun -n N` it must be N, else loom and mpirun are of different MPIs.
int petsc_ranks();
// The plugin's collective maximum over the ranks (for set_interrupt_agreement), null without a plugin that starts.
using MaxOverRanks = int (*)(int);
MaxOverRanks petsc_max_over_ranks();

std::unique_ptr<LinearSolver> make_cholmod_solver();  // supernodal LL^T, SPD only
// General sparse LU. Above `wide_above` Units (8 bytes) of estimated workspace it factorises with 64-bit indices
// (umfpack_dl: the int version fails beyond 2^31 Units); 0 always does (for tests).
inline constexpr double kUmfpackWideAbove = 5e8;
std::unique_ptr<LinearSolver> make_umfpack_solver(double wide_above = kUmfpackWideAbove);
// Conjugate gradients with the diagonal preconditioner, SPD only; each solve stops at
// |A x - b| <= tolerance |b| (solve() returns false if it does not get there in n iterations).
std::unique_ptr<LinearSolver> make_cg_solver(double tolerance);
inline constexpr double kDefaultCgTolerance = 1e-10;

// The solver a run uses: picks the back-end, redoes the symbolic analysis only when the pattern
// changes, and with `automatic` switches from CHOLMOD to UMFPACK for good the first time a matrix is
// not positive definite.
//
// With reuse_factor (solver.reuse_factor), a factorize() of a matrix whose pattern has a factorisation already
// (an earlier Newton iteration's or step's tangent) keeps that factorisation, and the next solve() runs GMRES on the
// new matrix preconditioned by it (from the left), to |M^-1 (A x - b)| <= tolerance |M^-1 b| (the cg tolerance; M the
// kept factorisation, so this bounds the relative error of x). Only when GMRES does not get
// there in kReuseIterations is the matrix factorised afresh and solved directly; after a GMRES solve that needed more
// than kRefactorAbove iterations the next factorize() factorises. The iterates then differ from the fresh
// factorisation's by the tolerance, not by round-off.
class LinearSolve {
 public:
  static constexpr int kReuseIterations = 20, kRefactorAbove = 8;
  // cg_tolerance: the relative residual each solve of kind cg, or each GMRES solve with reuse_factor, reaches
  // (unused by the direct back-ends otherwise).
  // backend_options: solver.petsc_options (kind petsc only). With kind petsc, reuse_factor keeps the preconditioner
  // in the back-end instead (make_petsc_solver).
  explicit LinearSolve(LinearSolverKind kind, double cg_tolerance = kDefaultCgTolerance, bool reuse_factor = false,
                       std::string backend_options = {});
  ~LinearSolve();
  // The symbolic analysis (fill-reducing ordering, elimination tree, supernodes) of pattern.matrix, if its
  // pattern is not the one analysed last; true if it ran.
  bool analyze(const SparsePattern& pattern);
  bool analysed(const SparsePattern& pattern) const { return analysed_version_ == pattern.version; }
  // Factorizes pattern.matrix (analysing it first if its pattern is new); false if it is singular.
  bool factorize(const SparsePattern& pattern);
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  // solve() in two parts, so that a caller can time the factorisation a failed GMRES solve falls back on as a
  // factorisation: deferred() is true after a factorize() that kept the earlier factorisation; solve_deferred()
  // then tries GMRES (true: x solves it), and after a failed try factorize_deferred() factorises the matrix afresh
  // (false: singular), after which solve() back-substitutes. After a false solve_deferred() the matrix is still the
  // deferred one: factorize_deferred() must come next (solve() does both in that order).
  bool deferred() const { return pending_ != nullptr; }
  bool solve_deferred(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  bool factorize_deferred();
  std::string backend() const;
  // A restarted run takes the back-end the run it continues had come to (automatic: UMFPACK once a
  // matrix was not positive definite), so that it factorizes as that run would have.
  void use_backend(const std::string& name);
  int analyses() const { return analyses_; }
  // Whether the back-end wants the structure of the equations (SolveStructure), and giving it: call before the
  // analysis of every new pattern (solve_linear_step and solve_grid_step do).
  bool wants_structure() const { return solver_->wants_structure(); }
  void set_structure(SolveStructure structure) { solver_->set_structure(std::move(structure)); }
  long long linear_iterations() const { return solver_->iterations(); }
  // Where the back-end's options come from (solver.petsc_options' file:line), for the error a bad option raises.
  void set_options_where(std::string where) { options_where_ = std::move(where); }
  long long preconditioner_set_ups() const { return solver_->preconditioner_set_ups(); }
  // Why the last factorize returned false.
  const std::string& failure() const { return failure_; }
  // The smallest pivot-based estimate of 1 / cond since reset_condition() (0 after a singular matrix; stays
  // infinite with cg, which has no pivots).
  // Below kNearlySingular the matrix is singular up to round-off: a solution exists only by accident of
  // the rounding, and any component in its near-null space is arbitrary.
  static constexpr double kNearlySingular = 1e-13;
  double min_rcond() const { return min_rcond_; }
  void reset_condition() { min_rcond_ = INFINITY; }
  int factorizations() const { return factorizations_; }
  // reuse_factor: the solves done by GMRES on a kept factorisation, their iterations, and the GMRES solves that
  // failed and were factorised afresh.
  int reused_solves() const { return reused_solves_; }
  int gmres_iterations() const { return gmres_iterations_; }
  int reuse_fallbacks() const { return reuse_fallbacks_; }

 private:
  bool factorize_now(const SparsePattern& pattern);
  bool factorize_matrix(const SparseMatrix& A);

  LinearSolverKind kind_;
  double cg_tolerance_;
  std::string backend_options_;
  std::string options_where_ = "the scene";
  bool reuse_requested_;  // solver.reuse_factor as the scene gave it (petsc: the back-end keeps its preconditioner)
  bool reuse_factor_;
  bool have_factor_ = false;     // solver_ holds a factorisation of a matrix of the analysed pattern
  bool refactor_next_ = false;   // the last GMRES solve was slow: factorise at the next factorize()
  const SparsePattern* pending_ = nullptr;  // reuse_factor: the system the next solve() solves by GMRES
  int reused_solves_ = 0, gmres_iterations_ = 0, reuse_fallbacks_ = 0;
  std::unique_ptr<LinearSolver> solver_;
  std::uint64_t analysed_version_ = 0;
  double min_rcond_ = INFINITY;
  std::string failure_;
  int analyses_ = 0, factorizations_ = 0;
};

}  // namespace loom
