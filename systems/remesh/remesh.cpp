#include "systems/remesh/remesh.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include "engine/core/errors.hpp"
#include "engine/mesh/boundary_edges.hpp"
#include "systems/remesh/boundary_crossings.hpp"
#include "systems/remesh/boundary_loops.hpp"
#include "systems/remesh/point_in_mesh.hpp"

namespace loom {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<Index, Kernel>;
// Face info: the nesting level of the free-surface flood fill (-1: not reached).
using FaceBase = CGAL::Triangulation_face_base_with_info_2<int, Kernel, CGAL::Constrained_triangulation_face_base_2<Kernel>>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Exact_predicates_tag: constraints that cross would be split, not rejected (loom leaves crossing edges out).
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;

double circumradius(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double ab = (b - a).norm(), bc = (c - b).norm(), ca = (a - c).norm();
  const double twice_area = std::abs((b - a).x() * (c - a).y() - (c - a).x() * (b - a).y());
  return twice_area > 0.0 ? ab * bc * ca / (2.0 * twice_area) : std::numeric_limits<double>::infinity();
}

// The centre of the circle through a, b, c (not collinear).
Vec2 circumcentre(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 u = b - a, v = c - a;
  const double d = 2.0 * (u.x() * v.y() - u.y() * v.x());
  return a + Vec2(v.y() * u.squaredNorm() - u.y() * v.squaredNorm(), u.x() * v.squaredNorm() - v.x() * u.squaredNorm()) / d;
}

// Nesting levels by flood fill from the infinite face: crossing a constrained edge goes one level deeper, so the
// faces inside a closed polygon (and not inside a hole of it) have odd levels.
void mark_nesting_levels(Cdt& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  std::vector<Cdt::Edge> border;
  auto fill = [&](Cdt::Face_handle start, int level) {
    std::vector<Cdt::Face_handle> stack{start};
    while (!stack.empty()) {
      const Cdt::Face_handle f = stack.back();
      stack.pop_back();
      if (f->info() != -1) continue;
      f->info() = level;
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle n = f->neighbor(i);
        if (n->info() != -1) continue;
        if (cdt.is_constrained(Cdt::Edge(f, i))) border.emplace_back(f, i);
        else stack.push_back(n);
      }
    }
  };
  fill(cdt.infinite_face(), 0);
  while (!border.empty()) {
    const Cdt::Edge e = border.back();
    border.pop_back();
    const Cdt::Face_handle n = e.first->neighbor(e.second);
    if (n->info() == -1) fill(n, e.first->info() + 1);
  }
}

}  // namespace

