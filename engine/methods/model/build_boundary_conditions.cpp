#include "engine/methods/model/build_boundary_conditions.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <sstream>

#include "engine/core/errors.hpp"
#include "engine/mesh/boundary_edges.hpp"

namespace loom {

template <int D>
Index add_expression(BoundaryConditions<D>& bc, const ExpressionSpec& e) {
  std::ostringstream where;
  where << e.where << ": " << e.key;
  bc.expressions.emplace_back(e.text, where.str(), D);
  return Index(bc.expressions.size() - 1);
}
template Index add_expression<2>(BoundaryConditions<2>&, const ExpressionSpec&);
template Index add_expression<3>(BoundaryConditions<3>&, const ExpressionSpec&);

template <int D>
void prescribe_displacements(const SceneSpec& scene, std::size_t k, const std::vector<Index>& selected, const std::map<Index, std::array<Index, 2>>& tied,
                             const Nodes<D>& nodes, PrescribedDofs& seen, BoundaryConditions<D>& bc) {
  const BoundarySpec& spec = scene.boundaries[k];
  const int dofs_per_node = bc.per_node;
  for (int d = 0; d < D; ++d) {
    const std::optional<ExpressionSpec>& comp = spec.displacement[d];
    if (!comp) continue;
    const Index expr = add_expression(bc, *comp);
    for (Index i : selected) {
      if (tied.count(i)) continue;  // follows its corners
      const Index dof = i * dofs_per_node + d;
      auto it = seen.at.find(dof);
      if (it == seen.at.end()) {
        seen.at[dof] = bc.prescribed.size();
        bc.prescribed.push_back({dof, i, expr});
        seen.by.push_back(Index(k));
        bc.boundary_prescribed.back().push_back(Index(bc.prescribed.size() - 1));
        continue;
      }
      const auto& other = bc.prescribed[it->second];
      const std::string& other_text = bc.expressions[std::size_t(other.expression)].text();
      std::ostringstream at;
      for (int c = 0; c < D; ++c) at << (c ? ", " : "") << nodes.X[i][c];
      LOOM_CHECK(other_text == comp->text, InputError,
                 comp->where << ": error: " << comp->key << ": node at (" << at.str() << ") is also prescribed by boundary \""
                             << scene.boundaries[std::size_t(seen.by[it->second])].name << "\" with \""
                             << other_text << "\"; prescribe it once or with the same expression");
      bc.boundary_prescribed.back().push_back(Index(it->second));
    }
  }
}
template void prescribe_displacements<2>(const SceneSpec&, std::size_t, const std::vector<Index>&, const std::map<Index, std::array<Index, 2>>&,
                                         const Nodes<2>&, PrescribedDofs&, BoundaryConditions<2>&);
template void prescribe_displacements<3>(const SceneSpec&, std::size_t, const std::vector<Index>&, const std::map<Index, std::array<Index, 2>>&,
                                         const Nodes<3>&, PrescribedDofs&, BoundaryConditions<3>&);

std::optional<ExpressionSpec> combine(const std::optional<ExpressionSpec>& a, const std::optional<ExpressionSpec>& b) {
  if (!a) return b;
  if (!b) return a;
  ExpressionSpec e = *b;
  e.text = "(" + a->text + ") + (" + b->text + ")";
  return e;
}

const MeshRegion& boundary_group(const SceneSpec& scene, const BodyRegions& regions, std::size_t k) {
  const BoundarySpec& spec = scene.boundaries[k];
  const auto body = std::size_t(spec.body);
  const MeshRegion* region = nullptr;
  std::string known;
  if (body < regions.size())
    for (const auto& r : regions[body]) {
      if (r.name == spec.group) region = &r;
      known += (known.empty() ? "" : ", ") + ("\"" + r.name + "\"");
    }
  LOOM_CHECK(region, InputError,
             spec.region_where << ": error: boundary[" << k << "].region.group: the mesh of body \"" << scene.bodies[body].name
                               << "\" has no physical group \"" << spec.group << "\" (its groups: " << (known.empty() ? "none" : known) << ")");
  return *region;
}

void check_traction_support(const SceneSpec& scene, std::size_t k, std::size_t loaded, std::size_t in_region, const std::string& needs) {
  if (loaded > 0) return;
  const BoundarySpec& spec = scene.boundaries[k];
  LOOM_CHECK(in_region > 0, InputError,
             spec.region_where << ": error: boundary[" << k << "].region." << (spec.group.empty() ? "box" : "group")
                               << ": a traction needs " << needs << ", and this region holds none");
  const bool plane = scene.scene.dimension == 2;
  const Vec2 d = spec.normal ? *spec.normal : Vec2(0.0, 0.0);
  std::ostringstream os;
  os << spec.normal_where << ": error: boundary[" << k << "].region.normal: a traction needs " << needs
     << ", and this region holds none facing region.normal: its filter removed all " << in_region << " of the region's boundary "
     << (plane ? "edges" : "faces") << " (none has its outward normal within 45 degrees of (" << d.x() << ", " << d.y();
  if (!plane) os << ", " << spec.normal_z;
  os << "))";
  throw InputError(os.str());
}

namespace {
// Cells with a node on each side (tri6, quad9); a quad9 centre node is never on the boundary.
bool quadratic(const Cells& cb) { return cb.stride == 6 || cb.stride == 9; }
}  // namespace

BoundaryConditions<2> build_boundary_conditions(const SceneSpec& scene, const Nodes<2>& nodes,
                                                const std::vector<Cells>& cells, const std::vector<Index>& node_body,
                                                const BodyRegions& regions, int dofs_per_node, bool tie_mid_nodes,
                                                const std::vector<TractionEdge<2>>* frozen_tractions) {
  BoundaryConditions<2> bc;
  bc.per_node = dofs_per_node;
  const Index n_dofs = nodes.size() * dofs_per_node;

  // Region tolerance: relative to the size of each body.
  std::vector<Vec2> lo(scene.bodies.size(), Vec2::Constant(1e300)), hi(scene.bodies.size(), Vec2::Constant(-1e300));
  for (Index i = 0; i < nodes.size(); ++i) {
    const auto b = std::size_t(node_body[std::size_t(i)]);
    lo[b] = lo[b].cwiseMin(nodes.X[i]), hi[b] = hi[b].cwiseMax(nodes.X[i]);
  }

  // Boundary edges of every block (bodies do not share nodes), with the mid-node of quadratic cells.
  struct Edge {
    Index a, b, mid;
  };
  std::vector<Edge> edges;
  for (const Cells& cb : cells)
    for (const auto& e : boundary_edges(cb.nodes.values(), cb.stride))
      edges.push_back({e.a, e.b, quadratic(cb) ? cb.node(e.cell, corners_of_stride(cb.stride) + e.side) : kNoIndex});

  // The nodes each region selects: in the box, or in the group (mid-nodes: both corners of their edge).
  std::vector<std::pair<Index, Index>> mid_corners(std::size_t(nodes.size()), {kNoIndex, kNoIndex});
  for (const Cells& cb : cells)
    if (quadratic(cb)) {
      const int k = corners_of_stride(cb.stride);
      for (Index c = 0; c < cb.size(); ++c)
        for (int s = 0; s < k; ++s) mid_corners[std::size_t(cb.node(c, k + s))] = {cb.node(c, s), cb.node(c, (s + 1) % k)};
    }
  std::vector<std::vector<char>> member(scene.boundaries.size(), std::vector<char>(std::size_t(nodes.size()), 0));
  for (std::size_t k = 0; k < scene.boundaries.size(); ++k) {
    const BoundarySpec& spec = scene.boundaries[k];
    const auto body = std::size_t(spec.body);
    std::vector<char>& in = member[k];
    if (spec.group.empty()) {
      const double tol = 1e-9 * std::max(1.0, (hi[body] - lo[body]).norm());
      for (Index i = 0; i < nodes.size(); ++i) {
        const Vec2& X = nodes.X[i];
        in[std::size_t(i)] = node_body[std::size_t(i)] == spec.body && X.x() >= spec.box_min.x() - tol && X.x() <= spec.box_max.x() + tol &&
                             X.y() >= spec.box_min.y() - tol && X.y() <= spec.box_max.y() + tol;
      }
      continue;
    }
    const MeshRegion* region = &boundary_group(scene, regions, k);
    for (Index v : region->corners) in[std::size_t(v)] = 1;
    const std::set<std::array<Index, 2>> curve(region->edges.begin(), region->edges.end());
    for (Index i = 0; i < nodes.size(); ++i) {
      const auto [a, b] = mid_corners[std::size_t(i)];
      if (a == kNoIndex || !in[std::size_t(a)] || !in[std::size_t(b)]) continue;
      // A curve holds the mid-nodes of its own edges; a surface those of every edge between its nodes.
      if (region->dim == 2 || (region->dim == 1 && curve.count({std::min(a, b), std::max(a, b)}))) in[std::size_t(i)] = 1;
    }
  }
  auto in_region = [&](const BoundarySpec& spec, Index i) { return member[std::size_t(&spec - scene.boundaries.data())][std::size_t(i)] != 0; };
  // region.normal: the edge's outward normal in the reference configuration. Cells are counter-clockwise
  // (generators, mesh files and remeshes alike), and a boundary edge a -> b runs as in its cell, so the body lies
  // on its left and the outward normal is the edge turned clockwise, (y_b - y_a, -(x_b - x_a)).
  auto facing = [&](const BoundarySpec& spec, const Edge& e) {
    const std::optional<Vec2> d = region_normal<2>(spec);
    if (!d) return true;
    const Vec2 t = nodes.X[e.b] - nodes.X[e.a];
    return faces_direction<2>(Vec2(t.y(), -t.x()), *d);
  };

  // Seed 000 eq 24: in PFEM, the mid-nodes of boundary edges that carry a condition are tied to the
  // midpoint of their corners (both components), instead of being prescribed or loaded on their own.
  std::map<Index, std::array<Index, 2>> tied;  // mid-node -> corners
  if (tie_mid_nodes)
    for (const BoundarySpec& spec : scene.boundaries) {
      if (!spec.has_traction && !spec.displacement.x && !spec.displacement.y) continue;
      // With region.normal (a traction alone, the loader sees to it) only the edges that carry the traction.
      for (const Edge& e : edges)
        if (e.mid != kNoIndex && in_region(spec, e.a) && in_region(spec, e.b) && facing(spec, e)) tied[e.mid] = {e.a, e.b};
    }
  for (const auto& [mid, corner] : tied)
    for (int d = 0; d < 2; ++d) bc.ties.push_back({mid * dofs_per_node + d, {corner[0] * dofs_per_node + d, corner[1] * dofs_per_node + d}});

  PrescribedDofs seen;
  for (std::size_t k = 0; k < scene.boundaries.size(); ++k) {
    const BoundarySpec& spec = scene.boundaries[k];
    const auto body = std::size_t(spec.body);
    auto inside = [&](Index i) { return in_region(spec, i); };
    std::vector<Index> selected;
    for (Index i = 0; i < nodes.size(); ++i)
      if (inside(i)) selected.push_back(i);
    LOOM_CHECK(!selected.empty(), InputError,
               spec.region_where << ": error: boundary[" << k << "].region." << (spec.group.empty() ? "box" : "group")
                                 << ": the region selects no node of body \""
                                 << scene.bodies[body].name << "\" (its nodes span [" << lo[body].x() << ", " << lo[body].y()
                                 << "] to [" << hi[body].x() << ", " << hi[body].y() << "])");
    bc.boundary_names.push_back(spec.name);
    bc.boundary_nodes.push_back(selected);
    bc.boundary_prescribed.emplace_back();

    prescribe_displacements(scene, k, selected, tied, nodes, seen, bc);

    if (spec.has_traction) {
      // Compiled in every build, so that expression indices (kept by frozen traction edges) stay valid.
      std::array<Index, 2> expr{kNoIndex, kNoIndex};
      if (spec.traction.x) expr[0] = add_expression(bc, *spec.traction.x);
      if (spec.traction.y) expr[1] = add_expression(bc, *spec.traction.y);
      if (frozen_tractions) continue;
      std::size_t n_edges = 0, n_in_region = 0;  // loaded; in the region, before region.normal's filter
      for (const auto& e : edges) {
        if (!inside(e.a) || !inside(e.b)) continue;
        ++n_in_region;
        if (!facing(spec, e)) continue;
        bc.traction_edges.push_back({e.a, e.b, tied.count(e.mid) ? kNoIndex : e.mid, expr}), ++n_edges;
      }
      check_traction_support(scene, k, n_edges, n_in_region, "boundary edges with both end nodes in the region");
      for (Index e : expr)
        if (e != kNoIndex) bc.has_loads = true, bc.loads_depend_on_time |= bc.expressions[std::size_t(e)].depends_on_time();
    }
  }

  if (frozen_tractions) {
    bc.traction_edges = *frozen_tractions;
    bc.has_loads = !bc.traction_edges.empty();
    for (const auto& e : bc.traction_edges)
      for (Index x : e.expression)
        if (x != kNoIndex) bc.loads_depend_on_time |= bc.expressions[std::size_t(x)].depends_on_time();
  }
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    std::array<Index, 2> expr{kNoIndex, kNoIndex};
    const auto x = combine(scene.body_force.x, scene.bodies[b].body_force.x);
    const auto y = combine(scene.body_force.y, scene.bodies[b].body_force.y);
    if (x) expr[0] = add_expression(bc, *x);
    if (y) expr[1] = add_expression(bc, *y);
    for (Index e : expr)
      if (e != kNoIndex) bc.has_loads = true, bc.loads_depend_on_time |= bc.expressions[std::size_t(e)].depends_on_time();
    bc.body_force.push_back(expr);
  }
  bc.target = Eigen::VectorXd::Zero(n_dofs);
  bc.external = Eigen::VectorXd::Zero(n_dofs);
  return bc;
}

