#include "systems/remesh/remesh_3d.hpp"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <Eigen/Geometry>
#include <Eigen/LU>  // determinant

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "engine/core/errors.hpp"
#include "engine/core/parallel.hpp"
#include "engine/mesh/tet_adjacency.hpp"
#include "engine/mesh/simplex_geometry.hpp"
#include "engine/mesh/tet_mesh.hpp"
#include "systems/remesh/delaunay_check.hpp"
#include "systems/remesh/point_in_tets.hpp"
#include "systems/remesh/surface_graph.hpp"
#include "systems/remesh/tet_flips.hpp"

namespace loom {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<Index, Kernel>;
// A cell's info: its index among the kept cells (kNoIndex: dropped), so that the kept cells' neighbours are read
// from the triangulation rather than found again.
using CellBase = CGAL::Triangulation_cell_base_with_info_3<Index, Kernel, CGAL::Delaunay_triangulation_cell_base_3<Kernel>>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase, CellBase, CGAL::Sequential_tag>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;
using Quad = std::array<Index, 4>;
using Triple = std::array<Index, 3>;

double volume_of(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) { return (b - a).cross(c - a).dot(d - a) / 6.0; }

Triple sorted_face(Index a, Index b, Index c) {
  Triple t{a, b, c};
  std::sort(t.begin(), t.end());
  return t;
}

// The distance from p to the triangle (a, b, c) (Ericson, Real-Time Collision Detection §5.1.5).
double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

// What R3.2 reads of the previous mesh.
struct Previous {
  std::optional<TetCellSet> cells;
  std::vector<std::array<Index, 4>> neighbours;  // tet_face_neighbours
  std::vector<Triple> surface_faces;  // sorted triples, sorted
  std::vector<std::vector<Index>> surface_at;  // per point: the previous surface faces (indices into `faces`) around it
  std::vector<Triple> faces;          // outward
  std::vector<char> on_surface;
};

Previous read_previous(Index n, const std::vector<Index>& tets, std::vector<std::array<Index, 4>> neighbours) {
  Previous p;
  p.cells.emplace(tets);
  p.neighbours = std::move(neighbours);
  for (const BoundaryFace& f : boundary_faces(tets, p.neighbours)) p.faces.push_back(f.nodes);
  p.on_surface.assign(std::size_t(n), 0);
  p.surface_at.assign(std::size_t(n), {});
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    p.surface_faces.push_back(sorted_face(p.faces[f][0], p.faces[f][1], p.faces[f][2]));
    for (Index v : p.faces[f]) p.on_surface[std::size_t(v)] = 1, p.surface_at[std::size_t(v)].push_back(Index(f));
  }
  std::sort(p.surface_faces.begin(), p.surface_faces.end());
  return p;
}

double circumradius(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double det = u.dot(v.cross(w));
  if (det == 0.0) return std::numeric_limits<double>::infinity();
  return ((u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) / (2.0 * det)).norm();
}

// The outcome of R3.2 for one cell.
enum class Verdict { keep, merge, tear, cap, drop };

struct Classifier {
  const std::vector<Vec3>& x;
  const Remesh3dSettings& settings;
  const std::vector<double>& average_distance;
  const Previous* previous = nullptr;
  const PointInTets* in_previous = nullptr;
  const SurfaceGraph* surface = nullptr;

  double l_char(const Index* v) const {
    if (!settings.local) return settings.l_char;
    return (average_distance[std::size_t(v[0])] + average_distance[std::size_t(v[1])] + average_distance[std::size_t(v[2])] +
            average_distance[std::size_t(v[3])]) / 4.0;
  }