void remesh_points(const std::vector<Vec2>& positions, const std::vector<Edge>& constraints,
                   const std::vector<Index>& previous_triangles, const RemeshSettings& settings,
                   const std::vector<double>& average_distance, RemeshResult& out) {
  const Index n = Index(positions.size());
  std::vector<std::pair<Kernel::Point_2, Index>> points;
  points.reserve(positions.size());
  for (Index i = 0; i < n; ++i) points.emplace_back(Kernel::Point_2(positions[std::size_t(i)].x(), positions[std::size_t(i)].y()), i);
  Cdt cdt;
  cdt.insert(points.begin(), points.end());  // spatially sorted insertion
  LOOM_CHECK(Index(cdt.number_of_vertices()) == n, RunError,
             "remesh: " << n - Index(cdt.number_of_vertices()) << " points coincide with others (the body has collapsed)");
  std::vector<Cdt::Vertex_handle> vertex(static_cast<std::size_t>(n));
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) vertex[std::size_t(v->info())] = v;
  const std::vector<char> crossing = crossing_edges(positions, constraints);
  out.crossings = Index(std::count(crossing.begin(), crossing.end(), 1));
  for (std::size_t k = 0; k < constraints.size(); ++k)
    if (!crossing[k]) cdt.insert_constraint(vertex[std::size_t(constraints[k][0])], vertex[std::size_t(constraints[k][1])]);
  // A constraint through a point splits at it; only crossing constraints create vertices, and they are left out.
  LOOM_CHECK(Index(cdt.number_of_vertices()) == n, RunError,
             "remesh: the previous boundary polygon intersects itself (" << Index(cdt.number_of_vertices()) - n << " crossings)");

  const bool constrained = settings.surface == SurfaceMode::constrained;
  // Which faces lie inside the previous boundary: the constrained mode's rule, and in both modes what tells a face
  // that holds material from one that fills a gap (merged_face). Needs the previous boundary (or mesh).
  const bool classify = constrained || !previous_triangles.empty();
  BoundaryLoops loops;
  std::optional<PointInMesh> previous;
  if (classify) {
    if (out.crossings == 0) mark_nesting_levels(cdt);
    else previous.emplace(positions, previous_triangles);
  }
  if (constrained) loops = boundary_loops(n, constraints, &positions);
  // Two corners on different loops (or on none: a point that has left the body), or far apart along one.
  auto joins_two_surfaces = [&](const Index t[3]) {
    for (int i = 0; i < 3; ++i) {
      const Index a = t[i], b = t[(i + 1) % 3];
      const Index d = steps_along(loops, a, b);
      if (d == kNoIndex) return true;
      if (d >= kMergeSteps && length_along(loops, a, b) >= kMergeDetour * (positions[std::size_t(a)] - positions[std::size_t(b)]).norm()) return true;
    }
    return false;
  };

  out.triangles.clear();
  out.merged_face.clear();
  out.rejected = 0, out.merged = 0;
  out.area = 0.0;
  std::vector<char> used(std::size_t(n), 0);
  std::vector<Cdt::Face_handle> kept;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    const Index t[3] = {f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};  // CGAL: counter-clockwise
    const Vec2 &a = positions[std::size_t(t[0])], &b = positions[std::size_t(t[1])], &c = positions[std::size_t(t[2])];
    double l_char = settings.l_char;
    if (settings.local)
      l_char = (average_distance[std::size_t(t[0])] + average_distance[std::size_t(t[1])] + average_distance[std::size_t(t[2])]) / 3.0;
    const double radius = circumradius(a, b, c);
    bool passes = !(settings.alpha * l_char < radius);  // eq 16
    if (!passes && settings.spacing_at && std::isfinite(radius))
      passes = !(settings.alpha * settings.spacing_at(circumcentre(a, b, c)) < radius);
    const bool inside = !classify || (previous ? previous->contains((a + b + c) / 3.0) : f->info() % 2 == 1);
    bool merged = !inside;
    if (constrained) {
      if (inside && !passes && !f->is_constrained(0) && !f->is_constrained(1) && !f->is_constrained(2)) {
        ++out.rejected;  // the body opens inside
        continue;
      }
      if (!inside) {
        // Two surfaces close a gap when it is narrower than the mesh: every edge of the face within alpha l_char
        // (two rows of points h apart join when the gap is below about 0.9 h at alpha = 1.3). Not the
        // circumradius: in a slit that narrows the faces across it are slivers whose circumradius grows as the gap
        // closes, so the surfaces would pass through each other unmerged. The gap's area becomes material.
        // A face in a hole of the body (an enclosed void: nesting level 2, 4, ...) fills it whatever the distances
        // along its loop: a void the size of a cell has too few boundary edges to tell two surfaces apart.
        const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
        const bool in_hole = !previous && f->info() > 0;
        if (!(longest <= settings.alpha * l_char) || !(in_hole || joins_two_surfaces(t))) continue;
        ++out.merged;
      }
    } else if (!passes) {  // eq 16: reject T
      ++out.rejected;
      continue;
    }
    out.merged_face.push_back(merged ? 1 : 0);
    out.triangles.insert(out.triangles.end(), {t[0], t[1], t[2]});
    kept.push_back(f);
    for (Index k : t) used[std::size_t(k)] = 1;
    out.area += 0.5 * ((b - a).x() * (c - a).y() - (c - a).x() * (b - a).y());
  }
  out.isolated = Index(std::count(used.begin(), used.end(), 0));
  // The outline: the sides of kept faces whose neighbour across was not kept, by face and side, which is
  // boundary_of(out.triangles) without searching for the pairs (CGAL's faces know their neighbours).
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = 0;
  for (const Cdt::Face_handle& f : kept) f->info() = 1;
  out.boundary.clear();
  for (const Cdt::Face_handle& f : kept)
    for (int side = 0; side < 3; ++side)  // corners (side, side + 1), opposite corner side + 2
      if (f->neighbor((side + 2) % 3)->info() != 1) out.boundary.push_back({f->vertex(side)->info(), f->vertex((side + 1) % 3)->info()});
}

void average_neighbour_distance(const std::vector<Vec2>& positions, const std::vector<Index>& triangles,
                                std::vector<double>& average_distance) {
  // Each node's neighbours bucketed (a counting sort, linear), then summed in ascending order of the
  // neighbour: the order in which a sort of all edges by their node pair visited them.
  const std::size_t n = positions.size();
  std::vector<Index> first(n + 1, 0);
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3)
    for (int s = 0; s < 3; ++s) ++first[std::size_t(triangles[t + std::size_t(s)]) + 1], ++first[std::size_t(triangles[t + std::size_t((s + 1) % 3)]) + 1];
  for (std::size_t i = 0; i < n; ++i) first[i + 1] += first[i];
  std::vector<Index> neighbour(static_cast<std::size_t>(first[n]));
  {
    std::vector<Index> cursor(first.begin(), first.end() - 1);
    for (std::size_t t = 0; t + 2 < triangles.size(); t += 3)
      for (int s = 0; s < 3; ++s) {
        const Index a = triangles[t + std::size_t(s)], b = triangles[t + std::size_t((s + 1) % 3)];
        neighbour[std::size_t(cursor[std::size_t(a)]++)] = b, neighbour[std::size_t(cursor[std::size_t(b)]++)] = a;
      }
  }
  average_distance.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto begin = neighbour.begin() + first[i], end = neighbour.begin() + first[i + 1];
    std::sort(begin, end);
    const auto last = std::unique(begin, end);
    double sum = 0.0;
    for (auto j = begin; j != last; ++j) {
      const std::size_t a = std::min(i, std::size_t(*j)), b = std::max(i, std::size_t(*j));
      sum += (positions[a] - positions[b]).norm();
    }
    if (last != begin) average_distance[i] = sum / int(last - begin);
  }
}

std::vector<Edge> boundary_of(const std::vector<Index>& triangles) {
  std::vector<Edge> out;
  for (const auto& e : boundary_edges(triangles, 3)) out.push_back({e.a, e.b});
  return out;
}

}  // namespace loom
