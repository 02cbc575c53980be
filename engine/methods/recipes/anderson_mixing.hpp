// Anderson mixing (Walker & Ni 2011, "Anderson acceleration for fixed-point iterations", type II) of the
// Newton increments of one step. With OSGS the tangent leaves out the derivative of the residual
// projections (seed 003 §5: they are data lagged by one iteration), so Newton is a fixed-point iteration
// x_k+1 = x_k + f_k, f_k = -K^-1 R(x_k), converging linearly. Anderson replaces f_k by
//   f_k - (dX + dF) gamma,   gamma = argmin |f_k - dF gamma|,
// where the columns of dX and dF are the last `depth` differences of the iterates and of the raw
// increments. The residual R, and so the converged solution, is unchanged; only the path is.
#pragma once

#include <Eigen/Dense>
#include <deque>

namespace loom {

class AndersonMixing {
 public:
  explicit AndersonMixing(int depth = 5) : depth_(depth) {}

  // The raw increment f_k of the current iterate; returns the increment to apply. `applied` is the
  // multiple of the previous returned increment that was added to the iterate (1 without line search).
  Eigen::VectorXd mix(const Eigen::VectorXd& f, double applied) {
    if (has_previous_ && f.size() == f_previous_.size()) {
      dF_.push_back(f - f_previous_);
      dX_.push_back(applied * previous_);
      if (int(dF_.size()) > depth_) dF_.pop_front(), dX_.pop_front();
    } else {
      dF_.clear(), dX_.clear();
    }
    f_previous_ = f;
    has_previous_ = true;
    previous_ = f;
    if (dF_.empty()) return previous_;
    const Eigen::Index n = f.size(), m = Eigen::Index(dF_.size());
    Eigen::MatrixXd F(n, m), X(n, m);
    for (Eigen::Index j = 0; j < m; ++j) F.col(j) = dF_[std::size_t(j)], X.col(j) = dX_[std::size_t(j)];
    const Eigen::VectorXd gamma = F.colPivHouseholderQr().solve(f);
    if (gamma.allFinite()) previous_ = f - (X + F) * gamma;
    return previous_;
  }

 private:
  int depth_;
  bool has_previous_ = false;
  Eigen::VectorXd f_previous_, previous_;
  std::deque<Eigen::VectorXd> dF_, dX_;
};

}  // namespace loom
