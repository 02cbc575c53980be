#include "engine/linalg/factor_preconditioned_gmres.hpp"

#include <unsupported/Eigen/IterativeSolvers>

namespace loom {
namespace {

// Eigen's preconditioner concept around a LinearSolver that is already factorised: compute() does nothing.
class FactorPreconditioner {
 public:
  FactorPreconditioner() = default;
  template <class M>
  explicit FactorPreconditioner(const M&) {}
  void use(LinearSolver* factor) { factor_ = factor; }
  template <class M>
  FactorPreconditioner& analyzePattern(const M&) { return *this; }
  template <class M>
  FactorPreconditioner& factorize(const M&) { return *this; }
  template <class M>
  FactorPreconditioner& compute(const M&) { return *this; }
  template <class R>
  Eigen::VectorXd solve(const Eigen::MatrixBase<R>& b) const {
    const Eigen::VectorXd in = b;
    Eigen::VectorXd out;
    if (!factor_->solve(in, out)) out.setConstant(in.size(), NAN);  // GMRES then fails its residual test
    return out;
  }
  Eigen::ComputationInfo info() const { return Eigen::Success; }

 private:
  LinearSolver* factor_ = nullptr;
};

}  // namespace

GmresOutcome factor_preconditioned_gmres(const SparseMatrix& A, LinearSolver& factor, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                         double tolerance, int max_iterations) {
  Eigen::GMRES<SparseMatrix, FactorPreconditioner> gmres;
  gmres.preconditioner().use(&factor);
  gmres.compute(A);
  gmres.setMaxIterations(max_iterations);
  gmres.set_restart(max_iterations);
  // Eigen's GMRES is preconditioned from the left and stops at |M^-1 (b - A x)| <= tolerance |M^-1 b|. With M^-1 A =
  // I + E, E small, that is the error of x: |x - x*| <= tolerance |x*| (1 + O(|E|)), what a Newton increment needs. The
  // force residual |b - A x| is no test here: the stiff rows (a wall's penalty, the pressure's 1 / kappa scale) make
  // it 1e-8 to 1e-7 of |b| for an increment exact to 1e-10 (the channel flow's tangents).
  gmres.setTolerance(tolerance);
  x = gmres.solve(b);
  GmresOutcome out;
  out.iterations = int(gmres.iterations());
  out.converged = gmres.info() == Eigen::Success && x.allFinite();
  return out;
}

}  // namespace loom
