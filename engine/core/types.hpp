// Basic types shared by the whole engine.
// Index is 32-bit everywhere (DESIGN §2); geometry is templated on the dimension D (2 now, 3 later);
// kinematics are always 3x3 so that materials are written once (plane strain: F33 = 1).
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>  // determinant and inverse of the fixed-size kinematics
#include <cstdint>
#include <limits>

namespace loom {

using Index = std::int32_t;
inline constexpr Index kNoIndex = -1;

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;
using Vec2 = Vec<2>;
using Vec3 = Vec<3>;
using Vec4 = Vec<4>;
using Mat3 = Eigen::Matrix3d;
using Mat32 = Eigen::Matrix<double, 3, 2>;  // one row per corner of a linear triangle: shape gradients
using Mat42 = Eigen::Matrix<double, 4, 2>;  // one row per corner of a bilinear quadrilateral
using Mat43 = Eigen::Matrix<double, 4, 3>;  // one row per corner of a linear tetrahedron: shape gradients

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Embeds an in-plane vector into 3D (z = 0); used for output and plane-strain kinematics.
template <int D>
Vec3 to_vec3(const Vec<D>& v) {
  Vec3 r = Vec3::Zero();
  r.template head<D>() = v;
  return r;
}

}  // namespace loom