  // Round-off flat: a cell of four (nearly) coplanar points, which CGAL's exact predicates make a cell of.
  bool flat(const Index* v) const {
    const Vec3 &a = x[std::size_t(v[0])], &b = x[std::size_t(v[1])], &c = x[std::size_t(v[2])], &d = x[std::size_t(v[3])];
    double longest = 0.0, largest_face = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) longest = std::max(longest, (x[std::size_t(v[i])] - x[std::size_t(v[j])]).norm());
    for (const auto& f : kTetFaces) {
      const Vec3 &p = x[std::size_t(v[f[0]])], &q = x[std::size_t(v[f[1]])], &r = x[std::size_t(v[f[2]])];
      largest_face = std::max(largest_face, 0.5 * (q - p).cross(r - p).norm());
    }
    return 3.0 * std::abs(volume_of(a, b, c, d)) <= 1e-9 * longest * largest_face;
  }

  // Deep enough below the previous surface to be material: a tenth of the cell's smallest altitude. A flat cell
  // is material when its centroid lies off the planes of its corners' surface faces (it joins two quadrilaterals cut
  // the other way inside the body, and the flips remove it); in one of those planes it is a cap of a face whose
  // points round-off has made slightly concave (it may span the face, far from its corners' faces).
  bool below_surface(const Index* v, const Vec3& centroid, double volume, bool is_flat) const {
    double depth = std::numeric_limits<double>::infinity(), plane_depth = depth, largest_face = 0.0, longest = 0.0;
    for (int k = 0; k < 4; ++k) {
      for (Index f : previous->surface_at[std::size_t(v[k])]) {
        const Triple& s = previous->faces[std::size_t(f)];
        const Vec3 &p = x[std::size_t(s[0])], &q = x[std::size_t(s[1])], &r = x[std::size_t(s[2])];
        depth = std::min(depth, distance_to_triangle(centroid, p, q, r));
        plane_depth = std::min(plane_depth, std::abs((q - p).cross(r - p).normalized().dot(centroid - p)));
      }
      const Vec3 &a = x[std::size_t(v[kTetFaces[k][0]])], &b = x[std::size_t(v[kTetFaces[k][1]])], &c = x[std::size_t(v[kTetFaces[k][2]])];
      largest_face = std::max(largest_face, 0.5 * (b - a).cross(c - a).norm());
      for (int j = k + 1; j < 4; ++j) longest = std::max(longest, (x[std::size_t(v[k])] - x[std::size_t(v[j])]).norm());
    }
    if (is_flat) return plane_depth > 1e-9 * longest;
    return depth >= 0.1 * (3.0 * volume / largest_face);
  }

  // `outside`: whether the cell holds no material (not a previous cell, and its centroid outside the previous mesh);
  // v is positively oriented, in canonical_tet's order (so that nothing here depends on how the triangulation
  // stores the cell).
  Verdict operator()(const Index* v, bool& outside) const {
    const Vec3 &a = x[std::size_t(v[0])], &b = x[std::size_t(v[1])], &c = x[std::size_t(v[2])], &d = x[std::size_t(v[3])];
    const double alpha_l = settings.alpha * l_char(v);
    const bool passes = !(alpha_l < circumradius(a, b, c, d));  // eq 16
    outside = false;
    if (!previous) return passes ? Verdict::keep : Verdict::drop;
    bool inside = previous->cells->contains(v);
    const bool is_flat = flat(v);
    bool capped = false;
    if (!inside) {
      const Vec3 centroid = (a + b + c + d) / 4.0;
      inside = in_previous->contains_near(centroid, v[0]);
      outside = !inside;
      const bool all_on_surface = previous->on_surface[std::size_t(v[0])] && previous->on_surface[std::size_t(v[1])] &&
                                  previous->on_surface[std::size_t(v[2])] && previous->on_surface[std::size_t(v[3])];
      if (inside && all_on_surface && !below_surface(v, centroid, std::abs(volume_of(a, b, c, d)), is_flat)) inside = false, capped = true;
    }
    if (inside && is_flat) return Verdict::keep;  // its circumsphere means nothing; the flips remove it
    double longest = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) longest = std::max(longest, (x[std::size_t(v[i])] - x[std::size_t(v[j])]).norm());
    if (inside) {
      if (passes) return Verdict::keep;
      // A cell on the surface may fail eq 16 by being flat (a large circumsphere over short edges): it stays unless
      // an edge is longer than alpha l_char too, as across an opening (the spec keeps every surface cell, so a
      // body pulled apart would stay joined by its skin).
      if (longest <= alpha_l)
        for (const auto& f : kTetFaces)
          if (std::binary_search(previous->surface_faces.begin(), previous->surface_faces.end(), sorted_face(v[f[0]], v[f[1]], v[f[2]])))
            return Verdict::keep;
      return Verdict::tear;
    }
    // Outside: two surfaces closer than the mesh join, a void of the body the size of a cell fills.
    // Short edges or a small circumsphere: a cell that reaches into a previous cell's corner region across a narrow
    // gap may have a face diagonal of the lattice as an edge (longer than alpha l_char) and still a small sphere.
    if (passes || longest <= alpha_l) {
      const Index corners[4] = {v[0], v[1], v[2], v[3]};
      bool in_void = true;
      for (Index k : corners) in_void = in_void && surface->on_surface(k) && surface->inner(surface->component(k));
      if (in_void || joins_two_surfaces(*surface, x, corners)) return Verdict::merge;
    }
    return capped ? Verdict::cap : Verdict::drop;
  }
};

