#include "engine/mesh/tet_generators.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <utility>

namespace loom {
namespace {

// Appends (a, b, c, d), swapped to positive orientation.
void add_tet(TetMeshData& mesh, Index a, Index b, Index c, Index d) {
  const auto& X = mesh.X;
  if (tet_volume(X[std::size_t(a)], X[std::size_t(b)], X[std::size_t(c)], X[std::size_t(d)]) < 0.0) std::swap(c, d);
  mesh.tets.insert(mesh.tets.end(), {a, b, c, d});
}

}  // namespace

TetMeshData generate_box(const BoxSpec& spec) {
  if (spec.nx < 1 || spec.ny < 1 || spec.nz < 1) throw std::invalid_argument("generate_box: divisions must be >= 1");
  TetMeshData mesh;
  const int sx = spec.nx + 1, sy = spec.ny + 1;
  auto node = [&](int i, int j, int k) { return Index(i + sx * (j + sy * k)); };
  mesh.X.reserve(std::size_t(sx) * std::size_t(sy) * std::size_t(spec.nz + 1));
  for (int k = 0; k <= spec.nz; ++k)
    for (int j = 0; j <= spec.ny; ++j)
      for (int i = 0; i <= spec.nx; ++i)
        mesh.X.push_back(spec.origin + Vec3(spec.size.x() * i / spec.nx, spec.size.y() * j / spec.ny, spec.size.z() * k / spec.nz));
  static constexpr int kPaths[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  mesh.tets.reserve(24 * std::size_t(spec.nx) * std::size_t(spec.ny) * std::size_t(spec.nz));
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i)
        for (const auto& path : kPaths) {
          std::array<int, 3> c = {i, j, k};
          Index v[4];
          v[0] = node(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[std::size_t(path[s])];
            v[s + 1] = node(c[0], c[1], c[2]);
          }
          add_tet(mesh, v[0], v[1], v[2], v[3]);
        }
  return mesh;
}

TetMeshData generate_bcc_box(const BoxSpec& spec) {
  if (spec.nx < 1 || spec.ny < 1 || spec.nz < 1) throw std::invalid_argument("generate_bcc_box: divisions must be >= 1");
  TetMeshData mesh = generate_box(spec);
  mesh.tets.clear();
  const int n[3] = {spec.nx, spec.ny, spec.nz};
  const int sx = spec.nx + 1, sy = spec.ny + 1;
  auto corner = [&](const std::array<int, 3>& c) { return Index(c[0] + sx * (c[1] + sy * c[2])); };
  const Index first_centre = Index(mesh.X.size());
  auto centre = [&](const std::array<int, 3>& c) { return first_centre + Index(c[0] + spec.nx * (c[1] + spec.ny * c[2])); };
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i)
        mesh.X.push_back(spec.origin + Vec3(spec.size.x() * (i + 0.5) / spec.nx, spec.size.y() * (j + 0.5) / spec.ny, spec.size.z() * (k + 0.5) / spec.nz));
  // Each cube's face across axis a, on its low (s = 0) or high (s = 1) side: its four corners in cyclic order.
  auto face_corners = [&](const std::array<int, 3>& cube, int a, int s) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    std::array<Index, 4> f;
    static constexpr int kCycle[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int q = 0; q < 4; ++q) {
      std::array<int, 3> p = cube;
      p[std::size_t(a)] += s, p[std::size_t(b)] += kCycle[q][0], p[std::size_t(c)] += kCycle[q][1];
      f[std::size_t(q)] = corner(p);
    }
    return f;
  };
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) {
        const std::array<int, 3> cube = {i, j, k};
        for (int a = 0; a < 3; ++a) {
          // The high face: an octahedron with the next cube's centre, or a pyramid on the box's face.
          const std::array<Index, 4> f = face_corners(cube, a, 1);
          std::array<int, 3> next = cube;
          ++next[std::size_t(a)];
          if (next[std::size_t(a)] < n[a]) {
            for (int q = 0; q < 4; ++q) add_tet(mesh, centre(cube), centre(next), f[std::size_t(q)], f[std::size_t((q + 1) % 4)]);
          } else {
            const int lo = int(std::min_element(f.begin(), f.end()) - f.begin());
            const Index p0 = f[std::size_t(lo)], p1 = f[std::size_t((lo + 1) % 4)], p2 = f[std::size_t((lo + 2) % 4)], p3 = f[std::size_t((lo + 3) % 4)];
            add_tet(mesh, centre(cube), p0, p1, p2), add_tet(mesh, centre(cube), p0, p2, p3);
          }
          // The low face on the box's face: a pyramid (interior low faces are the previous cube's high faces).
          if (cube[std::size_t(a)] == 0) {
            const std::array<Index, 4> g = face_corners(cube, a, 0);
            const int lo = int(std::min_element(g.begin(), g.end()) - g.begin());
            const Index p0 = g[std::size_t(lo)], p1 = g[std::size_t((lo + 1) % 4)], p2 = g[std::size_t((lo + 2) % 4)], p3 = g[std::size_t((lo + 3) % 4)];
            add_tet(mesh, centre(cube), p0, p1, p2), add_tet(mesh, centre(cube), p0, p2, p3);
          }
        }
      }
  return mesh;
}

