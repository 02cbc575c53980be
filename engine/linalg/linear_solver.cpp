#include "engine/linalg/linear_solver.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/UmfPackSupport>

#include "engine/core/errors.hpp"
#include "engine/linalg/bisected_cholesky.hpp"
#include "engine/linalg/cholmod_lower.hpp"
#include "engine/linalg/factor_preconditioned_gmres.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <vector>

namespace loom {
namespace {

// Eigen keeps UMFPACK's report protected: these expose the condition estimate.
template <class Matrix>
class UmfpackLUOf : public Eigen::UmfPackLU<Matrix> {
 public:
  // min |U_ii| / max |U_ii| of the scaled factorization (UMFPACK's Info[UMFPACK_RCOND]).
  double rcond() const { return this->m_umfpackInfo(UMFPACK_RCOND); }
  // The symbolic analysis's estimate of the numeric factorisation's peak memory, in 8-byte Units.
  double peak_memory_estimate() const { return this->m_umfpackInfo(UMFPACK_PEAK_MEMORY_ESTIMATE); }
  // Counted after a numeric factorisation (Info[UMFPACK_LNZ] > 0), estimated after the symbolic one.
  LinearSolver::FactorSize factor_size() const {
    const auto& info = this->m_umfpackInfo;
    if (info(UMFPACK_LNZ) > 0) return {info(UMFPACK_LNZ) + info(UMFPACK_UNZ), info(UMFPACK_FLOPS)};
    return {info(UMFPACK_LNZ_ESTIMATE) + info(UMFPACK_UNZ_ESTIMATE), info(UMFPACK_FLOPS_ESTIMATE)};
  }
};
using UmfpackLU = UmfpackLUOf<SparseMatrix>;
using WideMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, SuiteSparse_long>;
using WideUmfpackLU = UmfpackLUOf<WideMatrix>;

// Supernodal LL^T by CHOLMOD, the matrix stored as the lower triangle in the factor's order (cholmod_lower.hpp).
// The ordering is CHOLMOD's default choice for the matrix (AMD, or METIS where AMD fills much) with its weighted
// postorder, as when Eigen's wrapper handed CHOLMOD the upper triangle; the permuted matrix, analysed in natural
// order, then has the same elimination tree, column counts and supernodes, and its factorisation performs the same
// operations on the same numbers: the factor and every solve are the same bit for bit, without the transpose
// CHOLMOD made at every factorisation of a matrix given with its ordering (5 % of the MPM cantilever's step).
class CholmodSolver final : public LinearSolver {
 public:
  CholmodSolver() { cholmod_start(&c_), set_relaxed_supernodes(c_); }
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;
  ~CholmodSolver() override {
    release();
    cholmod_finish(&c_);
  }
  const char* name() const override { return "cholmod"; }
  void analyze(const SparseMatrix& A) override {
    release();
    const int n = int(A.rows());
    cholmod_sparse upper{};  // the pattern; stype 1: CHOLMOD reads the upper triangle only
    upper.nrow = upper.ncol = std::size_t(n), upper.nzmax = std::size_t(A.nonZeros());
    upper.p = const_cast<int*>(A.outerIndexPtr()), upper.i = const_cast<int*>(A.innerIndexPtr()), upper.x = nullptr;
    upper.stype = 1, upper.itype = CHOLMOD_INT, upper.xtype = CHOLMOD_PATTERN, upper.dtype = CHOLMOD_DOUBLE, upper.sorted = 1, upper.packed = 1;
    // CHOLMOD's default strategy; only its (postordered) permutation is read, so the simplicial analysis, which
    // skips the supernodal pattern that the analysis of the permuted matrix builds.
    c_.nmethods = 0, c_.postorder = 1, c_.supernodal = CHOLMOD_SIMPLICIAL;
    cholmod_factor* ordering = cholmod_analyze(&upper, &c_);
    c_.supernodal = CHOLMOD_SUPERNODAL;
    if (!ordering) throw std::runtime_error("cholmod: the fill-reducing ordering failed");
    const int* perm = static_cast<const int*>(ordering->Perm);
    order_.assign(perm, perm + n);
    cholmod_free_factor(&ordering, &c_);
    std::vector<int> position(static_cast<std::size_t>(n));
    for (int q = 0; q < n; ++q) position[std::size_t(order_[std::size_t(q)])] = q;
    build_permuted_lower(A, n, [&](int g) { return position[std::size_t(g)]; }, H_);
    c_.nmethods = 1, c_.method[0].ordering = CHOLMOD_NATURAL, c_.postorder = 0;
    cholmod_sparse view = H_.view(n, -1);
    L_ = cholmod_analyze(&view, &c_);
    if (!L_) throw std::runtime_error("cholmod: the symbolic analysis failed");
    if (n > 0) B_ = cholmod_allocate_dense(std::size_t(n), 1, std::size_t(n), CHOLMOD_REAL, &c_);
  }
  bool factorize(const SparseMatrix& A) override {
    H_.gather(A);
    cholmod_sparse view = H_.view(int(A.rows()), -1);
    cholmod_factorize(&view, L_, &c_);
    return c_.status >= CHOLMOD_OK && L_->minor == L_->n;  // minor < n: not positive definite
  }
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    const int n = int(order_.size());
    x.resize(n);
    if (n == 0) return true;  // no free dof (CHOLMOD allocates no empty dense matrix)
    double* y = static_cast<double*>(B_->x);
    for (int q = 0; q < n; ++q) y[q] = b[order_[std::size_t(q)]];
    if (!cholmod_solve2(CHOLMOD_A, L_, B_, nullptr, &X_, nullptr, &Y_, &E_, &c_)) return false;
    const double* z = static_cast<const double*>(X_->x);
    for (int q = 0; q < n; ++q) x[order_[std::size_t(q)]] = z[q];
    return true;
  }
  // (min diag L / max diag L)^2: CHOLMOD's own cheap estimate of 1 / cond(A).
  double rcond() override { return L_ ? cholmod_rcond(L_, &c_) : 0.0; }
  FactorSize factor_size() override { return {c_.lnz, c_.fl}; }

