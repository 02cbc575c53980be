// Walls: the rigid planes of a mesh-based run (seed 001 §1.8) with their penalties, built once from the scene;
// the per-node contact state (boundary share facing each plane, first-contact point) lives in Nodes
// (contact_share, contact_point, in_contact) so that it follows the particles through PFEM remeshes and
// checkpoints.
#pragma once

#include <string>
#include <vector>

#include "engine/core/types.hpp"

namespace loom {

// A scene's walls have at most this many planes in all (a box is four), so that a node's share of the boundary
// facing each of them is a fixed-size column entry.
constexpr int kMaxWallPlanes = 8;
using WallShares = Eigen::Matrix<double, kMaxWallPlanes, 1>;

struct WallPlane {
  Vec2 point = Vec2::Zero();
  Vec2 normal = Vec2::UnitY();  // unit, pointing to the material's side
  Index wall = 0;               // the wall it belongs to
  // Signed distance of x from the plane: negative behind it.
  double gap(const Vec2& x) const { return (x - point).dot(normal); }
};

struct Wall {
  std::string name;
  double k_n = 0.0;  // normal penalty (and tangential, with stick), force / length / length
  bool stick = false;
  Index body = kNoIndex;  // the body it acts on; kNoIndex: every body
};

struct Walls {
  std::vector<Wall> walls;
  std::vector<WallPlane> planes;
  bool empty() const { return planes.empty(); }
  bool acts_on(const WallPlane& p, Index body) const {
    const Index b = walls[std::size_t(p.wall)].body;
    return b == kNoIndex || b == body;
  }
};

// What the walls do at the converged state (wall_force and penetration probes).
struct WallResult {
  Vec2 force = Vec2::Zero();  // the force the wall exerts on the bodies
  double penetration = 0.0;   // largest distance of a node behind the wall, >= 0
  Vec2 normal = Vec2::Zero();  // the normal of a wall of one plane (a box: zero)
};

}  // namespace loom