// The result's volume, slivers and isolated points.
void finish(const std::vector<Vec3>& x, Remesh3dResult& out) {
  std::vector<char> used(x.size(), 0);
  out.volume = 0.0, out.slivers = 0;
  for (std::size_t t = 0; t + 3 < out.tets.size(); t += 4) {
    const Vec3 &a = x[std::size_t(out.tets[t])], &b = x[std::size_t(out.tets[t + 1])], &c = x[std::size_t(out.tets[t + 2])],
               &d = x[std::size_t(out.tets[t + 3])];
    out.volume += volume_of(a, b, c, d);
    out.slivers += tet_quality(a, b, c, d) < 0.1;
    for (std::size_t k = 0; k < 4; ++k) used[std::size_t(out.tets[t + k])] = 1;
  }
  out.isolated = Index(std::count(used.begin(), used.end(), 0));
}

// The cells R3.2 keeps, with their face neighbours among them (kNoIndex: a dropped or infinite cell across).
struct Kept {
  std::vector<Index> tets;                       // positively oriented
  std::vector<char> outside;                     // per cell: it holds no material
  std::vector<std::array<Index, 4>> neighbours;  // across the face opposite each corner
};

// det [x1 - x0, x2 - x0, x3 - x0] in the corners' order, computed as the elements compute it (tet4_gradients).
double jacobian(const Quad& q, const std::vector<Vec3>& x) {
  Mat3 J;
  for (int j = 0; j < 3; ++j) J.col(j) = x[std::size_t(q[std::size_t(j + 1)])] - x[std::size_t(q[0])];
  return J.determinant();
}

// A cell's corners in canonical_tet's order, in the orientation whose Jacobian, computed as the elements will, is
// positive (a cell flat to round-off may be positive in floating point one way only; if neither, CGAL's exact
// orientation). Neither choice depends on the order in which the triangulation stores the cell's vertices, so
// nothing computed from the corners does.
Quad canonical_corners(const Index* stored, const std::vector<Vec3>& x) {
  Quad s{stored[0], stored[1], stored[2], stored[3]};
  std::sort(s.begin(), s.end());
  const Quad even = canonical_tet(s), odd = canonical_tet({s[0], s[1], s[3], s[2]});
  if (jacobian(even, x) > 0.0) return even;
  if (jacobian(odd, x) > 0.0) return odd;
  auto point = [&](Index v) { return Kernel::Point_3(x[std::size_t(v)].x(), x[std::size_t(v)].y(), x[std::size_t(v)].z()); };
  return CGAL::orientation(point(s[0]), point(s[1]), point(s[2]), point(s[3])) == CGAL::POSITIVE ? even : odd;
}