 private:
  void release() {
    cholmod_free_factor(&L_, &c_);
    for (cholmod_dense** d : {&B_, &X_, &Y_, &E_}) cholmod_free_dense(d, &c_);
  }

  cholmod_common c_{};
  std::vector<int> order_;  // the factor's q-th dof is the matrix's order_[q]
  CholmodCsc H_;
  cholmod_factor* L_ = nullptr;
  cholmod_dense *B_ = nullptr, *X_ = nullptr, *Y_ = nullptr, *E_ = nullptr;
};

// UMFPACK's int version (umfpack_di) addresses its workspace with int: it runs out of memory once the
// numeric factorisation needs more than 2^31 Units (16 GB of address space), which 3D systems reach from about
// 1e5 dofs (an elastic tet4 cube of 8.6e4 dofs: estimate 2.1e9 Units, factorisation fails; docs/solvers_3d.md).
// When the symbolic analysis estimates more than `wide_above` Units, the matrix is copied to 64-bit indices and
// factorised by umfpack_dl instead (same algorithm; the copy costs one pass over the values per factorisation).
// Ordering: UMFPACK's AMD, unless its factorisation would cost more than kMetisAboveFlops; then CHOLMOD's choice
// (AMD, or METIS's nested dissection where AMD fills much): on 3D meshes METIS cuts the flops 2.5x at 2.6e4 dofs.
// Small systems (every 2D scene) keep AMD and their results bit for bit.
class UmfpackSolver final : public LinearSolver {
 public:
  explicit UmfpackSolver(double wide_above) : wide_above_(wide_above) {
    // No iterative refinement: the default two refinement steps double the solve time (68 against 29 ms at
    // 1e5 cells, perf/README.md) for no change of the Newton residual; Newton corrects the rest.
    solver_.umfpackControl()(UMFPACK_IRSTEP) = 0;
    wide_solver_.umfpackControl()(UMFPACK_IRSTEP) = 0;
  }
  const char* name() const override { return "umfpack"; }
  static constexpr double kMetisAboveFlops = 1e10;
  void analyze(const SparseMatrix& A) override {
    const double amd = UMFPACK_ORDERING_AMD;
    solver_.umfpackControl()(UMFPACK_ORDERING) = wide_solver_.umfpackControl()(UMFPACK_ORDERING) = amd;
    wide_ = wide_above_ <= 0.0;
    if (!wide_) {
      solver_.analyzePattern(A);
      if (solver_.info() == Eigen::Success && solver_.factor_size().flops > kMetisAboveFlops) {
        solver_.umfpackControl()(UMFPACK_ORDERING) = wide_solver_.umfpackControl()(UMFPACK_ORDERING) = UMFPACK_ORDERING_CHOLMOD;
        solver_.analyzePattern(A);
      }
      wide_ = solver_.info() != Eigen::Success || solver_.peak_memory_estimate() > wide_above_;
    }
    if (!wide_) return;
    wide_matrix_ = A;
    wide_solver_.analyzePattern(wide_matrix_);
  }
  bool factorize(const SparseMatrix& A) override {
    if (!wide_) {
      solver_.factorize(A);
      return solver_.info() == Eigen::Success;
    }
    std::copy(A.valuePtr(), A.valuePtr() + A.nonZeros(), wide_matrix_.valuePtr());  // same pattern, same order
    wide_solver_.factorize(wide_matrix_);
    return wide_solver_.info() == Eigen::Success;
  }
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    x = wide_ ? Eigen::VectorXd(wide_solver_.solve(b)) : Eigen::VectorXd(solver_.solve(b));
    return (wide_ ? wide_solver_.info() : solver_.info()) == Eigen::Success;
  }
  double rcond() override { return wide_ ? wide_solver_.rcond() : solver_.rcond(); }
  FactorSize factor_size() override { return wide_ ? wide_solver_.factor_size() : solver_.factor_size(); }

