#include "engine/methods/pfem/particle_insertion_3d.hpp"

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

#include "engine/core/errors.hpp"
#include "engine/mesh/tet_adjacency.hpp"
#include "engine/mesh/tet_mesh.hpp"

namespace loom {
namespace {

using NodePair = std::pair<Index, Index>;

constexpr int kTetEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

// Per particle, 1 if its motion or load is prescribed: a Dirichlet dof or a corner of a dead-load face.
std::vector<char> fixed_particles_3d(const PfemTopology3d& topo, const FemModelT<3>& m) {
  std::vector<char> fixed(std::size_t(topo.n_points), 0);
  auto mark = [&](Index i) {
    if (i >= 0 && i < topo.n_points) fixed[std::size_t(i)] = 1;
  };
  for (const auto& p : m.bc.prescribed) mark(p.node);
  for (const TractionFace& f : topo.tractions) mark(f.nodes[0]), mark(f.nodes[1]), mark(f.nodes[2]);
  return fixed;
}

// The edges to split in one body: longer than `longest_allowed` at x_n, no end fixed, at most one per tetrahedron
// (longest first; ties by the sorted ends, so that the choice does not depend on the order of the cells).
std::vector<NodePair> edges_to_split(const std::vector<Index>& tets, const Nodes<3>& nodes, const std::vector<char>& fixed, double longest_allowed) {
  std::map<NodePair, std::vector<Index>> cells_of;
  for (std::size_t t = 0; t + 3 < tets.size(); t += 4)
    for (const auto& e : kTetEdges) {
      const Index a = tets[t + std::size_t(e[0])], b = tets[t + std::size_t(e[1])];
      cells_of[{std::min(a, b), std::max(a, b)}].push_back(Index(t / 4));
    }
  std::vector<std::pair<double, NodePair>> long_edges;
  for (const auto& [e, cells] : cells_of) {
    if (fixed[std::size_t(e.first)] || fixed[std::size_t(e.second)]) continue;
    const double length = (nodes.position_n(e.first) - nodes.position_n(e.second)).norm();
    if (length > longest_allowed) long_edges.push_back({length, e});
  }
  std::sort(long_edges.begin(), long_edges.end(), [](const auto& p, const auto& q) { return p.first > q.first || (p.first == q.first && p.second < q.second); });
  std::vector<char> cut(tets.size() / 4, 0);
  std::vector<NodePair> chosen;
  for (const auto& [length, e] : long_edges) {
    const std::vector<Index>& cells = cells_of.at(e);
    if (std::any_of(cells.begin(), cells.end(), [&](Index c) { return cut[std::size_t(c)]; })) continue;
    for (Index c : cells) cut[std::size_t(c)] = 1;
    chosen.push_back(e);
  }
  return chosen;
}

// Every cell (N = 4 corners) or surface face (N = 3) with a split edge becomes two: one with the edge's second end
// replaced by its midpoint, one with the first (replacing a corner by a point of an edge towards the other end keeps
// the orientation). A cell or face has at most one split edge: its tetrahedron is cut at most once.
template <int N>
void split_cells(const std::map<NodePair, Index>& mid_of, std::vector<Index>& cells) {
  const std::size_t n = cells.size();
  for (std::size_t t = 0; t + N - 1 < n; t += N)
    for (int i = 0; i < N; ++i)
      for (int j = i + 1; j < N; ++j) {
        const Index a = cells[t + std::size_t(i)], b = cells[t + std::size_t(j)];
        const auto it = mid_of.find({std::min(a, b), std::max(a, b)});
        if (it == mid_of.end()) continue;
        std::vector<Index> other(cells.begin() + std::ptrdiff_t(t), cells.begin() + std::ptrdiff_t(t + N));
        other[std::size_t(i)] = it->second;
        cells[t + std::size_t(j)] = it->second;
        cells.insert(cells.end(), other.begin(), other.end());
        i = j = N;  // one split edge per cell
      }
}

}  // namespace

std::vector<double> initial_spacing_3d(const PfemTopology3d& topo, const Nodes<3>& nodes) {
  std::vector<double> h0(topo.tets.size(), 0.0);
  for (std::size_t b = 0; b < topo.tets.size(); ++b) {
    double sum = 0.0;
    const auto& t = topo.tets[b];
    for (std::size_t k = 0; k + 3 < t.size(); k += 4)
      for (const auto& e : kTetEdges) sum += (nodes.X[t[k + std::size_t(e[0])]] - nodes.X[t[k + std::size_t(e[1])]]).norm();
    h0[b] = t.empty() ? 0.0 : sum / (1.5 * double(t.size()));  // six edges per four corners
  }
  return h0;
}

Index insert_particles_3d(double insert_above, PfemTopology3d& topo, FemModelT<3>& m) {
  LOOM_ASSERT(m.nodes.size() == topo.n_points, "particle insertion in 3D takes linear cells (no mid-nodes)");
  const std::vector<char> fixed = fixed_particles_3d(topo, m);
  Index inserted = 0;
  for (std::size_t b = 0; b < topo.tets.size(); ++b) {
    const std::vector<NodePair> split = edges_to_split(topo.tets[b], m.nodes, fixed, insert_above * topo.spacing[b]);
    std::map<NodePair, Index> mid_of;
    for (const NodePair& e : split) {
      const Index mid = m.nodes.size();
      mid_of[e] = mid;
      m.nodes.resize(mid + 1);
      m.nodes.for_each_column([&](const char*, auto& col) {
        if (col.used()) col[mid] = 0.5 * (col[e.first] + col[e.second]);
      });
      if (m.nodes.lumped_mass.used()) m.nodes.lumped_mass[mid] = 0.0;  // the remesh shares the split cells' mass out
      if (m.nodes.in_contact.used()) {  // held by a stick wall where both ends are, at the mean of their anchors
        const bool both = m.nodes.in_contact[e.first] != 0.0 && m.nodes.in_contact[e.second] != 0.0;
        m.nodes.in_contact[mid] = both ? 1.0 : 0.0;
        if (!both) m.nodes.contact_point[mid] = Vec3::Zero();
      }
      m.node_body.push_back(Index(b));
      topo.points_of_body[b].push_back(mid);
      ++topo.n_points, ++inserted;
    }
    if (split.empty()) continue;
    split_cells<4>(mid_of, topo.tets[b]);
    std::vector<Index> faces;
    for (const auto& f : topo.surface[b]) faces.insert(faces.end(), f.begin(), f.end());
    split_cells<3>(mid_of, faces);
    topo.surface[b].clear();
    for (std::size_t k = 0; k + 2 < faces.size(); k += 3) topo.surface[b].push_back({faces[k], faces[k + 1], faces[k + 2]});
    topo.neighbours[b] = tet_face_neighbours(topo.tets[b]);
  }
  return inserted;
}

}  // namespace loom