// R3.2 over the finite cells of dt (classified in parallel: each cell's verdict is its own); counts the verdicts
// into out. `first_mesh`: no previous mesh. What follows depends on the kept cells as a set only (the flips, R3.5's
// order), not on the order the triangulation stores them in.
Kept keep_cells(Delaunay& dt, const std::vector<Vec3>& x, const Classifier& classify, bool first_mesh, Remesh3dResult& out) {
  using Cell = Delaunay::Cell_handle;
  std::vector<Cell> cells;
  cells.reserve(dt.number_of_finite_cells());
  for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) c->info() = kNoIndex;
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) cells.push_back(c);
  std::vector<Quad> corners(cells.size());
  std::vector<Verdict> verdicts(cells.size());
  std::vector<char> outside(cells.size());
  for_each_index(Index(cells.size()), [&](Index i) {
    const Cell c = cells[std::size_t(i)];
    const Index stored[4] = {c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(), c->vertex(3)->info()};
    corners[std::size_t(i)] = canonical_corners(stored, x);
    bool out_of_body = false;
    verdicts[std::size_t(i)] = classify(corners[std::size_t(i)].data(), out_of_body);
    outside[std::size_t(i)] = out_of_body;
  });
  Kept kept;
  std::vector<std::size_t> kept_cells;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const Verdict verdict = verdicts[i];
    if (verdict == Verdict::keep || verdict == Verdict::merge) {
      cells[i]->info() = Index(kept_cells.size());
      kept_cells.push_back(i);
      kept.tets.insert(kept.tets.end(), corners[i].begin(), corners[i].end()), kept.outside.push_back(outside[i]);
    }
    out.merged += verdict == Verdict::merge;
    out.rejected += verdict == Verdict::tear || (verdict == Verdict::drop && first_mesh);
    out.capped += verdict == Verdict::cap;
  }
  // The face opposite kept corner k is the one opposite the same vertex in the triangulation's cell.
  kept.neighbours.resize(kept_cells.size());
  for (std::size_t t = 0; t < kept_cells.size(); ++t) {
    const Cell c = cells[kept_cells[t]];
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k)
        if (c->vertex(k)->info() == kept.tets[4 * t + std::size_t(j)]) kept.neighbours[t][std::size_t(j)] = c->neighbor(k)->info();
  }
  return kept;
}

// R3.5: cells in the order of their sorted corners, each with its corners in canonical_tet's order; and R3.6's
// surface in boundary_faces' order (ascending cell, local face), read from the neighbours.
void write_sorted(const Kept& kept, Remesh3dResult& out) {
  const std::vector<Index> order = tet_sorted_order(kept.tets);
  std::vector<Index> position(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) position[std::size_t(order[i])] = Index(i);
  out.tets.reserve(kept.tets.size());
  out.merged_cell.reserve(order.size());
  out.neighbours.resize(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::size_t t = std::size_t(order[i]);
    const Index* v = &kept.tets[4 * t];
    const Quad q = canonical_tet({v[0], v[1], v[2], v[3]});
    out.tets.insert(out.tets.end(), q.begin(), q.end());
    out.merged_cell.push_back(kept.outside[t]);
    for (int j = 0; j < 4; ++j) {
      const Index across = kept.neighbours[t][std::size_t(std::find(v, v + 4, q[std::size_t(j)]) - v)];
      out.neighbours[i][std::size_t(j)] = across == kNoIndex ? kNoIndex : position[std::size_t(across)];
      if (across == kNoIndex)
        out.surface.push_back({q[std::size_t(kTetFaces[j][0])], q[std::size_t(kTetFaces[j][1])], q[std::size_t(kTetFaces[j][2])]});
    }
  }
}

