// The 3D remesh's flips with the points fixed (tet_flips.hpp): the sliver pass (R3.4) and the Delaunay repair (R3.8),
// both on FlipMesh (flip_mesh.hpp).
#include "systems/remesh/tet_flips.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "systems/remesh/flip_mesh.hpp"

namespace loom {
namespace {

using namespace flips;

constexpr int kMaxRepairPasses = 50;  // Lawson's flips terminate; a cap against a cycle the margins could allow
constexpr double kSliver = 0.1;       // q below which a tet is a sliver (the spec's measure; Remesh3dResult::slivers)

}  // namespace

double tet_quality(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  const Vec3 vw = v.cross(w), wu = w.cross(u), uv = u.cross(v);
  const double det = u.dot(vw);  // 6 V
  // Circumcentre - a = n / (2 det), so R = |n| / (2 |det|); r_in = 3V / S = |det| / (2 S).
  const Vec3 n = u.squaredNorm() * vw + v.squaredNorm() * wu + w.squaredNorm() * uv;
  const double two_s = vw.norm() + wu.norm() + uv.norm() + (v - u).cross(w - u).norm();  // 2 S
  const double den = two_s * n.norm();
  if (!(den > 0.0)) return 0.0;
  return 6.0 * det * std::abs(det) / den;  // 3 r_in / R = 6 det^2 / (2S |n|), with the sign of det
}

namespace {

// R3.4's passes on a mesh: each over the tets below the threshold, worst first.
void remove_slivers(FlipMesh& mesh, const FlipSettings& settings, FlipStats& stats) {
  mesh.count(settings.threshold, stats.below_before, stats.worst_before);
  for (int pass = 0; pass < settings.max_passes; ++pass) {
    const std::vector<Index> bad = mesh.bad_tets(settings.threshold);
    if (bad.empty()) break;
    ++stats.passes;
    Index done = 0;
    for (Index t : bad) {
      if (!mesh.alive(t)) continue;  // replaced by an earlier flip of this pass
      const Candidate c = mesh.best_around(t);
      if (c.kind == 0) continue;
      mesh.apply(c);
      ++done;
      if (c.kind == 1) ++stats.flips23;
      else if (c.old_tets.size() == 3) ++stats.flips32;
      else ++stats.edge_removals;
    }
    if (done == 0) break;
  }
  mesh.count(settings.threshold, stats.below_after, stats.worst_after);
}

}  // namespace

FlipStats improve_by_flips(const std::vector<Vec3>& points, std::vector<Index>& tets, const FlipSettings& settings,
                           std::vector<Index>* origin, std::vector<std::array<Index, 4>>* neighbours) {
  const std::size_t n_input = tets.size() / 4;
  FlipMesh mesh(points, tets, neighbours);
  FlipStats stats;
  remove_slivers(mesh, settings, stats);
  mesh.write(tets, n_input, origin, neighbours);
  return stats;
}

DelaunayRepairStats repair_delaunay(const std::vector<Vec3>& points, std::vector<Index>& tets, const FlipSettings& slivers,
                                    std::vector<std::array<Index, 4>>* neighbours) {
  const std::size_t n_input = tets.size() / 4;
  FlipMesh mesh(points, tets, neighbours);
  const double floor = slivers.threshold;
  const Bar bar{false, floor};
  DelaunayRepairStats stats;
  for (int pass = 0; pass < kMaxRepairPasses; ++pass) {
    const std::vector<std::pair<Index, int>> failing = mesh.failing_faces();
    if (failing.empty()) break;
    ++stats.passes;
    Index done = 0;
    for (const auto& [t, f] : failing) {
      if (!mesh.alive(t) || !mesh.fails_delaunay(t, f)) continue;  // an earlier flip of this pass replaced or fixed it
      const Candidate c = mesh.lawson_flip(t, f, bar);
      if (c.kind == 0) continue;
      mesh.apply(c);
      ++done;
    }
    stats.flips += done;
    if (done == 0) break;
  }
  if (stats.flips > 0 && slivers.threshold > 0.0) remove_slivers(mesh, slivers, stats.slivers);
  // What is left: a face whose flip only the quality bar refuses is kept (the sliver pass would undo the flip), and
  // one that no flip mends between two tets that are not slivers; one that no flip mends beside a sliver is stuck.
  const Bar positive{false, -kInf};
  for (const auto& [t, f] : mesh.failing_faces()) {
    ++stats.failing_after;
    stats.stuck += mesh.worst_across(t, f) < std::min(floor, kSliver) && mesh.lawson_flip(t, f, positive).kind == 0;
  }
  mesh.write(tets, n_input, nullptr, neighbours);
  return stats;
}

}  // namespace loom