TetMeshData extrude(const MeshData& mesh, double depth, int layers) {
  if (layers < 1 || !(depth > 0.0)) throw std::invalid_argument("extrude: needs layers >= 1 and depth > 0");
  std::vector<Index> triangles = mesh.triangles;
  for (std::size_t q = 0; q < mesh.quads.size(); q += 4) {
    const Index* v = mesh.quads.data() + q;
    const int lo = int(std::min_element(v, v + 4) - v);  // cut along the diagonal from the lowest corner
    const Index a = v[lo], b = v[(lo + 1) % 4], c = v[(lo + 2) % 4], d = v[(lo + 3) % 4];
    triangles.insert(triangles.end(), {a, b, c, a, c, d});
  }
  TetMeshData out;
  const Index n = Index(mesh.X.size());
  out.X.reserve(mesh.X.size() * std::size_t(layers + 1));
  for (int l = 0; l <= layers; ++l)
    for (const Vec2& x : mesh.X) out.X.push_back(Vec3(x.x(), x.y(), depth * l / layers));
  out.tets.reserve(triangles.size() / 3 * 12 * std::size_t(layers));
  for (int l = 0; l < layers; ++l)
    for (std::size_t t = 0; t < triangles.size(); t += 3) {
      std::array<Index, 3> v = {triangles[t], triangles[t + 1], triangles[t + 2]};
      std::sort(v.begin(), v.end());
      const Index base = n * l;
      const Index b0 = v[0] + base, b1 = v[1] + base, b2 = v[2] + base;
      const Index t0 = b0 + n, t1 = b1 + n, t2 = b2 + n;
      add_tet(out, b0, b1, b2, t0);
      add_tet(out, b1, b2, t0, t1);
      add_tet(out, b2, t0, t1, t2);
    }
  return out;
}

double distort_interior_nodes(TetMeshData& mesh, double fraction, std::uint64_t seed) {
  if (fraction <= 0.0) return 1.0;
  const std::size_t n = mesh.X.size(), nt = mesh.tets.size() / 4;
  std::vector<char> on_boundary(n, 0);
  for (const auto& f : boundary_faces(mesh.tets))
    for (Index v : f.nodes) on_boundary[std::size_t(v)] = 1;
  auto volume = [&](std::size_t t) {
    const Index* v = mesh.tets.data() + 4 * t;
    return tet_volume(mesh.X[std::size_t(v[0])], mesh.X[std::size_t(v[1])], mesh.X[std::size_t(v[2])], mesh.X[std::size_t(v[3])]);
  };
  // h: the node's smallest altitude, 3 V / (area of the opposite face), over its tetrahedra.
  std::vector<double> h(n, std::numeric_limits<double>::infinity()), before(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    before[t] = volume(t);
    const Index* v = mesh.tets.data() + 4 * t;
    for (int a = 0; a < 4; ++a) {
      const int* f = kTetFaces[a];
      const Vec3& p = mesh.X[std::size_t(v[f[0]])];
      const double area = 0.5 * (mesh.X[std::size_t(v[f[1]])] - p).cross(mesh.X[std::size_t(v[f[2]])] - p).norm();
      h[std::size_t(v[a])] = std::min(h[std::size_t(v[a])], 3.0 * before[t] / area);
    }
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 r;  // drawn for every node (x, y, z in turn), so the moves do not depend on the boundary
    for (int k = 0; k < 3; ++k) r[k] = unit(rng);
    if (r.norm() > 1.0) r.normalize();
    if (on_boundary[i]) continue;
    mesh.X[i] += fraction * h[i] * r;
  }
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t < nt; ++t) smallest = std::min(smallest, volume(t) / before[t]);
  return smallest;
}

Tet10MeshData tet10_from_tet4(const TetMeshData& mesh) {
  static constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  const std::size_t nt = mesh.tets.size() / 4;
  // Edges as (lower, higher, slot), sorted, to give each a number in order of first appearance.
  struct Slot {
    Index a, b;
    std::size_t slot;  // 6 t + e
  };
  std::vector<Slot> slots;
  slots.reserve(6 * nt);
  for (std::size_t t = 0; t < nt; ++t)
    for (int e = 0; e < 6; ++e) {
      Index a = mesh.tets[4 * t + std::size_t(kEdges[e][0])], b = mesh.tets[4 * t + std::size_t(kEdges[e][1])];
      if (a > b) std::swap(a, b);
      slots.push_back({a, b, 6 * t + std::size_t(e)});
    }
  std::sort(slots.begin(), slots.end(), [](const Slot& x, const Slot& y) {
    return x.a != y.a ? x.a < y.a : x.b != y.b ? x.b < y.b : x.slot < y.slot;
  });
  std::vector<std::size_t> first_slot(6 * nt);  // each slot -> the first slot of its edge
  for (std::size_t i = 0; i < slots.size();) {
    std::size_t j = i;
    while (j < slots.size() && slots[j].a == slots[i].a && slots[j].b == slots[i].b) first_slot[slots[j++].slot] = slots[i].slot;
    i = j;
  }
  Tet10MeshData out;
  out.X = mesh.X;
  out.n_corners = Index(mesh.X.size());
  out.cells.resize(10 * nt);
  std::vector<Index> mid(6 * nt, kNoIndex);
  for (std::size_t t = 0; t < nt; ++t) {
    for (int a = 0; a < 4; ++a) out.cells[10 * t + std::size_t(a)] = mesh.tets[4 * t + std::size_t(a)];
    for (int e = 0; e < 6; ++e) {
      const std::size_t s = first_slot[6 * t + std::size_t(e)];
      if (mid[s] == kNoIndex) {
        mid[s] = Index(out.X.size());
        const Index a = mesh.tets[4 * t + std::size_t(kEdges[e][0])], b = mesh.tets[4 * t + std::size_t(kEdges[e][1])];
        out.X.push_back(0.5 * (mesh.X[std::size_t(a)] + mesh.X[std::size_t(b)]));
      }
      out.cells[10 * t + 4 + std::size_t(e)] = mid[s];
    }
  }
  return out;
}

}  // namespace loom
