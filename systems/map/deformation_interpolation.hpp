// Interpolation of deformation gradients for state transfer (seed 000 §3.2, eqs 19-23):
//  ISO0: the components of F, linearly (det F is not preserved);
//  ISO1: F = F_vol F_iso with F_vol = J^(1/3) I, F_iso = J^(-1/3) F; J^(1/3) and F_iso are interpolated
//        separately and recombined (isochoric states are preserved approximately);
//  ISO2: polar decomposition F = R U; log U (symmetric) and log R (skew) are interpolated, U is rebuilt by
//        spectral decomposition and R by the Rodrigues formula (eq 22-23): tr log U = ln det F is linear,
//        so isochoric states stay isochoric to round-off.
#pragma once

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "engine/core/types.hpp"
#include "systems/map/iso_mode.hpp"

namespace loom {

// log U and log R of F = R U (det F > 0).
struct PolarLog {
  Mat3 log_U = Mat3::Zero();
  Mat3 log_R = Mat3::Zero();
};

// Skew matrix of the rotation vector w: W v = w x v.
inline Mat3 skew(const Vec3& w) {
  Mat3 W;
  W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return W;
}

// Rodrigues: exp(W) = I + sin(t)/t W + (1 - cos t)/t^2 W^2, t = |w|.
inline Mat3 rotation_from_log(const Mat3& W) {
  const Vec3 w(W(2, 1), W(0, 2), W(1, 0));
  const double t = w.norm();
  if (t < 1e-12) return Mat3::Identity() + W + 0.5 * W * W;
  return Mat3::Identity() + std::sin(t) / t * W + (1.0 - std::cos(t)) / (t * t) * W * W;
}

// Inverse of Rodrigues for a proper rotation with angle below pi.
inline Mat3 log_of_rotation(const Mat3& R) {
  const double c = std::clamp(0.5 * (R.trace() - 1.0), -1.0, 1.0);
  const double t = std::acos(c);
  const Mat3 A = 0.5 * (R - R.transpose());
  if (t < 1e-8) return A;  // sin t / t -> 1
  return t / std::sin(t) * A;
}

inline PolarLog polar_log(const Mat3& F) {
  Eigen::SelfAdjointEigenSolver<Mat3> eig(F.transpose() * F);  // C = F^T F = U^2
  const Vec3 lambda2 = eig.eigenvalues();
  const Mat3& Q = eig.eigenvectors();
  PolarLog p;
  p.log_U = Q * (0.5 * lambda2.array().log()).matrix().asDiagonal() * Q.transpose();
  const Mat3 U_inv = Q * lambda2.array().rsqrt().matrix().asDiagonal() * Q.transpose();
  p.log_R = log_of_rotation(F * U_inv);
  return p;
}

inline Mat3 from_polar_log(const PolarLog& p) {
  Eigen::SelfAdjointEigenSolver<Mat3> eig(0.5 * (p.log_U + p.log_U.transpose()));
  const Mat3 U = eig.eigenvectors() * eig.eigenvalues().array().exp().matrix().asDiagonal() * eig.eigenvectors().transpose();
  return rotation_from_log(0.5 * (p.log_R - p.log_R.transpose())) * U;
}

// sum_k w[k] F[k] in the chosen representation; weights sum to one.
template <int N>
Mat3 interpolate_deformation(const Mat3* const (&F)[N], const double (&w)[N], IsoMode mode) {
  switch (mode) {
    case IsoMode::iso0: {
      Mat3 r = Mat3::Zero();
      for (int k = 0; k < N; ++k) r += w[k] * *F[k];
      return r;
    }
    case IsoMode::iso1: {
      double vol = 0.0;
      Mat3 iso = Mat3::Zero();
      for (int k = 0; k < N; ++k) {
        const double c = std::cbrt(F[k]->determinant());
        vol += w[k] * c;
        iso += w[k] * *F[k] / c;
      }
      return vol * iso;
    }
    case IsoMode::iso2: {
      PolarLog r;
      for (int k = 0; k < N; ++k) {
        const PolarLog p = polar_log(*F[k]);
        r.log_U += w[k] * p.log_U;
        r.log_R += w[k] * p.log_R;
      }
      return from_polar_log(r);
    }
  }
  return *F[0];
}

}  // namespace loom
