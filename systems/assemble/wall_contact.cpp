#include "systems/assemble/wall_contact.hpp"

#include <algorithm>

#include "engine/core/parallel.hpp"
#include "engine/mesh/boundary_edges.hpp"

namespace loom {
namespace {

NodeContact contact_of(const Walls& walls, std::size_t plane, const Nodes<2>& nodes, Index i, const Vec2& x) {
  const WallPlane& p = walls.planes[plane];
  const Wall& w = walls.walls[std::size_t(p.wall)];
  const double k = w.k_n * nodes.contact_share[i][Index(plane)];
  const bool held = nodes.in_contact[i] != 0.0;
  return node_contact(p, k, w.stick, held, held ? nodes.contact_point[i] : Vec2::Zero(), nodes.position_n(i), x);
}

// A node whose displacement is prescribed in both directions (a Dirichlet node, an inlet's driven row behind the
// section) goes where it is told: no wall acts on it.
bool driven(const DofMap& dofs, Index i) {
  return dofs.kind[std::size_t(dofs.dof(i, 0))] == DofKind::prescribed && dofs.kind[std::size_t(dofs.dof(i, 1))] == DofKind::prescribed;
}

}  // namespace

Vec2 first_contact_point(const WallPlane& p, const Vec2& x_n, const Vec2& x) {
  const double g_n = p.gap(x_n), g = p.gap(x);
  if (!(g_n > 0.0)) return x_n - g_n * p.normal;
  return x_n + (g_n / (g_n - g)) * (x - x_n);
}

NodeContact node_contact(const WallPlane& p, double k, bool stick, bool held, const Vec2& held_point, const Vec2& x_n, const Vec2& x) {
  NodeContact c;
  // A node exactly on the wall is in contact too: its force is zero but its tangent holds a body that starts
  // resting on the wall (a static run would otherwise begin with a singular matrix).
  const double g = p.gap(x);
  if (!(g <= 0.0)) return c;
  const Eigen::Matrix2d nn = p.normal * p.normal.transpose();
  c.penetration = -g;
  c.r = k * g * p.normal;
  c.K = k * nn;
  if (!stick) return c;
  const Eigen::Matrix2d tt = Eigen::Matrix2d::Identity() - nn;
  const double g_n = p.gap(x_n);
  if (held || !(g_n > 0.0)) {  // a fixed anchor
    c.r += k * tt * (x - (held ? held_point : first_contact_point(p, x_n, x)));
    c.K += k * tt;
    return c;
  }
  // Arriving in this step: x - c = phi (x - x_n) with phi = -g / (g_n - g), d phi / dx = -g_n / (g_n - g)^2 n^T.
  const Vec2 dx = x - x_n;
  const double phi = -g / (g_n - g), dphi = -g_n / ((g_n - g) * (g_n - g));
  c.r += k * phi * (tt * dx);
  c.K += k * (phi * tt + (tt * dx) * (dphi * p.normal).transpose());
  return c;
}

void measure_contact_areas(const StepContext&, const Walls& walls, const std::vector<Cells>& cells, Nodes<2>& nodes) {
  std::fill(nodes.contact_share.begin(), nodes.contact_share.end(), WallShares::Zero());
  const auto planes = Index(walls.planes.size());
  LOOM_ASSERT(planes <= kMaxWallPlanes, planes << " wall planes, at most " << kMaxWallPlanes);
  for (const Cells& cb : cells) {
    const int corners = corners_of_stride(cb.stride);
    const bool quadratic = cb.stride == 6 || cb.stride == 9;
    for (const BoundaryEdge& e : boundary_edges(cb.nodes.values(), cb.stride)) {
      // Counter-clockwise cells: the body lies left of a -> b, so the outward normal times the length is the
      // edge turned clockwise.
      const Vec2 d = nodes.position_n(e.b) - nodes.position_n(e.a), area(d.y(), -d.x());
      WallShares facing = WallShares::Zero();
      for (Index p = 0; p < planes; ++p) facing[p] = std::max(0.0, -area.dot(walls.planes[std::size_t(p)].normal));
      const double end = quadratic ? 1.0 / 6.0 : 0.5;
      nodes.contact_share[e.a] += end * facing;
      nodes.contact_share[e.b] += end * facing;
      if (quadratic) nodes.contact_share[cb.node(e.cell, corners + e.side)] += (2.0 / 3.0) * facing;
    }
  }
}

void add_wall_contact(const Walls& walls, const std::vector<Index>& node_body, const Nodes<2>& nodes, bool tangent, LinearSystem& system) {
  const DofMap& dofs = system.dofs;
  double* values = system.pattern.matrix.valuePtr();
  for_each_index(nodes.size(), [&](Index i) {
    if (nodes.contact_share[i].isZero(0.0) || driven(dofs, i)) return;
    const Vec2 x = nodes.position(i);
    NodeContact sum;
    for (std::size_t p = 0; p < walls.planes.size(); ++p) {
      if (!walls.acts_on(walls.planes[p], node_body[std::size_t(i)])) continue;
      const NodeContact c = contact_of(walls, p, nodes, i, x);
      sum.r += c.r, sum.K += c.K;
    }
    if (sum.r.isZero(0.0) && sum.K.isZero(0.0)) return;
    Index eq[2];
    for (int d = 0; d < 2; ++d) {
      const Index dof = dofs.dof(i, d);
      eq[d] = dofs.equation[std::size_t(dof)];
      system.residual_full[dof] += sum.r[d];
      if (eq[d] != kNoIndex) system.residual[eq[d]] += sum.r[d];
    }
    if (!tangent) return;
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        if (eq[a] == kNoIndex || eq[b] == kNoIndex || sum.K(a, b) == 0.0) continue;
        const Index slot = a == b ? system.pattern.diagonal_slot[std::size_t(eq[a])] : find_slot(system.pattern, eq[a], eq[b]);
        values[slot] += sum.K(a, b);
      }
  });
}

