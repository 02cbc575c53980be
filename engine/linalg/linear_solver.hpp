// Linear solver back-ends behind one interface (DESIGN §8: a distributed back-end must fit here later).
// The symbolic analysis is kept while the sparsity pattern is unchanged (SparsePattern::version).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

#include "engine/linalg/sparse_pattern.hpp"

namespace loom {

enum class LinearSolverKind { automatic, cholmod, umfpack };

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  virtual const char* name() const = 0;
  virtual void analyze(const SparseMatrix& A) = 0;      // symbolic
  virtual bool factorize(const SparseMatrix& A) = 0;    // numeric; false: singular / not SPD
  virtual bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) = 0;
  // The back-end's estimate of 1 / cond(A) from its pivots, after a successful factorize.
  virtual double rcond() = 0;
};

std::unique_ptr<LinearSolver> make_cholmod_solver();  // supernodal LL^T, SPD only
std::unique_ptr<LinearSolver> make_umfpack_solver();  // general sparse LU

// The solver a run uses: picks the back-end, redoes the symbolic analysis only when the pattern
// changes, and with `automatic` switches from CHOLMOD to UMFPACK for good the first time a matrix is
// not positive definite.
class LinearSolve {
 public:
  explicit LinearSolve(LinearSolverKind kind);
  ~LinearSolve();
  // The symbolic analysis (fill-reducing ordering, elimination tree, supernodes) of pattern.matrix, if its
  // pattern is not the one analysed last; true if it ran.
  bool analyze(const SparsePattern& pattern);
  bool analysed(const SparsePattern& pattern) const { return analysed_version_ == pattern.version; }
  // Factorizes pattern.matrix (analysing it first if its pattern is new); false if it is singular.
  bool factorize(const SparsePattern& pattern);
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  std::string backend() const;
  // A restarted run takes the back-end the run it continues had come to (automatic: UMFPACK once a
  // matrix was not positive definite), so that it factorizes as that run would have.
  void use_backend(const std::string& name);
  int analyses() const { return analyses_; }
  // Why the last factorize returned false.
  const std::string& failure() const { return failure_; }
  // The smallest pivot-based estimate of 1 / cond since reset_condition() (0 after a singular matrix).
  // Below kNearlySingular the matrix is singular up to round-off: a solution exists only by accident of
  // the rounding, and any component in its near-null space is arbitrary.
  static constexpr double kNearlySingular = 1e-13;
  double min_rcond() const { return min_rcond_; }
  void reset_condition() { min_rcond_ = INFINITY; }
  int factorizations() const { return factorizations_; }

 private:
  LinearSolverKind kind_;
  std::unique_ptr<LinearSolver> solver_;
  std::uint64_t analysed_version_ = 0;
  double min_rcond_ = INFINITY;
  std::string failure_;
  int analyses_ = 0, factorizations_ = 0;
};

}  // namespace loom
