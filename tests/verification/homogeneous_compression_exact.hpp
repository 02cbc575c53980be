// The exact state of the homogeneous plane-strain compression of a Neo-Hooke block (seed 000 eq 48) with
// rollers on the left and bottom, the top pushed down by d and the right edge free: stretches l2 = 1 - d / H
// and l1 from P11 = mu l1 + (lambda ln J - mu) / l1 = 0 (Newton), the top reaction per unit thickness
// P22 W and the right edge's displacement (l1 - 1) W. The derivation is in homogeneous_compression_test.cpp.
#pragma once

#include <cmath>

namespace loom::verification {

struct HomogeneousCompression {
  double l1 = 0, l2 = 0, reaction = 0, ux_right = 0;
  double p11 = 0;  // P11 at the solution: the free right edge's condition, ~0
};

inline HomogeneousCompression homogeneous_compression_exact(double E, double nu, double W, double H, double d) {
  const double mu = E / (2.0 * (1.0 + nu)), lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  HomogeneousCompression s;
  s.l2 = 1.0 - d / H;
  double l1 = 1.0;
  for (int it = 0; it < 50; ++it) {
    const double f = mu * l1 * l1 + lambda * std::log(l1 * s.l2) - mu;
    const double step = f / (2.0 * mu * l1 + lambda / l1);
    l1 -= step;
    if (std::abs(step) < 1e-16 * l1) break;
  }
  s.l1 = l1;
  const double J = l1 * s.l2;
  s.p11 = mu * l1 + (lambda * std::log(J) - mu) / l1;
  s.reaction = (mu * s.l2 + (lambda * std::log(J) - mu) / s.l2) * W;
  s.ux_right = (l1 - 1.0) * W;
  return s;
}

// 3D, the faces x = W and z = T free: F = diag(l, l2, l) (by symmetry the two lateral stretches are equal), l from
// P11 = mu l + (lambda ln(l^2 l2) - mu) / l = 0, i.e. f(l) = mu l^2 + lambda ln(l^2 l2) - mu = 0 with
// f'(l) = 2 mu l + 2 lambda / l > 0 (a unique root), the top reaction P22 W T, the lateral displacements (l - 1) W
// at x = W (ux_right) and (l - 1) T at z = T (l1 = l).
struct HomogeneousCompression3d {
  double l = 0, l2 = 0, reaction = 0, ux_right = 0, uz_front = 0, p11 = 0;
};

inline HomogeneousCompression3d homogeneous_compression_3d_exact(double E, double nu, double W, double H, double T, double d) {
  const double mu = E / (2.0 * (1.0 + nu)), lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  HomogeneousCompression3d s;
  s.l2 = 1.0 - d / H;
  double l = 1.0;
  for (int it = 0; it < 50; ++it) {
    const double step = (mu * l * l + lambda * std::log(l * l * s.l2) - mu) / (2.0 * mu * l + 2.0 * lambda / l);
    l -= step;
    if (std::abs(step) < 1e-16 * l) break;
  }
  s.l = l;
  const double J = l * l * s.l2;
  s.p11 = mu * l + (lambda * std::log(J) - mu) / l;
  s.reaction = (mu * s.l2 + (lambda * std::log(J) - mu) / s.l2) * W * T;
  s.ux_right = (l - 1.0) * W, s.uz_front = (l - 1.0) * T;
  return s;
}

}  // namespace loom::verification