 private:
  double wide_above_;
  bool wide_ = false;
  UmfpackLU solver_;
  WideMatrix wide_matrix_;
  WideUmfpackLU wide_solver_;
};

// Eigen's ConjugateGradient on the whole matrix (both triangles are stored) with the diagonal (Jacobi)
// preconditioner: for 3D systems beyond ~3e5 dofs, where CHOLMOD's factor outgrows memory. Measured on a linear
// elastic cube (docs/solvers_3d.md): 3e5 dofs in 4.8 s against CHOLMOD's 27 s on two threads (nu = 0.3; 18 s at
// nu = 0.49), and at 1e6 dofs CHOLMOD would need a 16 GB factor. Eigen's IncompleteCholesky halves the
// iterations but doubles the time: its triangular solves cost more than the iterations they save.
class ConjugateGradientSolver final : public LinearSolver {
 public:
  explicit ConjugateGradientSolver(double tolerance) { cg_.setTolerance(tolerance); }
  const char* name() const override { return "cg"; }
  void analyze(const SparseMatrix& A) override { cg_.analyzePattern(A); }
  bool factorize(const SparseMatrix& A) override {  // the preconditioner: 1 / diag(A)
    cg_.factorize(A);
    const Eigen::VectorXd diagonal = A.diagonal();
    return (diagonal.array() > 0.0).all();  // a positive definite matrix has a positive diagonal
  }
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    x = cg_.solve(b);
    return cg_.info() == Eigen::Success;
  }
  double rcond() override { return NAN; }
  bool estimates_condition() const override { return false; }

 private:
  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper, Eigen::DiagonalPreconditioner<double>> cg_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_cg_solver(double tolerance) { return std::make_unique<ConjugateGradientSolver>(tolerance); }
std::unique_ptr<LinearSolver> make_cholmod_solver() { return std::make_unique<CholmodSolver>(); }
std::unique_ptr<LinearSolver> make_umfpack_solver(double wide_above) { return std::make_unique<UmfpackSolver>(wide_above); }

