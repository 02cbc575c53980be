#include "systems/assemble/wall_contact.hpp"

#include <Eigen/Geometry>
#include <algorithm>

#include "engine/core/parallel.hpp"
#include "engine/mesh/boundary_edges.hpp"
#include "engine/mesh/tet_adjacency.hpp"

namespace loom {
namespace {

template <int D>
NodeContactT<D> contact_of(const WallsT<D>& walls, std::size_t plane, const Nodes<D>& nodes, Index i, const Vec<D>& x) {
  const WallPlaneT<D>& p = walls.planes[plane];
  const Wall& w = walls.walls[std::size_t(p.wall)];
  const double k = w.k_n * nodes.contact_share[i][Index(plane)];
  const bool held = nodes.in_contact[i] != 0.0;
  return node_contact<D>(p, k, w.stick, held, held ? Vec<D>(nodes.contact_point[i]) : Vec<D>::Zero(), nodes.position_n(i), x);
}

// A node whose displacement is prescribed in every direction (a Dirichlet node, an inlet's driven row behind the
// section) goes where it is told: no wall acts on it.
template <int D>
bool driven(const DofMap& dofs, Index i) {
  for (int d = 0; d < D; ++d)
    if (dofs.kind[std::size_t(dofs.dof(i, d))] != DofKind::prescribed) return false;
  return true;
}

template <int D>
WallShares facing_planes(const WallsT<D>& walls, const Vec<D>& area) {
  WallShares facing = WallShares::Zero();
  for (Index p = 0; p < Index(walls.planes.size()); ++p) facing[p] = std::max(0.0, -area.dot(walls.planes[std::size_t(p)].normal));
  return facing;
}

void measure_block(const WallsT<2>& walls, const Cells& cb, Nodes<2>& nodes) {
  const int corners = corners_of_stride(cb.stride);
  const bool quadratic = cb.stride == 6 || cb.stride == 9;
  for (const BoundaryEdge& e : boundary_edges(cb.nodes.values(), cb.stride)) {
    // Counter-clockwise cells: the body lies left of a -> b, so the outward normal times the length is the
    // edge turned clockwise.
    const Vec2 d = nodes.position_n(e.b) - nodes.position_n(e.a), area(d.y(), -d.x());
    const WallShares facing = facing_planes(walls, area);
    const double end = quadratic ? 1.0 / 6.0 : 0.5;
    nodes.contact_share[e.a] += end * facing;
    nodes.contact_share[e.b] += end * facing;
    if (quadratic) nodes.contact_share[cb.node(e.cell, corners + e.side)] += (2.0 / 3.0) * facing;
  }
}

// The mid-edge node of tet10 (VTK order: edges 01 12 20 03 13 23 at 4..9) between local corners a and b.
int tet10_mid_node(int a, int b) {
  static constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (int e = 0; e < 6; ++e)
    if ((kEdges[e][0] == a && kEdges[e][1] == b) || (kEdges[e][0] == b && kEdges[e][1] == a)) return 4 + e;
  return -1;
}

void measure_block(const WallsT<3>& walls, const Cells& cb, Nodes<3>& nodes) {
  const bool quadratic = cb.stride == 10;
  std::vector<Index> corners;
  corners.reserve(std::size_t(cb.size()) * 4);
  for (Index c = 0; c < cb.size(); ++c) corners.insert(corners.end(), cb.cell_nodes(c), cb.cell_nodes(c) + 4);
  for (const BoundaryFace& f : boundary_faces(corners)) {
    const Vec3 a = nodes.position_n(f.nodes[0]);
    const Vec3 area = 0.5 * (nodes.position_n(f.nodes[1]) - a).cross(nodes.position_n(f.nodes[2]) - a);  // outward
    const WallShares facing = facing_planes(walls, area);
    if (!quadratic) {
      for (const Index n : f.nodes) nodes.contact_share[n] += facing / 3.0;
      continue;
    }
    // The quadratic face: int N dA is 0 at the corners and A / 3 at each mid-edge node.
    const int* k = kTetFaces[f.local];
    for (int j = 0; j < 3; ++j) nodes.contact_share[cb.node(f.tet, tet10_mid_node(k[j], k[(j + 1) % 3]))] += facing / 3.0;
  }
}

}  // namespace

template <int D>
Vec<D> first_contact_point(const WallPlaneT<D>& p, const std::type_identity_t<Vec<D>>& x_n, const std::type_identity_t<Vec<D>>& x) {
  const double g_n = p.gap(x_n), g = p.gap(x);
  if (!(g_n > 0.0)) return x_n - g_n * p.normal;
  return x_n + (g_n / (g_n - g)) * (x - x_n);
}

template <int D>
NodeContactT<D> node_contact(const WallPlaneT<D>& p, double k, bool stick, bool held, const std::type_identity_t<Vec<D>>& held_point,
                             const std::type_identity_t<Vec<D>>& x_n, const std::type_identity_t<Vec<D>>& x) {
  using Matrix = Eigen::Matrix<double, D, D>;
  NodeContactT<D> c;
  // A node exactly on the wall is in contact too: its force is zero but its tangent holds a body that starts
  // resting on the wall (a static run would otherwise begin with a singular matrix).
  const double g = p.gap(x);
  if (!(g <= 0.0)) return c;
  const Matrix nn = p.normal * p.normal.transpose();
  c.penetration = -g;
  c.r = k * g * p.normal;
  c.K = k * nn;
  if (!stick) return c;
  const Matrix tt = Matrix::Identity() - nn;
  const double g_n = p.gap(x_n);
  if (held || !(g_n > 0.0)) {  // a fixed anchor
    c.r += k * tt * (x - (held ? held_point : first_contact_point(p, x_n, x)));
    c.K += k * tt;
    return c;
  }
  // Arriving in this step: x - c = phi (x - x_n) with phi = -g / (g_n - g), d phi / dx = -g_n / (g_n - g)^2 n^T.
  const Vec<D> dx = x - x_n;
  const double phi = -g / (g_n - g), dphi = -g_n / ((g_n - g) * (g_n - g));
  c.r += k * phi * (tt * dx);
  c.K += k * (phi * tt + (tt * dx) * (dphi * p.normal).transpose());
  return c;
}

template <int D>
void measure_contact_areas(const StepContext&, const WallsT<D>& walls, const std::vector<Cells>& cells, Nodes<D>& nodes) {
  std::fill(nodes.contact_share.begin(), nodes.contact_share.end(), WallShares::Zero());
  LOOM_ASSERT(Index(walls.planes.size()) <= kMaxWallPlanes, walls.planes.size() << " wall planes, at most " << kMaxWallPlanes);
  for (const Cells& cb : cells) measure_block(walls, cb, nodes);
}

template <int D>
void add_wall_contact(const WallsT<D>& walls, const std::vector<Index>& node_body, const Nodes<D>& nodes, bool tangent, LinearSystem& system) {
  const DofMap& dofs = system.dofs;
  double* values = system.pattern.matrix.valuePtr();
  for_each_index(nodes.size(), [&](Index i) {
    if (nodes.contact_share[i].isZero(0.0) || driven<D>(dofs, i)) return;
    const Vec<D> x = nodes.position(i);
    NodeContactT<D> sum;
    for (std::size_t p = 0; p < walls.planes.size(); ++p) {
      if (!walls.acts_on(walls.planes[p], node_body[std::size_t(i)])) continue;
      const NodeContactT<D> c = contact_of(walls, p, nodes, i, x);
      sum.r += c.r, sum.K += c.K;
    }
    if (sum.r.isZero(0.0) && sum.K.isZero(0.0)) return;
    Index eq[D];
    for (int d = 0; d < D; ++d) {
      const Index dof = dofs.dof(i, d);
      eq[d] = dofs.equation[std::size_t(dof)];
      system.residual_full[dof] += sum.r[d];
      if (eq[d] != kNoIndex) system.residual[eq[d]] += sum.r[d];
    }
    if (!tangent) return;
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) {
        if (eq[a] == kNoIndex || eq[b] == kNoIndex || sum.K(a, b) == 0.0) continue;
        const Index slot = a == b ? system.pattern.diagonal_slot[std::size_t(eq[a])] : find_slot(system.pattern, eq[a], eq[b]);
        values[slot] += sum.K(a, b);
      }
  });
}

