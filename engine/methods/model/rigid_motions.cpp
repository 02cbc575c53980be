#include "engine/methods/model/rigid_motions.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstdio>
#include <numeric>

namespace loom {
namespace {

Index find(std::vector<Index>& parent, Index i) {
  while (parent[std::size_t(i)] != i) i = parent[std::size_t(i)] = parent[std::size_t(parent[std::size_t(i)])];
  return i;
}

std::string point(const Vec2& p) {
  char buf[80];
  std::snprintf(buf, sizeof buf, "(%.6g, %.6g)", std::abs(p.x()) < 1e-12 ? 0.0 : p.x(), std::abs(p.y()) < 1e-12 ? 0.0 : p.y());
  return buf;
}

}  // namespace

std::string FreeRigidMotion::describe() const {
  if (held_components == 0) return "has no prescribed displacement: it can translate and rotate freely";
  if (free_motions >= 2) return "can move freely in " + std::to_string(free_motions) + " rigid motions (its displacement conditions hold too little)";
  if (rotation) return "can rotate freely about " + point(centre);
  if (std::abs(direction.y()) < 1e-9) return "can translate freely along x";
  if (std::abs(direction.x()) < 1e-9) return "can translate freely along y";
  return "can translate freely along " + point(direction);
}

std::vector<FreeRigidMotion> free_rigid_motions(const std::vector<Vec2>& X, const std::vector<const Cells*>& blocks,
                                                const std::vector<char>& held, const std::vector<Index>* active) {
  const Index n = Index(X.size());
  std::vector<Index> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), Index(0));
  std::vector<char> in_cell(static_cast<std::size_t>(n), 0);
  for (const Cells* cb : blocks) {
    auto join = [&](Index c) {
      const Index* v = cb->cell_nodes(c);
      for (int a = 0; a < cb->stride; ++a) {
        in_cell[std::size_t(v[a])] = 1;
        parent[std::size_t(find(parent, v[a]))] = find(parent, v[0]);
      }
    };
    if (active) for (Index c : *active) join(c);
    else for (Index c = 0; c < cb->size(); ++c) join(c);
  }
  // Pieces in order of their first node.
  std::vector<Index> piece_of(static_cast<std::size_t>(n), kNoIndex);
  std::vector<std::vector<Index>> pieces;
  for (Index i = 0; i < n; ++i) {
    if (!in_cell[std::size_t(i)]) continue;
    const Index root = find(parent, i);
    if (piece_of[std::size_t(root)] == kNoIndex) piece_of[std::size_t(root)] = Index(pieces.size()), pieces.emplace_back();
    pieces[std::size_t(piece_of[std::size_t(root)])].push_back(i);
  }
  std::vector<FreeRigidMotion> free;
  for (auto& nodes : pieces) {
    Vec2 lo = X[std::size_t(nodes[0])], hi = lo, centre = Vec2::Zero();
    for (Index i : nodes) lo = lo.cwiseMin(X[std::size_t(i)]), hi = hi.cwiseMax(X[std::size_t(i)]), centre += X[std::size_t(i)];
    centre /= double(nodes.size());
    const double L = std::max((hi - lo).norm(), 1e-300);
    Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
    int rows = 0;
    for (Index i : nodes)
      for (int d = 0; d < 2; ++d) {
        if (!held[2 * std::size_t(i) + std::size_t(d)]) continue;
        const Vec2 r = (X[std::size_t(i)] - centre) / L;
        const Eigen::Vector3d row = d == 0 ? Eigen::Vector3d(1, 0, -r.y()) : Eigen::Vector3d(0, 1, r.x());
        AtA += row * row.transpose();
        ++rows;
      }
    // Entries of A are O(1): a free motion leaves an eigenvalue at round-off of the sum of `rows` terms.
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(AtA);
    const double tol = 1e-10 * std::max(1.0, eig.eigenvalues().maxCoeff());
    FreeRigidMotion f;
    f.held_components = rows;
    for (int k = 0; k < 3; ++k) f.free_motions += eig.eigenvalues()[k] <= tol;
    if (f.free_motions == 0) continue;
    if (f.free_motions == 1) {
      const Eigen::Vector3d m = eig.eigenvectors().col(0);  // ascending eigenvalues: the free one first
      const double omega = m.z() / L;
      if (std::abs(m.z()) > 1e-6 * m.head<2>().norm()) {
        f.rotation = true;
        f.centre = centre + Vec2(-m.y(), m.x()) / omega;  // where t + omega e_z x (X - X_c) vanishes
      } else {
        f.direction = Vec2(m.x(), m.y()).normalized();
      }
    }
    f.nodes = std::move(nodes);
    free.push_back(std::move(f));
  }
  return free;
}

}  // namespace loom
