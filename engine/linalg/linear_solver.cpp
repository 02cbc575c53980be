#include "engine/linalg/linear_solver.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>

#include <iostream>

namespace loom {
namespace {

class CholmodSolver final : public LinearSolver {
 public:
  CholmodSolver() { solver_.cholmod().print = 0; }  // failures are reported by loom, not printed by CHOLMOD
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

 private:
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> solver_;
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

 private:
  Eigen::UmfPackLU<SparseMatrix> solver_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_cholmod_solver() { return std::make_unique<CholmodSolver>(); }
std::unique_ptr<LinearSolver> make_umfpack_solver() { return std::make_unique<UmfpackSolver>(); }

LinearSolve::LinearSolve(LinearSolverKind kind) : kind_(kind) {
  solver_ = kind == LinearSolverKind::umfpack ? make_umfpack_solver() : make_cholmod_solver();
}

LinearSolve::~LinearSolve() = default;

bool LinearSolve::factorize(const SparsePattern& pattern) {
  for (;;) {
    if (analysed_version_ != pattern.version) {
      solver_->analyze(pattern.matrix);
      analysed_version_ = pattern.version;
      ++analyses_;
    }
    ++factorizations_;
    if (solver_->factorize(pattern.matrix)) return true;
    if (kind_ != LinearSolverKind::automatic || std::string(solver_->name()) == "umfpack") return false;
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