template <int D>
void commit_wall_contact(const StepContext&, const WallsT<D>& walls, const std::vector<Index>& node_body, Nodes<D>& nodes) {
  for_each_index(nodes.size(), [&](Index i) {
    const Vec<D> x = nodes.position(i);
    bool touching = false;
    Vec<D> point = Vec<D>::Zero();
    for (const WallPlaneT<D>& p : walls.planes) {
      if (!walls.walls[std::size_t(p.wall)].stick || !walls.acts_on(p, node_body[std::size_t(i)]) || !(p.gap(x) <= 0.0)) continue;
      if (!touching) point = nodes.in_contact[i] != 0.0 ? Vec<D>(nodes.contact_point[i]) : first_contact_point<D>(p, nodes.position_n(i), x);
      touching = true;
    }
    nodes.in_contact[i] = touching ? 1.0 : 0.0;
    nodes.contact_point[i] = point;
  });
}

template <int D>
std::vector<WallResult> wall_results(const WallsT<D>& walls, const std::vector<Index>& node_body, const Nodes<D>& nodes, const DofMap& dofs) {
  std::vector<WallResult> results(walls.walls.size());
  std::vector<int> planes(walls.walls.size(), 0);
  for (const WallPlaneT<D>& p : walls.planes) ++planes[std::size_t(p.wall)], results[std::size_t(p.wall)].normal.template head<D>() = p.normal;
  for (std::size_t w = 0; w < results.size(); ++w)
    if (planes[w] != 1) results[w].normal.setZero();
  for (Index i = 0; i < nodes.size(); ++i) {  // serial: a sum in a fixed order
    if (driven<D>(dofs, i)) continue;
    const Vec<D> x = nodes.position_n(i);
    for (std::size_t q = 0; q < walls.planes.size(); ++q) {
      const WallPlaneT<D>& p = walls.planes[q];
      if (!walls.acts_on(p, node_body[std::size_t(i)])) continue;
      WallResult& r = results[std::size_t(p.wall)];
      r.penetration = std::max(r.penetration, -p.gap(x));
      if (!nodes.contact_share[i].isZero(0.0)) r.force.template head<D>() -= contact_of(walls, q, nodes, i, x).r;
    }
  }
  return results;
}

#define LOOM_WALL_CONTACT(D)                                                                                                               \
  template Vec<D> first_contact_point<D>(const WallPlaneT<D>&, const Vec<D>&, const Vec<D>&);                                            \
  template NodeContactT<D> node_contact<D>(const WallPlaneT<D>&, double, bool, bool, const Vec<D>&, const Vec<D>&, const Vec<D>&);       \
  template void measure_contact_areas<D>(const StepContext&, const WallsT<D>&, const std::vector<Cells>&, Nodes<D>&);                   \
  template void add_wall_contact<D>(const WallsT<D>&, const std::vector<Index>&, const Nodes<D>&, bool, LinearSystem&);                 \
  template void commit_wall_contact<D>(const StepContext&, const WallsT<D>&, const std::vector<Index>&, Nodes<D>&);                     \
  template std::vector<WallResult> wall_results<D>(const WallsT<D>&, const std::vector<Index>&, const Nodes<D>&, const DofMap&);
LOOM_WALL_CONTACT(2)
LOOM_WALL_CONTACT(3)
#undef LOOM_WALL_CONTACT

}  // namespace loom
