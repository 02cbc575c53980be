#include "engine/methods/model/model_checks.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "engine/core/errors.hpp"
#include "engine/mesh/triangle_geometry.hpp"
#include "engine/methods/model/rigid_motions.hpp"

namespace loom {
namespace {

std::string advice(const FreeRigidMotion& f) {
  if (f.held_components == 0)
    return "add a [[boundary]] with a displacement on it, or give it inertia (time.integrator = \"euler_backward\" and a density)";
  if (f.free_motions >= 2) return "prescribe both components at one node and one component at another node";
  if (f.rotation)
    return "hold a second point away from that one (prescribe u_x or u_y at a node elsewhere on the body, or widen the region "
           "that holds only this point)";
  if (std::abs(f.direction.y()) < 1e-9) return "prescribe u_x at one node at least (a roller: displacement = { x = 0.0 })";
  if (std::abs(f.direction.x()) < 1e-9) return "prescribe u_y at one node at least (a roller: displacement = { y = 0.0 })";
  return "prescribe a displacement component along that direction at one node at least";
}

}  // namespace

void check_rigid_motions_held(const SceneSpec& scene, const Nodes<2>& nodes, const std::vector<const Cells*>& blocks,
                              const BoundaryConditions<2>& bc, const std::vector<Index>& node_body,
                              const std::vector<Index>* active) {
  if (scene.time.integrator != Integrator::static_) return;
  const Index n = nodes.size();
  std::vector<char> held(2 * static_cast<std::size_t>(n), 0);
  std::map<Index, std::vector<std::size_t>> holders;  // node -> boundaries that prescribe one of its components
  for (std::size_t k = 0; k < bc.boundary_prescribed.size(); ++k)
    for (Index e : bc.boundary_prescribed[k]) {
      const auto& p = bc.prescribed[std::size_t(e)];
      const int d = int(p.dof % bc.per_node);
      if (d >= 2) continue;  // a prescribed pressure or dilatation holds no motion
      held[2 * std::size_t(p.node) + std::size_t(d)] = 1;
      holders[p.node].push_back(k);
    }
  std::vector<Vec2> X(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) X[std::size_t(i)] = nodes.X[i];
  const auto free = free_rigid_motions(X, blocks, held, active);
  if (free.empty()) return;
  const FreeRigidMotion& f = free.front();
  const Index body = node_body.empty() ? 0 : node_body[std::size_t(f.nodes.front())];
  const BodySpec& spec = scene.bodies[std::size_t(body)];
  std::map<std::size_t, int> held_nodes;  // boundary -> nodes of the piece it holds
  for (Index i : f.nodes) {
    auto it = holders.find(i);
    if (it == holders.end()) continue;
    auto ks = it->second;
    std::sort(ks.begin(), ks.end());
    ks.erase(std::unique(ks.begin(), ks.end()), ks.end());
    for (std::size_t k : ks) ++held_nodes[k];
  }
  std::ostringstream os;
  os << spec.where << ": error: body[" << body << "]: the run is static (no inertia), and ";
  if (active) os << "the active grid under body \"" << spec.name << "\" ";
  else os << "body \"" << spec.name << "\" " << (free.size() > 1 || f.nodes.size() < std::size_t(nodes.size()) ? "(a connected piece of it) " : "");
  os << f.describe();
  if (!held_nodes.empty()) {
    os << "; it is held only by";
    bool first = true;
    for (const auto& [k, count] : held_nodes) {
      os << (first ? " " : ", ") << "boundary \"" << bc.boundary_names[k] << "\" (" << count << (count == 1 ? " node)" : " nodes)");
      first = false;
    }
  }
  os << ". The tangent is singular and the answer would be arbitrary: " << advice(f);
  throw InputError(os.str());
}

void check_point_probes_inside(const SceneSpec& scene, const std::vector<Vec2>& X, const std::vector<Index>& corners,
                               const std::vector<Index>& corner_body) {
  for (std::size_t k = 0; k < scene.probes.size(); ++k) {
    const ProbeSpec& p = scene.probes[k];
    if (p.kind != ProbeKind::point && p.kind != ProbeKind::stress) continue;
    bool inside = false;
    for (std::size_t t = 0; t + 2 < corners.size() && !inside; t += 3) {
      if (p.body != kNoIndex && corner_body[t / 3] != p.body) continue;
      const auto l = barycentric(X[std::size_t(corners[t])], X[std::size_t(corners[t + 1])], X[std::size_t(corners[t + 2])], p.at);
      inside = l && l->minCoeff() >= -1e-6;  // barycentric: relative to the cell size
    }
    if (inside) continue;
    std::ostringstream os;
    os << p.where << ": error: probe[" << k << "].at: (" << p.at.x() << ", " << p.at.y() << ") lies outside "
       << (p.body == kNoIndex ? std::string("every body") : "body \"" + scene.bodies[std::size_t(p.body)].name + "\"")
       << " (reference coordinates; a curved 6-node cell counts by its straight corner triangle); a "
       << (p.kind == ProbeKind::stress ? "stress" : "point") << " probe reads the body at that point";
    throw InputError(os.str());
  }
}

void check_stress_probes_found(const SceneSpec& scene, const std::vector<std::size_t>& cells_found) {
  for (std::size_t k = 0; k < scene.probes.size(); ++k) {
    const ProbeSpec& p = scene.probes[k];
    if (p.kind != ProbeKind::stress || cells_found[k] > 0) continue;
    std::ostringstream os;
    os << p.where << ": error: probe[" << k << "].at: (" << p.at.x() << ", " << p.at.y() << ", " << p.at_z << ") lies outside "
       << (p.body == kNoIndex ? std::string("every body") : "body \"" + scene.bodies[std::size_t(p.body)].name + "\"")
       << " (reference coordinates; a curved 10-node cell counts by its straight corner tetrahedron); a stress probe reads "
          "the body at that point";
    throw InputError(os.str());
  }
}

}  // namespace loom
