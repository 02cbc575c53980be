#include "engine/methods/pfem/inlet_flow_3d.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>

#include "engine/core/errors.hpp"
#include "engine/mesh/tet_adjacency.hpp"
#include "engine/mesh/tet_mesh.hpp"

namespace loom {
namespace {

Vec3 inflow_velocity(const InletSpec& in) { return Vec3(in.velocity.x(), in.velocity.y(), in.velocity_z); }

// Three positive tetrahedra of the prism between pattern triangle (p0, p1, p2) and its copies (q0, q1, q2), p0 < p1 < p2:
// the side over edge (p_i, p_j), i < j, is cut by the diagonal p_j q_i (both prisms on an edge cut it alike).
void prism_tets(std::array<Index, 3> p, const std::map<Index, Index>& copy_of, const Nodes<3>& nodes, std::vector<Index>& tets) {
  std::sort(p.begin(), p.end());
  const Index q0 = copy_of.at(p[0]), q1 = copy_of.at(p[1]), q2 = copy_of.at(p[2]);
  for (std::array<Index, 4> t : {std::array<Index, 4>{p[0], p[1], p[2], q0}, {p[1], p[2], q0, q1}, {p[2], q0, q1, q2}}) {
    if (tet_volume(nodes.position_n(t[0]), nodes.position_n(t[1]), nodes.position_n(t[2]), nodes.position_n(t[3])) < 0.0) std::swap(t[2], t[3]);
    tets.insert(tets.end(), t.begin(), t.end());
  }
}

// Appends one fresh particle of `body` at x moving at v (undeformed: u = 0, J = 1; no mass until its cells give it some).
Index add_fresh_particle(const Vec3& x, const Vec3& v, Index body, PfemTopology3d& topo, FemModelT<3>& m) {
  const Index i = m.nodes.size();
  m.nodes.resize(i + 1);
  m.nodes.X[i] = x;
  if (m.nodes.v.used()) m.nodes.v[i] = m.nodes.v_n[i] = v;
  m.node_body.push_back(body);
  topo.points_of_body[std::size_t(body)].push_back(i);
  ++topo.n_points;
  return i;
}

// A new layer `behind` upstream of `front`, joined to it; returns the new layer (ascending indices).
std::vector<Index> add_layer(const InletSpec& in, const InletDisc& disc, const std::vector<Index>& front, double behind, PfemTopology3d& topo,
                             FemModelT<3>& m) {
  const std::vector<std::array<Index, 3>> pattern = layer_pattern(topo, in.body, front);
  LOOM_CHECK(!pattern.empty(), RunError,
             "inlet \"" << in.name << "\": no surface triangle of its body lies on its disc (" << front.size()
                        << " particle(s) there); the body's mesh must begin at the disc, with the material on the side the velocity points to");
  std::vector<Index> corners;  // the front's particles that a pattern triangle holds (one on the disc's rim alone has no copy)
  for (const auto& f : pattern) corners.insert(corners.end(), f.begin(), f.end());
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  std::map<Index, Index> copy_of;
  std::vector<Index> layer;
  for (Index i : corners) {
    const Index c = add_fresh_particle(m.nodes.position_n(i) - behind * disc.normal, disc.velocity, in.body, topo, m);
    copy_of[i] = c;
    layer.push_back(c);
  }
  std::vector<Index> fresh;
  for (const auto& f : pattern) prism_tets(f, copy_of, m.nodes, fresh);
  if (m.nodes.lumped_mass.used()) {  // the new material's mass, rho V / 4 to each corner
    const double rho = m.materials[std::size_t(in.body)].density;
    for (std::size_t t = 0; t + 3 < fresh.size(); t += 4) {
      const double share = rho * tet_volume(m.nodes.position_n(fresh[t]), m.nodes.position_n(fresh[t + 1]), m.nodes.position_n(fresh[t + 2]),
                                            m.nodes.position_n(fresh[t + 3])) / 4.0;
      for (std::size_t a = 0; a < 4; ++a) m.nodes.lumped_mass[fresh[t + a]] += share;
    }
  }
  std::vector<Index>& tets = topo.tets[std::size_t(in.body)];
  tets.insert(tets.end(), fresh.begin(), fresh.end());
  return layer;
}

}  // namespace

InletDisc inlet_disc(const InletSpec& in, const PfemTopology3d& topo, double t) {
  InletDisc d;
  const Vec3 v = inflow_velocity(in);
  d.speed = v.norm();
  d.normal = v / d.speed;
  d.velocity = v + in.section_velocity;
  d.centre = in.centre + std::clamp(t - in.start, 0.0, in.duration) * in.section_velocity;
  d.radius = in.radius;
  d.spacing = in.spacing > 0.0 ? in.spacing : topo.spacing[std::size_t(in.body)];
  return d;
}

std::vector<Index> particles_on_disc(const InletDisc& disc, const PfemTopology3d& topo, const Nodes<3>& nodes, Index body) {
  std::vector<Index> on;
  for (Index i : topo.points_of_body[std::size_t(body)]) {
    const Vec3 x = nodes.position_n(i);
    const double d = disc.distance(x);
    if (std::abs(d) <= 1e-6 * disc.spacing && (x - disc.centre - d * disc.normal).norm() <= disc.radius * (1.0 + 1e-9)) on.push_back(i);
  }
  std::sort(on.begin(), on.end());
  return on;
}

std::vector<std::array<Index, 3>> layer_pattern(const PfemTopology3d& topo, Index body, const std::vector<Index>& layer) {
  std::vector<std::array<Index, 3>> out;
  for (const auto& f : topo.surface[std::size_t(body)])
    if (std::all_of(f.begin(), f.end(), [&](Index v) { return std::binary_search(layer.begin(), layer.end(), v); })) out.push_back(f);
  return out;
}

void check_inlet_discs(const SceneSpec& scene, const PfemTopology3d& topo, const Nodes<3>& nodes) {
  for (std::size_t k = 0; k < scene.inlets.size(); ++k) {
    const InletSpec& in = scene.inlets[k];
    const InletDisc disc = inlet_disc(in, topo, in.start);
    const std::string& body = scene.bodies[std::size_t(in.body)].name;
    auto refuse = [&](const char* key, const std::string& why) {
      std::ostringstream os;
      os << in.where << ": error: inlet[" << k << "]." << key << ": " << why;
      throw InputError(os.str());
    };
    if (in.radius < 2.0 * disc.spacing)
      refuse("radius", "the disc's radius " + std::to_string(in.radius) + " is below two spacings (" + std::to_string(2.0 * disc.spacing) +
                           "): a layer would have no particle inside; lower spacing (or the body's) or widen the disc");
    const std::vector<Index> on = particles_on_disc(disc, topo, nodes, in.body);
    if (layer_pattern(topo, in.body, on).empty())
      refuse("centre", "no surface triangle of body \"" + body + "\" lies on the disc (" + std::to_string(on.size()) +
                           " particle(s) on it): the body's mesh must begin at the disc, its surface there in the disc's plane");
    Vec3 centroid = Vec3::Zero();
    for (Index i : topo.points_of_body[std::size_t(in.body)]) centroid += nodes.X[i];
    centroid /= double(topo.points_of_body[std::size_t(in.body)].size());
    if (!(disc.distance(centroid) > 0.0))
      refuse("velocity", "points away from body \"" + body + "\" (the material would flow in on the side where the body is not)");
  }
}

Index pour_inlets_3d(const std::vector<InletSpec>& inlets, double t_n, PfemTopology3d& topo, FemModelT<3>& m, bool& released) {
  const Index n_before = topo.n_points;
  std::vector<char> touched(topo.tets.size(), 0);
  for (std::size_t k = 0; k < inlets.size(); ++k) {
    const InletSpec& in = inlets[k];
    InletState& state = topo.inlets[k];
    if (state.closed || t_n < in.start) continue;
    const InletDisc disc = inlet_disc(in, topo, t_n);
    // The end: the driven layer has just reached the disc (the first layer's offset makes the layers arrive there at
    // the end time) and is released.
    if (state.started && t_n >= in.start + in.duration * (1.0 - 1e-12)) {
      state.row.clear();
      state.closed = released = true;
      continue;
    }
    std::vector<Index> front;
    if (!state.started) {
      front = particles_on_disc(disc, topo, m.nodes, in.body);
    } else {
      double d_front = 0.0;
      for (Index i : state.row) d_front += disc.distance(m.nodes.position_n(i));
      if (d_front / double(state.row.size()) < 0.0) continue;  // still upstream of the disc: driven on
      front = state.row;
    }
    // h behind the front; the first layer h_1 in [h/2, 3h/2) behind such that the poured depth |v| T is h_1 plus a
    // whole number of layers.
    double behind = disc.spacing;
    if (!state.started) {
      const double depth = disc.speed * in.duration;
      const double layers = std::max(1.0, std::round(depth / disc.spacing));
      behind = depth - (layers - 1.0) * disc.spacing;
    }
    state.row = add_layer(in, disc, front, behind, topo, m);
    state.started = true;
    touched[std::size_t(in.body)] = 1;
  }
  for (std::size_t b = 0; b < topo.tets.size(); ++b) {
    if (!touched[b]) continue;
    topo.neighbours[b] = tet_face_neighbours(topo.tets[b]);
    topo.surface[b].clear();
    for (const BoundaryFace& f : boundary_faces(topo.tets[b], topo.neighbours[b])) topo.surface[b].push_back(f.nodes);
  }
  return topo.n_points - n_before;
}

void add_inlet_layers(const std::vector<InletSpec>& inlets, const PfemTopology3d& topo, BoundaryConditions<3>& bc) {
  std::map<Index, std::size_t> entry;  // dof -> index in bc.prescribed
  for (std::size_t e = 0; e < bc.prescribed.size(); ++e) entry[bc.prescribed[e].dof] = e;
  for (std::size_t k = 0; k < inlets.size(); ++k) {
    const Vec3 v = inflow_velocity(inlets[k]) + inlets[k].section_velocity;
    for (Index i : topo.inlets[k].row)
      for (int d = 0; d < 3; ++d) {
        const BoundaryConditions<3>::Prescribed p{i * bc.per_node + d, i, kNoIndex, v[d]};
        const auto it = entry.find(p.dof);
        if (it != entry.end()) bc.prescribed[it->second] = p;
        else bc.prescribed.push_back(p);
      }
  }
}

}  // namespace loom