// R3.7 and R3.8: true when `out` holds the previous mesh as it is, or repaired by flips.
bool keep_or_repair(const std::vector<Vec3>& x, const std::vector<Index>& previous_tets, std::vector<std::array<Index, 4>>& neighbours,
                    const Remesh3dSettings& settings, const std::vector<double>& average_distance, Remesh3dResult& out) {
  const std::vector<double> no_distances;
  const std::vector<double>& distances = settings.local ? average_distance : no_distances;
  auto keep = [&](std::vector<Index> tets, std::vector<std::array<Index, 4>> nbr) {
    out.tets = std::move(tets);
    out.merged_cell.assign(out.tets.size() / 4, 0);
    out.kept_previous = true;
    out.neighbours = std::move(nbr);
    for (const BoundaryFace& f : boundary_faces(out.tets, out.neighbours)) out.surface.push_back(f.nodes);
    finish(x, out);
    return true;
  };
  const bool delaunay = faces_delaunay(x, previous_tets, neighbours);
  if (!delaunay && !settings.repair) return false;
  if (!no_merge_possible(x, previous_tets, neighbours, settings.alpha, distances, settings.l_char)) return false;
  if (delaunay) return no_tear(x, previous_tets, neighbours, settings.alpha, distances, settings.l_char) && keep(previous_tets, neighbours);
  std::vector<Index> tets = previous_tets;
  std::vector<std::array<Index, 4>> nbr = neighbours;
  FlipSettings slivers;
  slivers.threshold = settings.flip_quality;  // 0: no sliver pass, and no flip is refused for the quality it makes
  const DelaunayRepairStats repair = repair_delaunay(x, tets, slivers, &nbr);
  if (repair.stuck > 0 || !no_tear(x, tets, nbr, settings.alpha, distances, settings.l_char)) return false;
  if (repair.flips == 0) return keep(previous_tets, neighbours);
  const Kept kept{std::move(tets), std::vector<char>(nbr.size(), 0), std::move(nbr)};
  out.flipped = repair.slivers.flips23 + repair.slivers.flips32 + repair.slivers.edge_removals;
  out.repaired = repair.flips;
  write_sorted(kept, out);  // R3.5
  finish(x, out);            // R3.6
  return true;
}

}  // namespace

std::array<Index, 4> canonical_tet(const std::array<Index, 4>& v) {
  // Even permutations bringing corner k first: identity, (1 0 3 2), (2 3 0 1), (3 2 1 0).
  static constexpr int kFirst[4][4] = {{0, 1, 2, 3}, {1, 0, 3, 2}, {2, 3, 0, 1}, {3, 2, 1, 0}};
  const int m = int(std::min_element(v.begin(), v.end()) - v.begin());
  const Index a = v[std::size_t(kFirst[m][0])];
  Index rest[3] = {v[std::size_t(kFirst[m][1])], v[std::size_t(kFirst[m][2])], v[std::size_t(kFirst[m][3])]};
  const int r = int(std::min_element(rest, rest + 3) - rest);  // a 3-cycle of the other three is even too
  return {a, rest[r], rest[(r + 1) % 3], rest[(r + 2) % 3]};
}

std::vector<std::array<Index, 3>> surface_of(const std::vector<Index>& tets) {
  std::vector<std::array<Index, 3>> out;
  for (const BoundaryFace& f : boundary_faces(tets)) out.push_back(f.nodes);
  return out;
}

void average_neighbour_distance_3d(const std::vector<Vec3>& positions, const std::vector<Index>& tets, std::vector<double>& average_distance) {
  std::vector<double> sum(positions.size(), 0.0);
  std::vector<int> count(positions.size(), 0);
  for (const auto& [a, b] : tet_edges(tets)) {
    const double l = (positions[std::size_t(a)] - positions[std::size_t(b)]).norm();
    sum[std::size_t(a)] += l, sum[std::size_t(b)] += l, ++count[std::size_t(a)], ++count[std::size_t(b)];
  }
  average_distance.assign(positions.size(), 0.0);
  for (std::size_t i = 0; i < positions.size(); ++i)
    if (count[i] > 0) average_distance[i] = sum[i] / count[i];
}

