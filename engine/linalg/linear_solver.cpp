#include "engine/linalg/linear_solver.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/UmfPackSupport>

#include "engine/linalg/bisected_cholesky.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>

namespace loom {
namespace {

// Eigen keeps the factor and UMFPACK's report protected: these expose the condition estimates.
// The upper triangle: for a fill-reducing permutation CHOLMOD then builds the permuted lower triangle with one
// transpose per factorisation instead of two (its "fastest option for factoring a permuted matrix"; the
// patterns are symmetric, so either triangle holds the matrix): 9 % of the numeric factorisation of the
// MPM cantilever at 10^4 particles (perf/compare/README.md).
class CholmodLLT : public Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Upper> {
 public:
  // (min diag L / max diag L)^2: CHOLMOD's own cheap estimate of 1 / cond(A).
  double rcond() { return this->m_cholmodFactor ? cholmod_rcond(this->m_cholmodFactor, &this->cholmod()) : 0.0; }
};
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

class CholmodSolver final : public LinearSolver {
 public:
  CholmodSolver() {
    cholmod_common& c = solver_.cholmod();
    c.print = 0;  // failures are reported by loom, not printed by CHOLMOD
    // Supernode amalgamation twice as relaxed as CHOLMOD's defaults (nrelax 4, 16, 48; zrelax 0.8, 0.1, 0.05):
    // the supernodes of 2D meshes are small, and larger ones with a few explicit zeros run the dense kernels
    // better. Numeric factorisation 13-21 % faster on the MPM cantilever (10^4-10^5 particles) and Cook's
    // membrane at 10^5 cells, unchanged on small meshes (perf/compare/README.md).
    c.nrelax[0] = 8, c.nrelax[1] = 32, c.nrelax[2] = 96;
    c.zrelax[0] = 0.8, c.zrelax[1] = 0.2, c.zrelax[2] = 0.1;
  }
  const char* name() const override { return "cholmod"; }
  void analyze(const SparseMatrix& A) override { solver_.analyzePattern(A); }
  bool factorize(const SparseMatrix& A) override {
    solver_.factorize(A);
    return solver_.info() == Eigen::Success;
  }
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    x = solver_.solve(b);
    return solver_.info() == Eigen::Success;
  }
  double rcond() override { return solver_.rcond(); }
  FactorSize factor_size() override { return {solver_.cholmod().lnz, solver_.cholmod().fl}; }

 private:
  CholmodLLT solver_;
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

LinearSolve::LinearSolve(LinearSolverKind kind, double cg_tolerance) : kind_(kind), cg_tolerance_(cg_tolerance) {
  solver_ = kind == LinearSolverKind::umfpack            ? make_umfpack_solver()
            : kind == LinearSolverKind::cg                 ? make_cg_solver(cg_tolerance)
            : kind == LinearSolverKind::cholmod_bisected   ? make_bisected_cholmod_solver()
                                                           : make_cholmod_solver();
}

LinearSolve::~LinearSolve() = default;

bool LinearSolve::analyze(const SparsePattern& pattern) {
  if (analysed_version_ == pattern.version) return false;
  solver_->analyze(pattern.matrix);
  analysed_version_ = pattern.version;
  ++analyses_;
  return true;
}

bool LinearSolve::factorize(const SparsePattern& pattern) {
  for (;;) {
    analyze(pattern);
    ++factorizations_;
    if (solver_->factorize(pattern.matrix)) {
      if (!solver_->estimates_condition()) return true;
      const double rcond = solver_->rcond();
      min_rcond_ = std::min(min_rcond_, std::isfinite(rcond) ? rcond : 0.0);
      return true;
    }
    if (kind_ != LinearSolverKind::automatic || std::string(solver_->name()) == "umfpack") {
      min_rcond_ = 0.0;
      const std::string name = solver_->name();
      failure_ = name == "umfpack" ? "the tangent matrix is singular (UMFPACK met a zero pivot)"
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

bool LinearSolve::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (solver_->solve(b, x)) return true;
  failure_ = std::string(solver_->name()) == "cg"
                 ? "conjugate gradients did not reach solver.linear_tolerance within twice as many iterations as unknowns (the tangent "
                   "is not positive definite, or too ill-conditioned for a diagonal preconditioner; try \"umfpack\")"
                 : "the back-substitution failed";
  return false;
}

std::string LinearSolve::backend() const { return solver_->name(); }

void LinearSolve::use_backend(const std::string& name) {
  if (name == solver_->name()) return;
  solver_ = name == "umfpack"            ? make_umfpack_solver()
            : name == "cg"               ? make_cg_solver(cg_tolerance_)
            : name == "cholmod_bisected" ? make_bisected_cholmod_solver()
                                         : make_cholmod_solver();
  analysed_version_ = 0;
}

}  // namespace loom