namespace {

// The back-end of a kind; automatic starts with CHOLMOD.
std::unique_ptr<LinearSolver> make_backend(LinearSolverKind kind, double cg_tolerance, const std::string& options, bool reuse) {
  switch (kind) {
    case LinearSolverKind::petsc: return make_petsc_solver(cg_tolerance, options, reuse);
    case LinearSolverKind::umfpack: return make_umfpack_solver();
    case LinearSolverKind::cg: return make_cg_solver(cg_tolerance);
    case LinearSolverKind::cholmod_bisected: return make_bisected_cholmod_solver();
    case LinearSolverKind::cholmod:
    case LinearSolverKind::automatic: break;
  }
  return make_cholmod_solver();
}

}  // namespace

namespace {

using PetscFactory = LinearSolver* (*)(double, const char*, int);

// Opens the plugin once (RTLD_GLOBAL: Open MPI opens components of its own that need its symbols): its handle, or null
// with why not in `problem`.
void* petsc_plugin(std::string* problem) {
  static std::string why;
  static void* handle = [] () -> void* {
    const char* moved = std::getenv("LOOM_PETSC_PLUGIN");  // where the plugin is, if not where it was built
    const std::string path = moved ? moved : LOOM_PETSC_PLUGIN;
    if (path.empty()) {
      why = "this loom was built without PETSc (install Debian's libpetsc-real-dev and configure again; tools/setup.sh does)";
      return nullptr;
    }
    void* lib = dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL);
    if (!lib) {
      why = std::string("the PETSc plugin does not load: ") + dlerror();
      return nullptr;
    }
    auto interface = reinterpret_cast<int (*)()>(dlsym(lib, "loom_petsc_interface"));
    if (!dlsym(lib, "loom_make_petsc_solver") || !interface) why = path + " is not loom's PETSc plugin";
    else if (interface() != kLinearSolverInterface) why = path + " was built from another version of loom: build it again";
    return why.empty() ? lib : nullptr;
  }();
  if (problem) *problem = why;
  return handle;
}

PetscFactory petsc_factory(std::string* problem) {
  void* lib = petsc_plugin(problem);
  return lib ? reinterpret_cast<PetscFactory>(dlsym(lib, "loom_make_petsc_solver")) : nullptr;
}

int max_over_ranks(int value) {
  static auto reduce = reinterpret_cast<int (*)(int)>(dlsym(petsc_plugin(nullptr), "loom_petsc_max_over_ranks"));
  return reduce(value);
}

}  // namespace

std::string petsc_solver_problem() {
  std::string problem;
  petsc_factory(&problem);
  return problem;
}

int petsc_ranks() {
  void* lib = petsc_plugin(nullptr);
  auto ranks = lib ? reinterpret_cast<int (*)()>(dlsym(lib, "loom_petsc_ranks")) : nullptr;
  return ranks ? ranks() : 0;
}

MaxOverRanks petsc_max_over_ranks() { return petsc_ranks() > 0 ? &max_over_ranks : nullptr; }

std::unique_ptr<LinearSolver> make_petsc_solver(double tolerance, const std::string& options, bool reuse) {
  std::string problem;
  const PetscFactory factory = petsc_factory(&problem);
  LOOM_CHECK(factory != nullptr, InputError, "solver.linear = \"petsc\": " << problem);
  LinearSolver* solver = factory(tolerance, options.c_str(), reuse ? 1 : 0);
  if (!solver) throw std::runtime_error("solver.linear = \"petsc\": MPI or PETSc did not start (MPI_Init_thread or PetscInitialize failed)");
  return std::unique_ptr<LinearSolver>(solver);
}

LinearSolve::LinearSolve(LinearSolverKind kind, double cg_tolerance, bool reuse_factor, std::string backend_options)
    : kind_(kind), cg_tolerance_(cg_tolerance), backend_options_(std::move(backend_options)), reuse_requested_(reuse_factor),
      reuse_factor_(reuse_factor && kind != LinearSolverKind::cg && kind != LinearSolverKind::petsc),
      solver_(make_backend(kind, cg_tolerance, backend_options_, reuse_factor)) {}

LinearSolve::~LinearSolve() = default;

namespace {

// A back-end that failed because of the scene's options (petsc: one PETSc refused or never used) is bad input.
void refuse_bad_options(const LinearSolver& solver, const std::string& where) {
  LOOM_CHECK(solver.input_problem().empty(), InputError, where << ": error: solver.petsc_options: " << solver.input_problem());
}

}  // namespace

