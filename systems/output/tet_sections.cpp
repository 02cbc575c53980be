#include "systems/output/tet_sections.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "engine/mesh/tet_mesh.hpp"

namespace loom {
namespace {

// The corners split by side: up (d >= 0) first, then down, with their distances.
struct Sides {
  std::array<int, 4> up{}, down{};
  int n_up = 0, n_down = 0;
  std::array<double, 4> d{};
};

Sides sides_of(const std::array<Vec3, 4>& x, const Vec3& point, const Vec3& normal) {
  Sides s;
  for (int i = 0; i < 4; ++i) {
    s.d[std::size_t(i)] = (x[std::size_t(i)] - point).dot(normal);
    if (s.d[std::size_t(i)] >= 0.0) s.up[std::size_t(s.n_up++)] = i;
    else s.down[std::size_t(s.n_down++)] = i;
  }
  return s;
}

// Where edge (i, j), with corners on opposite sides, meets the plane.
Vec3 crossing(const std::array<Vec3, 4>& x, const Sides& s, int i, int j) {
  const double t = s.d[std::size_t(i)] / (s.d[std::size_t(i)] - s.d[std::size_t(j)]);
  return x[std::size_t(i)] + t * (x[std::size_t(j)] - x[std::size_t(i)]);
}

}  // namespace

double TetCut::area() const {
  if (n < 3) return 0.0;
  Vec3 twice = (points[1] - points[0]).cross(points[2] - points[0]);
  if (n == 4) twice += (points[2] - points[0]).cross(points[3] - points[0]);
  return 0.5 * twice.norm();
}

TetCut cut_tet(const std::array<Vec3, 4>& x, const Vec3& point, const Vec3& normal) {
  const Sides s = sides_of(x, point, normal);
  TetCut cut;
  if (s.n_up == 0 || s.n_down == 0) return cut;
  if (s.n_up == 1 || s.n_down == 1) {  // a triangle around the lone corner
    const bool lone_up = s.n_up == 1;
    const int lone = lone_up ? s.up[0] : s.down[0];
    const auto& others = lone_up ? s.down : s.up;
    for (int k = 0; k < 3; ++k) cut.points[std::size_t(k)] = crossing(x, s, lone, others[std::size_t(k)]);
    cut.n = 3;
    return cut;
  }
  // Two and two: a quadrilateral whose consecutive points share a corner, (u0 d0), (u0 d1), (u1 d1), (u1 d0).
  const int u0 = s.up[0], u1 = s.up[1], d0 = s.down[0], d1 = s.down[1];
  cut.points = {crossing(x, s, u0, d0), crossing(x, s, u0, d1), crossing(x, s, u1, d1), crossing(x, s, u1, d0)};
  cut.n = 4;
  return cut;
}

double tet_fraction_downstream(const std::array<Vec3, 4>& x, const Vec3& point, const Vec3& normal) {
  const double whole = std::abs(tet_volume(x[0], x[1], x[2], x[3]));
  if (whole == 0.0) return 0.0;
  const Sides s = sides_of(x, point, normal);
  if (s.n_down == 0) return 1.0;
  if (s.n_up == 0) return 0.0;
  const TetCut cut = cut_tet(x, point, normal);
  // The part on the side of a lone corner is a tetrahedron; two and two: the convex solid of the two corners up and the
  // cut, a pyramid from corner u0 over each face that does not hold it (the cut's two triangles, and the triangle of u1
  // with the crossings of its edges).
  auto volume = [](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) { return std::abs(tet_volume(a, b, c, d)); };
  const auto& p = cut.points;
  if (s.n_up == 1) return volume(x[std::size_t(s.up[0])], p[0], p[1], p[2]) / whole;
  if (s.n_down == 1) return 1.0 - volume(x[std::size_t(s.down[0])], p[0], p[1], p[2]) / whole;
  const Vec3& u0 = x[std::size_t(s.up[0])];
  const Vec3& u1 = x[std::size_t(s.up[1])];
  return (volume(u0, p[0], p[1], p[2]) + volume(u0, p[0], p[2], p[3]) + volume(u0, u1, p[2], p[3])) / whole;
}

}  // namespace loom