template <int D>
std::vector<DofKind> dof_kinds(const BoundaryConditions<D>& bc, const std::vector<Cells>& cells, Index n_nodes, int dofs_per_node) {
  std::vector<DofKind> kinds(std::size_t(n_nodes) * std::size_t(dofs_per_node), DofKind::free);
  if (dofs_per_node == D + 1) {
    // The dilatation (or pressure) is an unknown only at nodes of mixed u-phi (u-p) cells.
    for (Index i = 0; i < n_nodes; ++i) kinds[std::size_t((D + 1) * i + D)] = DofKind::absent;
    for (const Cells& cb : cells)
      if (has_dilatation(cb.formulation) || has_pressure(cb.formulation))
        for (Index k = 0; k < cb.nodes.size(); ++k) kinds[std::size_t((D + 1) * cb.nodes[k] + D)] = DofKind::free;
  }
  for (const auto& p : bc.prescribed) kinds[std::size_t(p.dof)] = DofKind::prescribed;
  for (const auto& t : bc.ties) kinds[std::size_t(t.dof)] = DofKind::tied;
  return kinds;
}
template std::vector<DofKind> dof_kinds<2>(const BoundaryConditions<2>&, const std::vector<Cells>&, Index, int);
template std::vector<DofKind> dof_kinds<3>(const BoundaryConditions<3>&, const std::vector<Cells>&, Index, int);

}  // namespace loom
