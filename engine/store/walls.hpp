// Walls: the rigid planes of a mesh-based run (seed 001 §1.8) with their penalties, built once from the scene;
// the per-node contact state (boundary share facing each plane, first-contact point) lives in Nodes
// (contact_share, contact_point, in_contact) so that it follows the particles through PFEM remeshes and
// checkpoints. 2D and 3D: WallsT<D> with planes (lines in 2D) of Vec<D>; Walls is the 2D store.
#pragma once

#include <string>
#include <vector>

#include "engine/core/types.hpp"

namespace loom {

// A scene's walls have at most this many planes in all (a box is four, six in 3D), so that a node's share of the boundary
// facing each of them is a fixed-size column entry.
constexpr int kMaxWallPlanes = 8;
using WallShares = Eigen::Matrix<double, kMaxWallPlanes, 1>;

template <int D>
struct WallPlaneT {
  Vec<D> point = Vec<D>::Zero();
  Vec<D> normal = Vec<D>::UnitY();  // unit, pointing to the material's side
  Index wall = 0;                   // the wall it belongs to
  // Signed distance of x from the plane: negative behind it.
  double gap(const Vec<D>& x) const { return (x - point).dot(normal); }
};
using WallPlane = WallPlaneT<2>;

struct Wall {
  std::string name;
  double k_n = 0.0;  // normal penalty (and tangential, with stick), force / length / length
  bool stick = false;
  Index body = kNoIndex;  // the body it acts on; kNoIndex: every body
};

template <int D>
struct WallsT {
  std::vector<Wall> walls;
  std::vector<WallPlaneT<D>> planes;
  bool empty() const { return planes.empty(); }
  bool acts_on(const WallPlaneT<D>& p, Index body) const {
    const Index b = walls[std::size_t(p.wall)].body;
    return b == kNoIndex || b == body;
  }
};
using Walls = WallsT<2>;

// What the walls do at the converged state (wall_force and penetration probes); in 2D the z components are zero.
struct WallResult {
  Vec3 force = Vec3::Zero();   // the force the wall exerts on the bodies
  double penetration = 0.0;    // largest distance of a node behind the wall, >= 0
  Vec3 normal = Vec3::Zero();  // the normal of a wall of one plane (a box: zero)
};

}  // namespace loom