void remesh_points_3d(const std::vector<Vec3>& positions, const std::vector<Index>& previous_tets, const Remesh3dSettings& settings,
                      const std::vector<double>& average_distance, Remesh3dResult& out,
                      const std::vector<std::array<Index, 4>>* previous_neighbours) {
  out = Remesh3dResult{};
  const Index n = Index(positions.size());
  std::vector<std::array<Index, 4>> neighbours;
  if (!previous_tets.empty())
    neighbours = previous_neighbours && previous_neighbours->size() == previous_tets.size() / 4 ? *previous_neighbours : tet_face_neighbours(previous_tets);
  if (settings.keep_delaunay && !previous_tets.empty() && keep_or_repair(positions, previous_tets, neighbours, settings, average_distance, out))
    return;
  // R3.2's view of the previous mesh
  std::optional<Previous> previous;
  std::optional<PointInTets> in_previous;
  std::optional<SurfaceGraph> surface;
  if (!previous_tets.empty()) {
    previous = read_previous(n, previous_tets, std::move(neighbours));
    in_previous.emplace(positions, previous_tets, &previous->neighbours);
    surface.emplace(n, previous->faces, positions);
  }
  const Classifier classify{positions, settings, average_distance, previous ? &*previous : nullptr, in_previous ? &*in_previous : nullptr,
                            surface ? &*surface : nullptr};
  // R3.1 and R3.2
  std::vector<std::pair<Kernel::Point_3, Index>> points;
  points.reserve(positions.size());
  for (Index i = 0; i < n; ++i) points.emplace_back(Kernel::Point_3(positions[std::size_t(i)].x(), positions[std::size_t(i)].y(), positions[std::size_t(i)].z()), i);
  // One thread: CGAL's concurrent insertion (Parallel_tag) was 1.2-1.5 times faster on two quiet cores (a tenth of a
  // remesh step) but 1.6 times slower with the other core busy, its threads spinning on locks (perf/README.md).
  Delaunay dt(points.begin(), points.end());
  LOOM_CHECK(Index(dt.number_of_vertices()) == n, RunError,
             "remesh: " << n - Index(dt.number_of_vertices()) << " points coincide with others (the body has collapsed)");
  Kept kept = keep_cells(dt, positions, classify, !previous, out);
  // R3.4
  if (settings.flip_quality > 0.0) {
    FlipSettings flips;
    flips.threshold = settings.flip_quality;
    std::vector<Index> origin;
    const std::vector<Index> before = kept.tets;
    const FlipStats s = improve_by_flips(positions, kept.tets, flips, &origin, &kept.neighbours);
    out.flipped = s.flips23 + s.flips32 + s.edge_removals;
    // A flip re-divides the region of the cells it replaces: a cell it made held no material where it lies (its
    // centroid) in a replaced cell that held none. (Not wherever its centroid lies outside the previous mesh: the
    // successors of material cells at a concave surface may poke out of it, and were counted as new material.)
    std::vector<char> survived(kept.outside.size(), 0);
    for (Index o : origin)
      if (o != kNoIndex) survived[std::size_t(o)] = 1;
    std::vector<const Index*> replaced_outside;
    for (std::size_t t = 0; t < survived.size(); ++t)
      if (!survived[t] && kept.outside[t]) replaced_outside.push_back(&before[4 * t]);
    const auto x = [&](Index i) { return positions[std::size_t(i)]; };
    std::vector<char> flipped_outside(origin.size());
    for (std::size_t t = 0; t < origin.size(); ++t) {
      if (origin[t] != kNoIndex) {
        flipped_outside[t] = kept.outside[std::size_t(origin[t])];
        continue;
      }
      const Vec3 centroid = simplex_centroid<3>(&kept.tets[4 * t], x);
      for (const Index* r : replaced_outside) flipped_outside[t] = flipped_outside[t] || simplex_contains<3>(r, x, centroid, 1e-12);
    }
    kept.outside = std::move(flipped_outside);
  }
  write_sorted(kept, out);  // R3.5
  finish(positions, out);  // R3.6
}

}  // namespace loom
