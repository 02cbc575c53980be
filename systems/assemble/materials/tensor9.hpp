// Fourth-order tensors of 3x3 kinematics stored as 9x9 matrices: A(3*i + j, 3*k + l) = A_ijkl, so that
// dP_ij = A_ijkl dF_kl is the matrix-vector product of A with the row-major flattening of dF.
#pragma once

#include <Eigen/Core>

#include "engine/core/types.hpp"

namespace loom {

using Mat9 = Eigen::Matrix<double, 9, 9>;

inline constexpr int ij(int i, int j) { return 3 * i + j; }

}  // namespace loom
