#include "engine/mesh/generators.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "engine/core/errors.hpp"
#include "engine/mesh/boundary_edges.hpp"

namespace loom {
namespace {

// In-circle determinant of d against the counter-clockwise triangle (a, b, c): positive inside.
double incircle(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const Vec2 ad = a - d, bd = b - d, cd = c - d;
  return ad.squaredNorm() * (bd.x() * cd.y() - cd.x() * bd.y()) - bd.squaredNorm() * (ad.x() * cd.y() - cd.x() * ad.y()) +
         cd.squaredNorm() * (ad.x() * bd.y() - bd.x() * ad.y());
}

// Triangulates the strip between two rows of nodes that both span the same x-interval, by merging the
// rows in order of x (a "zipper"). Where both rows advance at the same x (a square), `diag_up` picks the
// diagonal: true cuts lower-left to upper-right.
void zip_rows(const std::vector<Index>& lower, const std::vector<Index>& upper, const std::vector<Vec2>& X,
              int row, GridPattern pattern, std::vector<Index>& tris) {
  std::size_t i = 0, j = 0;
  int square = 0;
  while (i + 1 < lower.size() || j + 1 < upper.size()) {
    bool advance_lower;
    if (i + 1 == lower.size()) {
      advance_lower = false;
    } else if (j + 1 == upper.size()) {
      advance_lower = true;
    } else {
      const double xl = X[lower[i + 1]].x(), xu = X[upper[j + 1]].x();
      const double tol = 1e-12 * (1.0 + std::abs(xl));
      if (std::abs(xl - xu) <= tol) {
        // A quadrilateral. The shifted pattern cuts it by its Delaunay diagonal (only its row ends have
        // quadrilaterals, trapezoids), so that a PFEM remesh of the generated points finds the same cells
        // (seed 000 §5.1 relies on no spurious connectivity changes). right and alternating keep their
        // diagonal (what they are for).
        const Vec2 &a = X[std::size_t(lower[i])], &b = X[std::size_t(lower[i + 1])], &c = X[std::size_t(upper[j + 1])], &d = X[std::size_t(upper[j])];
        const double in_circle = incircle(a, b, c, d);  // > 0: d inside the circle through a, b, c
        const double scale = (c - a).squaredNorm() * (c - a).squaredNorm();
        bool diag_up = pattern != GridPattern::alternating || (square + row) % 2 == 0;
        if (pattern == GridPattern::shifted && std::abs(in_circle) > 1e-12 * scale) diag_up = in_circle < 0.0;
        // The square (lower[i], lower[i+1], upper[j+1], upper[j]) becomes two triangles.
        if (diag_up) {
          tris.insert(tris.end(), {lower[i], lower[i + 1], upper[j + 1]});
          tris.insert(tris.end(), {lower[i], upper[j + 1], upper[j]});
        } else {
          tris.insert(tris.end(), {lower[i], lower[i + 1], upper[j]});
          tris.insert(tris.end(), {lower[i + 1], upper[j + 1], upper[j]});
        }
        ++i, ++j, ++square;
        continue;
      }
      advance_lower = xl < xu;
    }
    if (advance_lower) {
      tris.insert(tris.end(), {lower[i], lower[i + 1], upper[j]});
      ++i;
    } else {
      tris.insert(tris.end(), {lower[i], upper[j + 1], upper[j]});
      ++j;
    }
  }
}

// Node rows of a structured grid on the unit square; shifted rows get half-edge offsets and end points.
MeshData unit_grid(int nx, int ny, GridPattern pattern) {
  LOOM_ASSERT(nx >= 1 && ny >= 1, "grid divisions must be positive");
  MeshData mesh;
  std::vector<std::vector<Index>> rows(static_cast<std::size_t>(ny) + 1);
  for (int r = 0; r <= ny; ++r) {
    const double y = double(r) / ny;
    const bool shifted = pattern == GridPattern::shifted && r % 2 == 1;
    auto add = [&](double x) {
      rows[std::size_t(r)].push_back(Index(mesh.X.size()));
      mesh.X.emplace_back(x, y);
    };
    if (shifted) {
      add(0.0);
      for (int i = 0; i < nx; ++i) add((i + 0.5) / nx);
      add(1.0);
    } else {
      for (int i = 0; i <= nx; ++i) add(double(i) / nx);
    }
  }
  for (int r = 0; r < ny; ++r) zip_rows(rows[std::size_t(r)], rows[std::size_t(r) + 1], mesh.X, r, pattern, mesh.triangles);
  return mesh;
}

// The same nodes as the right pattern, kept as (nx ny) counter-clockwise quadrilaterals.
MeshData unit_quad_grid(int nx, int ny) {
  MeshData mesh = unit_grid(nx, ny, GridPattern::right);
  mesh.triangles.clear();
  const auto node = [&](int i, int r) { return Index(r * (nx + 1) + i); };
  for (int r = 0; r < ny; ++r)
    for (int i = 0; i < nx; ++i) mesh.quads.insert(mesh.quads.end(), {node(i, r), node(i + 1, r), node(i + 1, r + 1), node(i, r + 1)});
  return mesh;
}

MeshData unit_mesh(int nx, int ny, GridPattern pattern, bool quads) {
  return quads ? unit_quad_grid(nx, ny) : unit_grid(nx, ny, pattern);
}

}  // namespace

MeshData generate_rectangle(const RectangleSpec& spec) {
  MeshData mesh = unit_mesh(spec.nx, spec.ny, spec.pattern, spec.quads);
  for (auto& p : mesh.X) p = spec.origin + p.cwiseProduct(spec.size);
  return mesh;
}

MeshData generate_cooks_membrane(int nx, int ny, GridPattern pattern, bool quads) {
  MeshData mesh = unit_mesh(nx, ny, pattern, quads);
  // Bilinear map of the unit square onto the trapezoid: xi along x (clamped edge at xi = 0), eta along y.
  const Vec2 c00(0, 0), c10(48, 44), c11(48, 60), c01(0, 44);
  for (auto& p : mesh.X) {
    const double xi = p.x(), eta = p.y();
    p = (1 - xi) * (1 - eta) * c00 + xi * (1 - eta) * c10 + xi * eta * c11 + (1 - xi) * eta * c01;
  }
  return mesh;
}

void distort_interior_nodes(MeshData& mesh, double fraction, std::uint64_t seed) {
  if (fraction <= 0.0) return;
  const Index n = Index(mesh.X.size());
  const bool quads = !mesh.quads.empty();
  std::vector<char> on_boundary(std::size_t(n), 0);
  for (const auto& e : boundary_edges(quads ? mesh.quads : mesh.triangles, quads ? 4 : 3)) on_boundary[std::size_t(e.a)] = on_boundary[std::size_t(e.b)] = 1;
  std::vector<Index> triangles = mesh.triangles;
  for (std::size_t q = 0; q < mesh.quads.size(); q += 4) {
    const Index* v = mesh.quads.data() + q;
    triangles.insert(triangles.end(), {v[0], v[1], v[2], v[0], v[2], v[3], v[0], v[1], v[3], v[1], v[2], v[3]});
  }
  // Each node moves by at most fraction * h, h = its smallest altitude over the adjacent triangles. The
  // doubled area 2A of a triangle is affine in each corner, so moves d_a change it by at most
  // sum_a |d_a| |e_a| + sum_pairs |d_b x d_c| <= 3 f 2A + 3 f^2 2A (|e_a| h_a = 2A and h_b h_c <= 2A):
  // no triangle can invert while 3 f + 3 f^2 < 1, i.e. f < 0.264 (the schema allows up to 0.25).
  std::vector<double> h(std::size_t(n), std::numeric_limits<double>::max());
  for (std::size_t t = 0; t < triangles.size() / 3; ++t) {
    const Index* v = triangles.data() + 3 * t;
    const Vec2 &x0 = mesh.X[std::size_t(v[0])], &x1 = mesh.X[std::size_t(v[1])], &x2 = mesh.X[std::size_t(v[2])];
    const double two_area = std::abs((x1 - x0).x() * (x2 - x0).y() - (x2 - x0).x() * (x1 - x0).y());
    for (int k = 0; k < 3; ++k) {
      const double opposite = (mesh.X[std::size_t(v[(k + 1) % 3])] - mesh.X[std::size_t(v[(k + 2) % 3])]).norm();
      h[std::size_t(v[k])] = std::min(h[std::size_t(v[k])], two_area / opposite);
    }
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (Index i = 0; i < n; ++i) {
    Vec2 d(unit(rng), unit(rng));  // drawn for every node so the pattern does not depend on the boundary
    if (on_boundary[std::size_t(i)]) continue;
    if (d.norm() > 1.0) d.normalize();
    mesh.X[std::size_t(i)] += fraction * h[std::size_t(i)] * d;
  }
}

void scale_mesh(MeshData& mesh, double factor) {
  for (auto& p : mesh.X) p *= factor;
}

}  // namespace loom
