#include "engine/linalg/linear_solver.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>

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
class UmfpackLU : public Eigen::UmfPackLU<SparseMatrix> {
 public:
  // min |U_ii| / max |U_ii| of the scaled factorization (UMFPACK's Info[UMFPACK_RCOND]).
  double rcond() const { return this->m_umfpackInfo(UMFPACK_RCOND); }
};

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

 private:
  CholmodLLT solver_;
};

class UmfpackSolver final : public LinearSolver {
 public:
  // No iterative refinement: the default two refinement steps double the solve time (68 against 29 ms at
  // 1e5 cells, perf/README.md) for no change of the Newton residual; Newton corrects the rest.
  UmfpackSolver() { solver_.umfpackControl()(UMFPACK_IRSTEP) = 0; }
  const char* name() const override { return "umfpack"; }
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

 private:
  UmfpackLU solver_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_cholmod_solver() { return std::make_unique<CholmodSolver>(); }
std::unique_ptr<LinearSolver> make_umfpack_solver() { return std::make_unique<UmfpackSolver>(); }

LinearSolve::LinearSolve(LinearSolverKind kind) : kind_(kind) {
  solver_ = kind == LinearSolverKind::umfpack ? make_umfpack_solver() : make_cholmod_solver();
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
      const double rcond = solver_->rcond();
      min_rcond_ = std::min(min_rcond_, std::isfinite(rcond) ? rcond : 0.0);
      return true;
    }
    if (kind_ != LinearSolverKind::automatic || std::string(solver_->name()) == "umfpack") {
      min_rcond_ = 0.0;
      failure_ = std::string(solver_->name()) == "umfpack"
                     ? "the tangent matrix is singular (UMFPACK met a zero pivot)"
                     : "the tangent matrix is not positive definite, or singular (CHOLMOD; solver.linear = \"auto\" or \"umfpack\" "
                       "take indefinite matrices)";
      return false;
    }
    // Not positive definite: the tangent is indefinite (instability, or a formulation without SPD
    // tangent); LU handles it from now on.
    solver_ = make_umfpack_solver();
    analysed_version_ = 0;
  }
}

bool LinearSolve::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) { return solver_->solve(b, x); }

std::string LinearSolve::backend() const { return solver_->name(); }

void LinearSolve::use_backend(const std::string& name) {
  if (name == solver_->name()) return;
  solver_ = name == "umfpack" ? make_umfpack_solver() : make_cholmod_solver();
  analysed_version_ = 0;
}

}  // namespace loom