void commit_wall_contact(const StepContext&, const Walls& walls, const std::vector<Index>& node_body, Nodes<2>& nodes) {
  for_each_index(nodes.size(), [&](Index i) {
    const Vec2 x = nodes.position(i);
    bool touching = false;
    Vec2 point = Vec2::Zero();
    for (const WallPlane& p : walls.planes) {
      if (!walls.walls[std::size_t(p.wall)].stick || !walls.acts_on(p, node_body[std::size_t(i)]) || !(p.gap(x) <= 0.0)) continue;
      if (!touching) point = nodes.in_contact[i] != 0.0 ? nodes.contact_point[i] : first_contact_point(p, nodes.position_n(i), x);
      touching = true;
    }
    nodes.in_contact[i] = touching ? 1.0 : 0.0;
    nodes.contact_point[i] = point;
  });
}

std::vector<WallResult> wall_results(const Walls& walls, const std::vector<Index>& node_body, const Nodes<2>& nodes, const DofMap& dofs) {
  std::vector<WallResult> results(walls.walls.size());
  std::vector<int> planes(walls.walls.size(), 0);
  for (const WallPlane& p : walls.planes) ++planes[std::size_t(p.wall)], results[std::size_t(p.wall)].normal = p.normal;
  for (std::size_t w = 0; w < results.size(); ++w)
    if (planes[w] != 1) results[w].normal.setZero();
  for (Index i = 0; i < nodes.size(); ++i) {  // serial: a sum in a fixed order
    if (driven(dofs, i)) continue;
    const Vec2 x = nodes.position_n(i);
    for (std::size_t q = 0; q < walls.planes.size(); ++q) {
      const WallPlane& p = walls.planes[q];
      if (!walls.acts_on(p, node_body[std::size_t(i)])) continue;
      WallResult& r = results[std::size_t(p.wall)];
      r.penetration = std::max(r.penetration, -p.gap(x));
      if (!nodes.contact_share[i].isZero(0.0)) r.force -= contact_of(walls, q, nodes, i, x).r;
    }
  }
  return results;
}

}  // namespace loom