bool LinearSolve::analyze(const SparsePattern& pattern) {
  if (analysed_version_ == pattern.version) return false;
  solver_->analyze(pattern.matrix);
  analysed_version_ = pattern.version;
  have_factor_ = false;
  ++analyses_;
  return true;
}

bool LinearSolve::factorize(const SparsePattern& pattern) {
  pending_ = nullptr;
  if (reuse_factor_ && have_factor_ && !refactor_next_ && analysed_version_ == pattern.version) {
    pending_ = &pattern;
    return true;
  }
  return factorize_now(pattern);
}

bool LinearSolve::factorize_now(const SparsePattern& pattern) {
  refactor_next_ = false;
  have_factor_ = false;
  for (;;) {
    analyze(pattern);
    ++factorizations_;
    if (solver_->factorize(pattern.matrix)) {
      have_factor_ = true;
      if (!solver_->estimates_condition()) return true;
      const double rcond = solver_->rcond();
      min_rcond_ = std::min(min_rcond_, std::isfinite(rcond) ? rcond : 0.0);
      return true;
    }
    refuse_bad_options(*solver_, options_where_);
    if (kind_ != LinearSolverKind::automatic || std::string(solver_->name()) == "umfpack") {
      min_rcond_ = 0.0;
      const std::string name = solver_->name();
      failure_ = !solver_->failure_reason().empty() ? solver_->failure_reason()
                 : name == "umfpack" ? "the tangent matrix is singular (UMFPACK met a zero pivot)"
                 : name == "cg"    ? "the tangent matrix has a diagonal entry <= 0, so it is not positive definite (solver.linear = \"cg\" "
                                     "needs a positive definite matrix; \"umfpack\" takes any)"
                                   : "the tangent matrix is not positive definite, or singular (" + name +
                                         "; solver.linear = \"auto\" or \"umfpack\" take indefinite matrices)";
      return false;
    }
    // Not positive definite: the tangent is indefinite (instability, or a formulation without SPD
    // tangent); LU handles it from now on.
    solver_ = make_umfpack_solver();
    analysed_version_ = 0;
  }
}

bool LinearSolve::solve_deferred(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  ++reused_solves_;
  const GmresOutcome gmres = factor_preconditioned_gmres(pending_->matrix, *solver_, b, x, cg_tolerance_, kReuseIterations);
  gmres_iterations_ += gmres.iterations;
  if (!gmres.converged) {
    ++reuse_fallbacks_;
    return false;
  }
  pending_ = nullptr;
  refactor_next_ = gmres.iterations > kRefactorAbove;
  return true;
}

bool LinearSolve::factorize_deferred() {
  const SparsePattern& pattern = *pending_;
  pending_ = nullptr;
  return factorize_now(pattern);
}

bool LinearSolve::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (pending_) {
    if (solve_deferred(b, x)) return true;
    if (!factorize_deferred()) return false;
  }
  if (solver_->solve(b, x)) return true;
  refuse_bad_options(*solver_, options_where_);
  failure_ = !solver_->failure_reason().empty() ? solver_->failure_reason()
             : std::string(solver_->name()) == "cg"
                 ? "conjugate gradients did not reach solver.linear_tolerance within twice as many iterations as unknowns (the tangent "
                   "is not positive definite, or too ill-conditioned for a diagonal preconditioner; try \"umfpack\")"
                 : "the back-substitution failed";
  return false;
}

std::string LinearSolve::backend() const { return solver_->name(); }

void LinearSolve::use_backend(const std::string& name) {
  if (name == solver_->name()) return;
  LinearSolverKind kind = LinearSolverKind::cholmod;  // a back-end's name() is its kind's scene word
  for (auto k : {LinearSolverKind::umfpack, LinearSolverKind::cg, LinearSolverKind::cholmod_bisected, LinearSolverKind::petsc})
    if (name == linear_solver_key(k)) kind = k;
  solver_ = make_backend(kind, cg_tolerance_, backend_options_, reuse_requested_);
  analysed_version_ = 0;
  have_factor_ = false;
}

}  // namespace loom
