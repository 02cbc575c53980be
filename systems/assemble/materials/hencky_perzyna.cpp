// Hencky-Perzyna's return map, stresses and tangent: the equations are in the header's comment.
#include "systems/assemble/materials/hencky_perzyna.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

#include "systems/assemble/materials/first_piola.hpp"

namespace loom {

double HenckyPerzyna::energy(const Mat3& be) const {
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(be, Eigen::EigenvaluesOnly);
  const Vec3 eps = 0.5 * eig.eigenvalues().array().log().matrix();
  const double theta = eps.sum();
  return G * (eps - Vec3::Constant(theta / 3.0)).squaredNorm() + 0.5 * K * theta * theta;
}

Mat3 HenckyPerzyna::kirchhoff(const Mat3& be) const {
  HistoryResponse r;
  if (!elastic_update(Mat3::Identity(), be, false, r)) return Mat3::Constant(std::numeric_limits<double>::quiet_NaN());
  return r.tau;
}

bool HenckyPerzyna::update(const Mat3& f, const Mat3& be_n, double dt, bool deviatoric, bool tangent, HistoryResponse& out) const {
  const Mat3 be_tr = f * be_n * f.transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(be_tr);
  const Vec3 w = eig.eigenvalues();
  if (!(w.minCoeff() > 0.0) || !(f.determinant() > 0.0)) return false;
  const Mat3& n = eig.eigenvectors();
  Vec3 eps = 0.5 * w.array().log().matrix();
  const double theta = eps.sum();
  const Vec3 s = 2.0 * G * (eps - Vec3::Constant(theta / 3.0));
  const double q = std::sqrt(0.5 * s.squaredNorm());
  const Mat3 dev = Mat3::Identity() - Mat3::Constant(1.0 / 3.0);
  Vec3 t = s;
  Mat3 a = 2.0 * G * dev;
  if (friction) {
    if (deviatoric) return false;  // its yield function needs the pressure: the scene checks refuse mixed elements
    out.plastic = friction->return_map(K, G, eps, t, a, out.tau_eq);
  } else {
    out.plastic = q > tau0;
    out.tau_eq = q;
  }
  if (out.plastic && !friction) {
    const double H = G + viscosity / dt;
    const double dgamma = (q - tau0) / H;
    const double factor = 1.0 - G * dgamma / q;
    const Vec3 nh = s / (std::sqrt(2.0) * q);
    t = factor * s;
    a = 2.0 * G * factor * dev - 2.0 * G * (G * tau0 / (H * q)) * nh * nh.transpose();
    eps -= dgamma / (2.0 * q) * s;
    out.tau_eq = factor * q;
  }
  if (!deviatoric && !friction) t.array() += K * theta, a.array() += K;
  // Elastic: b^e is the trial state itself (rebuilding it from the spectral form would only add round-off,
  // and a body at rest would drift by it step after step).
  out.be = out.plastic ? Mat3(n * eps.array().exp().square().matrix().asDiagonal() * n.transpose()) : be_tr;
  out.tau = n * t.asDiagonal() * n.transpose();
  out.J = std::exp(theta);
  if (tangent) out.c_tau = spatial_tangent(n, w, t, a);
  return true;
}

bool HenckyPerzyna::stress(const Mat3& F, Mat3& P) const {
  HistoryResponse r;
  if (!elastic(F, false, r)) return false;
  P = r.tau * F.inverse().transpose();
  return true;
}

bool HenckyPerzyna::stress_tangent(const Mat3& F, Mat3& P, Mat9& A) const {
  HistoryResponse r;
  if (!elastic(F, true, r)) return false;
  first_piola(F, r.tau, r.c_tau, 1.0, P, A);
  return true;
}

bool HenckyPerzyna::elastic_update(const Mat3& f, const Mat3& be_n, bool tangent, HistoryResponse& r) const {
  HenckyPerzyna e = *this;
  e.tau0 = std::numeric_limits<double>::infinity();
  e.friction.reset();
  return e.update(f, be_n, 1.0, false, tangent, r);
}

Mat9 HenckyPerzyna::spatial_tangent(const Mat3& n, const Vec3& w, const Vec3& t, const Mat3& a) {
  // m[A][B] = vec(n_A (x) n_B), row-major, so that n_ABCD = m[A][B] m[C][D]^T.
  Eigen::Matrix<double, 9, 1> m[3][3];
  for (int A = 0; A < 3; ++A)
    for (int B = 0; B < 3; ++B) {
      const Mat3 nn = n.col(A) * n.col(B).transpose();
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m[A][B][ij(i, j)] = nn(i, j);
    }
  Mat9 c = Mat9::Zero();
  for (int A = 0; A < 3; ++A) {
    for (int B = 0; B < 3; ++B) c += a(A, B) * m[A][A] * m[B][B].transpose();
    c -= 2.0 * t[A] * m[A][A] * m[A][A].transpose();
    for (int B = 0; B < 3; ++B) {
      if (A == B) continue;
      // Below sqrt(eps) relative separation the quotient loses more digits than the limit's O(d) error.
      const double g = std::abs(w[A] - w[B]) > 1.5e-8 * w.maxCoeff() ? (t[A] * w[B] - t[B] * w[A]) / (w[A] - w[B])
                                                                      : 0.5 * (a(A, A) - a(A, B)) - t[A];
      c += g * (m[A][B] * m[A][B].transpose() + m[A][B] * m[B][A].transpose());
    }
  }
  return c;
}

}  // namespace loom
